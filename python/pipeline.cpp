// The pipeline's functions, with the command line's names and defaults (lfcam --help): files,
// calibration and decoding, photographs, depth, all-in-focus and scores. Each long call runs
// without the GIL and stops on Ctrl-C (interruptible.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <map>
#include <memory>
#include <string>

#include "arrays.hpp"
#include "errors.hpp"
#include "interruptible.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/calibrate/white_database.hpp"
#include "lfcam/decode/decode_files.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/depth_knobs.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/render/denoise.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "progress.hpp"

namespace py = pybind11;

namespace lfcam::python {

namespace {

using Path = std::filesystem::path;

template <class T>
T choice(const std::map<std::string, T>& names, const std::string& name, const char* what) {
  auto it = names.find(name);
  if (it != names.end()) return it->second;
  std::string known;
  for (const auto& [key, value] : names) known += (known.empty() ? "" : ", ") + key;
  throw LibraryError(ErrorCode::Usage, std::string(what) + ": '" + name + "' is not one of " + known);
}

ColorFilter colorFilterNamed(const std::string& name) {
  if (auto filter = parseColorFilterName(name)) return *filter;
  throw LibraryError(ErrorCode::Usage, "bayer: '" + name + "' is not one of RGGB, BGGR, GRBG, GBRG, mono");
}

// Sets the depth knobs given as keyword arguments (their flag names with '_' for '-').
void setDepthKnobs(DepthOptions& options, const py::kwargs& knobs) {
  for (const auto& [key, value] : knobs) {
    std::string name = py::str(key);
    std::replace(name.begin(), name.end(), '_', '-');
    const DepthKnob* knob = nullptr;
    for (const DepthKnob& k : depthKnobs())
      if (name == k.name) knob = &k;
    if (!knob) throw LibraryError(ErrorCode::Usage, "depth: unknown option '" + std::string(py::str(key)) + "'");
    const double number = value.cast<double>();
    if (!(number >= knob->min && number <= knob->max))
      throw LibraryError(ErrorCode::Usage, "depth: " + std::string(py::str(key)) + " = " + std::to_string(number) +
                                               " is outside [" + std::to_string(knob->min) + ", " +
                                               std::to_string(knob->max) + "]");
    std::visit(
        [&](auto member) {
          using Member = std::remove_reference_t<decltype(options.*member)>;
          if constexpr (std::is_same_v<Member, int>)
            options.*member = int(number);
          else
            options.*member = number;
        },
        knob->member);
  }
}

}  // namespace

void bindPipeline(py::module_& m) {
  py::class_<LensletGrid>(m, "LensletGrid", "The microlens lattice found by calibrate (grid.json).")
      .def_readonly("pitch_x", &LensletGrid::pitchX)
      .def_readonly("pitch_y", &LensletGrid::pitchY)
      .def_readonly("rotation_rad", &LensletGrid::rotationRad)
      .def_readonly("origin", &LensletGrid::origin)
      .def_readonly("columns", &LensletGrid::columns)
      .def_readonly("rows", &LensletGrid::rows)
      .def_property_readonly("hexagonal", [](const LensletGrid& g) { return g.packing == Packing::Hexagonal; })
      .def(
          "write", [](const LensletGrid& g, const Path& path) { throwIfError(writeGrid(path, g)); }, py::arg("path"));

  m.def(
      "read",
      [](const Path& path, std::optional<int> lensletViews, const py::object& progress) {
        const Progress report(progress, "read");
        return interruptible(
            [&] { return valueOrThrow(readLightField(path, {.lensletViews = lensletViews}, report.callback())); });
      },
      py::arg("path"), py::kw_only(), py::arg("lenslet_views") = py::none(), py::arg("progress") = py::none(),
      "Reads a light field: .lf.h5, an HCI or RR_CC folder of views, or a lenslet image. progress: a callable of "
      "the fraction done, or True for a tqdm bar.");
  m.def(
      "write",
      [](const Path& path, const LightField& lf, const py::object& progress) {
        const Progress report(progress, "write");
        interruptible([&] { throwIfError(writeLightField(path, lf, {}, report.callback())); });
      },
      py::arg("path"), py::arg("light_field"), py::kw_only(), py::arg("progress") = py::none(),
      "Writes a light field; the format follows the name (.lf.h5, a folder). progress: as read's.");
  m.def(
      "read_image", [](const Path& path) { return interruptible([&] { return valueOrThrow(readImage(path)); }); },
      py::arg("path"), "Reads an image in linear light (PNG, JPEG, TIFF, EXR, PFM).");
  m.def(
      "write_image",
      [](const Path& path, const Image& image, std::optional<std::string> bitDepth) {
        ImageWriteOptions options;
        if (bitDepth)
          options.sampleType =
              choice<SampleType>({{"8", SampleType::UInt8}, {"16", SampleType::UInt16}, {"float", SampleType::Float32}},
                                 *bitDepth, "bit_depth");
        interruptible([&] { throwIfError(writeImage(path, image, options)); });
      },
      py::arg("path"), py::arg("image"), py::kw_only(), py::arg("bit_depth") = py::none(),
      "Writes an image; bit_depth '8', '16' or 'float' (default: the format's own).");

  m.def(
      "calibrate",
      [](const Path& white, std::optional<Path> metadata, bool pinhole, bool scene, std::optional<std::string> bayer,
         std::optional<double> blackLevel) {
        CalibrationOptions options;
        if (bayer) options.colorFilter = colorFilterNamed(*bayer);
        if (pinhole && scene) throw LibraryError(ErrorCode::Usage, "calibrate: pinhole and scene exclude each other");
        if (pinhole) options.target = CalibrationTarget::Pinhole;
        if (scene) options.target = CalibrationTarget::Scene;
        return interruptible([&] {
          if (metadata) options.hint = valueOrThrow(readLensletHint(*metadata));
          const RawImage raw = valueOrThrow(readRaw(white, {.blackLevel = blackLevel, .useCameraJson = false}));
          return valueOrThrow(calibrateGrid(raw, options, white.string()));
        });
      },
      py::arg("white"), py::kw_only(), py::arg("metadata") = py::none(), py::arg("pinhole") = false,
      py::arg("scene") = false, py::arg("bayer") = py::none(), py::arg("black_level") = py::none(),
      "Finds the microlens grid in a white image (or a pinhole image, or a scene raw).");
  m.def(
      "decode",
      [](const std::string& raw, std::string white, std::string dark, std::string grid,
         std::optional<std::string> bayer, std::optional<double> blackLevel, int views, const std::string& demosaic,
         const std::string& sampling, const py::object& progress, std::string whites, bool anyCamera) {
        RawFiles files{.raw = raw,
                       .white = white,
                       .dark = dark,
                       .grid = grid,
                       .whites = whites,
                       .anyCamera = anyCamera,
                       .blackLevel = blackLevel};
        if (bayer) files.bayer = colorFilterNamed(*bayer);
        files.decode.views = views;
        files.decode.demosaic = choice<DemosaicMethod>({{"mhc", DemosaicMethod::MalvarHeCutler},
                                                        {"ha", DemosaicMethod::HamiltonAdams},
                                                        {"lenslet", DemosaicMethod::LensletAware},
                                                        {"lightfield", DemosaicMethod::LightFieldAware}},
                                                       demosaic, "demosaic");
        files.decode.sampling = choice<Sampling>(
            {{"subpixel", Sampling::SubPixel}, {"integral", Sampling::IntegralPitch}}, sampling, "sampling");
        const Progress report(progress, "decode");
        return interruptible([&] { return valueOrThrow(decodeRawFiles(std::move(files), report.callback())); });
      },
      py::arg("raw"), py::kw_only(), py::arg("white") = "", py::arg("dark") = "", py::arg("grid") = "",
      py::arg("bayer") = py::none(), py::arg("black_level") = py::none(), py::arg("views") = 0,
      py::arg("demosaic") = "mhc", py::arg("sampling") = "subpixel", py::arg("progress") = py::none(),
      py::arg("whites") = "", py::arg("any_camera") = false,
      "Decodes a raw lenslet image into a light field; the grid is calibrated from the white image when no grid "
      "file is given. whites: a white-image database (lfcam whites index) choosing the white and grid of the raw's "
      "camera nearest its zoom and focus (any camera's with any_camera); the light field's source names it. "
      "progress: as read's.");
  m.def(
      "choose_white",
      [](const Path& raw, const Path& whites, bool anyCamera) {
        const WhiteChoice choice = interruptible([&] {
          const RawImage image = valueOrThrow(readRaw(raw));
          return valueOrThrow(chooseWhite(whites, image, anyCamera, raw.string()));
        });
        py::dict result;
        result["name"] = choice.white.name;
        result["white"] = choice.white.white.string();
        result["grid"] = choice.white.grid.string();
        result["reason"] = choice.reason;
        return result;
      },
      py::arg("raw"), py::arg("whites"), py::kw_only(), py::arg("any_camera") = false,
      "The white a white-image database chooses for a raw, as lfcam info --whites says: a dict of name, white, "
      "grid and reason.");

  py::class_<DepthMap>(m, "DepthMap", "A disparity map of the centre view and its confidence.")
      .def_readonly("disparity", &DepthMap::disparity)  // a view: kept alive by its DepthMap
      .def_readonly("confidence", &DepthMap::confidence)
      .def_readonly("disparity_min", &DepthMap::disparityMin)
      .def_readonly("disparity_max", &DepthMap::disparityMax)
      .def_readonly("labels", &DepthMap::labels);
  m.def(
      "depth",
      [](const LightField& lf, std::optional<Path> options, const py::kwargs& knobs) {
        DepthOptions settings;
        if (options) throwIfError(readDepthOptions(*options, settings));
        setDepthKnobs(settings, knobs);
        return interruptible([&] { return valueOrThrow(estimateDepth(lf, settings)); });
      },
      py::arg("light_field"), py::kw_only(), py::arg("options") = py::none(),
      "Disparity (pixels per view step) of the centre view and its confidence. Every option of `lfcam depth` is "
      "a keyword with '_' for '-' (e.g. defocus_weight=0.5); options= names a JSON options file.");
  py::class_<AllInFocus>(m, "AllInFocus", "An all-in-focus photograph and the slope chosen per pixel.")
      .def_readonly("photo", &AllInFocus::photo)  // a view: kept alive by its AllInFocus
      .def_readonly("slope", &AllInFocus::slope)
      .def_readonly("slopes", &AllInFocus::slopes);
  m.def(
      "edof",
      [](const LightField& lf, std::optional<py::array> depth, std::optional<double> min, std::optional<double> max,
         double step) {
        std::optional<Image> disparity;
        if (depth) disparity = imageFromArray(*depth, "depth");
        AllInFocusOptions options{.disparity = disparity ? &*disparity : nullptr,
                                  .disparityMin = min,
                                  .disparityMax = max,
                                  .sliceStep = step};
        return interruptible([&] { return valueOrThrow(allInFocus(lf, options)); });
      },
      py::arg("light_field"), py::kw_only(), py::arg("depth") = py::none(), py::arg("min") = py::none(),
      py::arg("max") = py::none(), py::arg("step") = 0.0,
      "Extended depth of field: an all-in-focus photomontage of a focal stack (Figure 15), following a disparity "
      "map when given (e.g. depth(...).disparity.array).");
  m.def(
      "denoise",
      [](const LightField& lf, std::optional<std::pair<double, double>> depthRange, std::optional<double> bandwidth) {
        DenoiseOptions options = defaultDenoiseOptions(lf);
        if (depthRange) options.slopeMin = depthRange->first, options.slopeMax = depthRange->second;
        if (bandwidth) options.bandwidth = *bandwidth;
        return interruptible([&] { return valueOrThrow(denoise(lf, options)); });
      },
      py::arg("light_field"), py::kw_only(), py::arg("depth_range") = py::none(), py::arg("bandwidth") = py::none(),
      "`lfcam denoise`: the light field through a 4D frequency-domain passband that keeps the surfaces of slopes "
      "depth_range = (A, B) (pixels per view step; A == B: one depth) and removes most sensor noise. Default range: "
      "the light field's stated disparity range, else (-2, 2); bandwidth in cycles per view step (default 0.11).");
  m.def(
      "score",
      [](const py::array& estimate, const py::array& truth, std::optional<py::array> mask, int border,
         const std::vector<double>& badpix) {
        const Image e = imageFromArray(estimate, "estimate"), t = imageFromArray(truth, "truth");
        const Image planes = mask ? imageFromArray(*mask, "mask") : Image();
        const HciScores s = interruptible([&] { return valueOrThrow(scoreHci(e, t, planes, border)); });
        py::dict d;
        d[badPixKey(0.01).c_str()] = s.badPix001, d[badPixKey(0.03).c_str()] = s.badPix003,
        d[badPixKey(0.07).c_str()] = s.badPix007;
        for (double threshold : badpix)
          d[badPixKey(threshold).c_str()] =
              interruptible([&] { return valueOrThrow(scoreDisparity(e, t, threshold, border)); }).badPix;
        d["mse_x100"] = s.mse100, d["bumpiness"] = s.bumpiness, d["pixels"] = s.pixels;
        return d;
      },
      py::arg("estimate"), py::arg("truth"), py::kw_only(), py::arg("mask") = py::none(), py::arg("border") = 15,
      py::arg("badpix") = std::vector<double>{},
      "The HCI benchmark's scores of a disparity map against its ground truth, as `lfcam score --json` prints "
      "them; badpix: more thresholds, as its --badpix.");
}

}  // namespace lfcam::python
