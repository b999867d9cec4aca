// lfcam.Image and lfcam.LightField: numpy views of their samples (arrays.hpp), and PNG pictures of
// them for Jupyter.
#include "arrays.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <string>

#include "core/memory_budget.hpp"
#include "errors.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "viewer/image_encode.hpp"

namespace py = pybind11;

namespace lfcam::python {

py::array viewOf(float* data, std::vector<py::ssize_t> shape, py::handle owner) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(float);
  for (std::size_t k = shape.size(); k-- > 0;) {
    strides[k] = stride;
    stride *= shape[k];
  }
  return py::array(py::dtype::of<float>(), std::move(shape), std::move(strides), data, owner);
}

py::array_t<float, py::array::c_style> floatArray(const py::array& array, std::initializer_list<int> ranks,
                                                  const char* what) {
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw LibraryError(ErrorCode::Usage, std::string(what) + ": expected a numeric array, got dtype " +
                                             std::string(py::str(array.dtype())));
  if (std::find(ranks.begin(), ranks.end(), int(array.ndim())) == ranks.end()) {
    std::string expected;
    for (int rank : ranks) expected += (expected.empty() ? "" : " or ") + std::to_string(rank);
    throw LibraryError(ErrorCode::Usage, std::string(what) + ": expected an array of " + expected +
                                             " dimensions, got " + std::to_string(array.ndim()));
  }
  for (py::ssize_t axis = 0; axis < array.ndim(); ++axis)
    if (array.shape(axis) < 1 || array.shape(axis) > INT_MAX)
      throw LibraryError(ErrorCode::Usage, std::string(what) + ": shape " + std::string(py::str(array.attr("shape"))) +
                                               " has an empty or absurd dimension");
  return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
}

Image imageFromArray(const py::array& array, const char* what) {
  const auto values = floatArray(array, {2, 3}, what);
  const bool planar = values.ndim() == 3;
  const int channels = planar ? int(values.shape(0)) : 1;
  Image image(int(values.shape(planar ? 2 : 1)), int(values.shape(planar ? 1 : 0)), channels);
  std::memcpy(image.pixels().data(), values.data(), image.pixels().size_bytes());
  return image;
}

namespace {

py::array imageView(Image& image, py::handle owner) {
  return viewOf(image.pixels().data(), {image.channels(), image.height(), image.width()}, owner);
}

py::array samplesView(LightField& lf, py::handle owner) {
  return viewOf(lf.samples().data(), {lf.nv(), lf.nu(), lf.channels(), lf.nt(), lf.ns()}, owner);
}

// What IPython shows for an image (_repr_png_): 8-bit sRGB, as lfcam writes a PNG file.
py::bytes png(const Image& image) { return valueOrThrow(encodeImage(image, {.format = EncodedFormat::Png})); }

py::object opticsDict(const std::optional<Optics>& optics) {
  if (!optics) return py::none();
  py::dict d;
  d["lens_step_mm"] = optics->lensStepMm;
  d["spatial_step_mm"] = optics->spatialStepMm;
  d["lens_to_microlens_mm"] = optics->lensToMicrolensMm;
  d["focal_length_mm"] = optics->focalLengthMm ? py::cast(*optics->focalLengthMm) : py::none();
  return d;
}

}  // namespace

void bindArrays(py::module_& m) {
  py::class_<Image>(m, "Image", py::buffer_protocol(), R"doc(
A float32 photograph with planar channels: `array` (and numpy.asarray(image)) is a view of shape
(channels, height, width), x to the right and y down, values in linear light. Writing through the
view changes the image. For matplotlib: numpy.moveaxis(image.array, 0, -1).)doc")
      .def(py::init([](const py::array& array) { return imageFromArray(array, "Image"); }), py::arg("array"),
           "A copy of a (height, width) or (channels, height, width) numeric array.")
      .def_property_readonly("width", &Image::width)
      .def_property_readonly("height", &Image::height)
      .def_property_readonly("channels", &Image::channels)
      .def_property_readonly(
          "array", [](py::object self) { return imageView(self.cast<Image&>(), self); },
          "The samples, (channels, height, width) float32, without a copy.")
      .def_buffer([](Image& image) {
        return py::buffer_info(image.pixels().data(), sizeof(float), py::format_descriptor<float>::format(), 3,
                               {image.channels(), image.height(), image.width()},
                               {sizeof(float) * image.planeSize(), sizeof(float) * image.width(), sizeof(float)});
      })
      .def("_repr_png_", &png, "The image as PNG bytes (8-bit sRGB), which Jupyter shows.")
      .def("__repr__", [](const Image& image) {
        return "<lfcam.Image " + std::to_string(image.width()) + "x" + std::to_string(image.height()) + ", " +
               std::to_string(image.channels()) + " channel(s)>";
      });

  py::class_<LightField>(m, "LightField", py::buffer_protocol(), R"doc(
The 4D light field L(u, v, s, t) with colour channels (lfcam's light_field.hpp): `samples` (and
numpy.asarray(light_field)) is a float32 view, without a copy, of shape (nv, nu, channels, nt, ns):
view row v and column u on the aperture (v down, u right as seen from behind the camera), then
the channel, then the sub-aperture image's row t and column s. `weights`, when present, has shape
(nv, nu, nt, ns). Slopes (disparities) are in pixels of (s, t) per view step, the HCI convention.)doc")
      .def(py::init([](const py::array& samples, std::optional<py::array> weights) {
             const auto values = floatArray(samples, {5}, "samples");
             LightField lf(LightFieldShape{int(values.shape(1)), int(values.shape(0)), int(values.shape(4)),
                                           int(values.shape(3)), int(values.shape(2))});
             std::memcpy(lf.samples().data(), values.data(), lf.samples().size_bytes());
             if (weights) {
               const auto w = floatArray(*weights, {4}, "weights");
               if (w.shape(0) != lf.nv() || w.shape(1) != lf.nu() || w.shape(2) != lf.nt() || w.shape(3) != lf.ns())
                 throw LibraryError(ErrorCode::Usage, "weights: expected shape (nv, nu, nt, ns) of the samples");
               lf.enableWeight();
               std::memcpy(lf.weights().data(), w.data(), lf.weights().size_bytes());
             }
             // Refused as the file readers refuse them, in their words, as a wrong argument.
             if (const Status finite = checkFinite(lf, "LightField"); !finite)
               throw LibraryError(ErrorCode::Usage, finite.error().message);
             return lf;
           }),
           py::arg("samples"), py::arg("weights") = py::none(),
           "A copy of samples (nv, nu, channels, nt, ns) and optional weights (nv, nu, nt, ns), all finite as in "
           "files. To fill a large light field without the copy, make LightField.zeros(...) and write into its "
           "samples.")
      .def_static(
          "zeros",
          [](int nu, int nv, int ns, int nt, int channels) {
            if (nu < 1 || nv < 1 || ns < 1 || nt < 1 || channels < 1)
              throw LibraryError(ErrorCode::Usage, "LightField.zeros: every size must be at least 1");
            using U = std::uint64_t;  // the readers' budget (memory_budget.hpp), before allocating
            throwIfError(checkMemory("LightField.zeros",
                                     checkedProduct({U(nu), U(nv), U(ns), U(nt), U(channels), sizeof(float)}),
                                     "its samples"));
            return LightField(LightFieldShape{nu, nv, ns, nt, channels});
          },
          py::arg("nu"), py::arg("nv"), py::arg("ns"), py::arg("nt"), py::arg("channels") = 3)
      .def_property_readonly("nu", &LightField::nu)
      .def_property_readonly("nv", &LightField::nv)
      .def_property_readonly("ns", &LightField::ns)
      .def_property_readonly("nt", &LightField::nt)
      .def_property_readonly("channels", &LightField::channels)
      .def_property_readonly(
          "samples", [](py::object self) { return samplesView(self.cast<LightField&>(), self); },
          "(nv, nu, channels, nt, ns) float32, without a copy.")
      .def_property_readonly(
          "weights",
          [](py::object self) -> py::object {
            LightField& lf = self.cast<LightField&>();
            if (!lf.hasWeight()) return py::none();
            return viewOf(lf.weights().data(), {lf.nv(), lf.nu(), lf.nt(), lf.ns()}, self);
          },
          "(nv, nu, nt, ns) float32 without a copy, or None.")
      .def(
          "view",
          [](const LightField& lf, int u, int v) {
            if (u < 0 || u >= lf.nu() || v < 0 || v >= lf.nv())
              throw LibraryError(ErrorCode::Usage, "view: (u, v) = (" + std::to_string(u) + ", " + std::to_string(v) +
                                                       ") is outside " + std::to_string(lf.nu()) + "x" +
                                                       std::to_string(lf.nv()) + " views");
            return lf.subApertureImage(u, v);
          },
          py::arg("u"), py::arg("v"), "A copy of sub-aperture view (u, v), indices from 0.")
      .def_property_readonly("source", [](const LightField& lf) { return lf.metadata.source; })
      .def_property_readonly(
          "optics", [](const LightField& lf) { return opticsDict(lf.metadata.optics); },
          "The optics (mm) when known, else None: what alpha and metric depth need.")
      .def_property_readonly("disparity_range",
                             [](const LightField& lf) -> py::object {
                               if (!lf.metadata.disparityMin || !lf.metadata.disparityMax) return py::none();
                               return py::make_tuple(*lf.metadata.disparityMin, *lf.metadata.disparityMax);
                             })
      .def_buffer([](LightField& lf) {
        const auto s = py::ssize_t(sizeof(float));
        return py::buffer_info(lf.samples().data(), sizeof(float), py::format_descriptor<float>::format(), 5,
                               {lf.nv(), lf.nu(), lf.channels(), lf.nt(), lf.ns()},
                               {s * lf.nu() * lf.channels() * lf.nt() * lf.ns(), s * lf.channels() * lf.nt() * lf.ns(),
                                s * lf.nt() * lf.ns(), s * lf.ns(), s});
      })
      .def(
          "_repr_png_",
          [](const LightField& lf) { return png(lf.subApertureImage((lf.nu() - 1) / 2, (lf.nv() - 1) / 2)); },
          "The centre view as PNG bytes (8-bit sRGB), which Jupyter shows.")
      .def("__repr__", [](const LightField& lf) {
        return "<lfcam.LightField " + std::to_string(lf.nu()) + "x" + std::to_string(lf.nv()) + " views of " +
               std::to_string(lf.ns()) + "x" + std::to_string(lf.nt()) + ", " + std::to_string(lf.channels()) +
               " channel(s)>";
      });
}

}  // namespace lfcam::python
