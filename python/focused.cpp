// Focused plenoptic captures (plenoptic 2.0, Raytrix) from Python, as the commands take them
// (tools/lfcam/focused_input.hpp): read with their calibration beside them, named, or found in the
// capture itself; their virtual depth, photographs at a virtual depth or viewpoint, and total focus.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "errors.hpp"
#include "interruptible.hpp"
#include "lfcam/focused/focused_capture.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"

namespace py = pybind11;

namespace lfcam::python {

namespace {

double framePixelsPerLens(const FocusedCapture& capture, std::optional<double> pixelsPerLens) {
  return pixelsPerLens ? *pixelsPerLens : defaultPixelsPerLens(capture.calibration);
}

py::list lensTypes(const FocusedCalibration& calibration) {
  py::list types;
  for (const LensType& type : calibration.lensTypes) {
    py::dict entry;
    entry["offset"] = py::make_tuple(type.offset[0], type.offset[1]);
    entry["virtual_depth_range"] = py::make_tuple(type.minVirtualDepth, type.maxVirtualDepth);
    types.append(entry);
  }
  return types;
}

}  // namespace

void bindFocused(py::module_& m) {
  py::class_<FocusedCapture>(m, "FocusedCapture",
                             "A focused plenoptic capture: its micro-images in linear light and their calibration.")
      .def_readonly("image", &FocusedCapture::image)  // a view: kept alive by its FocusedCapture
      .def_property_readonly(
          "packing", [](const FocusedCapture& c) { return std::string(packingName(c.calibration.grid.packing)); })
      .def_property_readonly("micro_image_diameter", [](const FocusedCapture& c) { return c.calibration.diameterPx(); })
      .def_property_readonly(
          "micro_images",
          [](const FocusedCapture& c) { return py::make_tuple(c.calibration.grid.columns, c.calibration.grid.rows); })
      .def_property_readonly("micro_image_orientation",
                             [](const FocusedCapture& c) {
                               return c.calibration.orientation == MicroImageOrientation::Upright ? "upright"
                                                                                                  : "inverted";
                             })
      .def_property_readonly("lens_types", [](const FocusedCapture& c) { return lensTypes(c.calibration); })
      .def_property_readonly(
          "calibration_path",
          [](const FocusedCapture& c) -> std::optional<std::string> {
            if (c.selfCalibration) return std::nullopt;
            return c.calibrationPath.string();
          },
          "the calibration file read, or None when the capture was calibrated from itself or its white")
      .def(
          "write_calibration",
          [](const FocusedCapture& c, const std::filesystem::path& path) {
            throwIfError(writeFocusedCalibration(path, c.calibration));
          },
          py::arg("path"), "Writes the calibration as Raytrix's RayCalibData (.xml) or its JSON twin (.json).");
  m.def(
      "read_focused",
      [](const std::filesystem::path& path, std::filesystem::path calibration, std::filesystem::path white,
         bool selfCalibrate) {
        const FocusedCaptureOptions options{
            .calibration = std::move(calibration), .white = std::move(white), .calibrateIfNone = selfCalibrate};
        return interruptible([&] { return valueOrThrow(readFocusedCapture(path, options)); });
      },
      py::arg("path"), py::kw_only(), py::arg("calibration") = "", py::arg("white") = "",
      py::arg("self_calibrate") = false,
      "Reads a focused plenoptic capture with its calibration: the one named, else PATH's name with .xml beside "
      "it; with neither and self_calibrate, the grid, orientation and lens types found from the white image when "
      "given, else from the capture itself (lfcam calibrate --focused). white: divides the capture by it.");
  py::class_<FocusedDepth>(m, "FocusedDepth", "A focused capture's virtual depth on a photograph's frame.")
      .def_readonly("virtual_depth", &FocusedDepth::virtualDepth)
      .def_readonly("confidence", &FocusedDepth::confidence);
  m.def(
      "focused_depth",
      [](const FocusedCapture& capture, std::optional<double> pixelsPerLens) {
        FocusedDepthRequest request;
        request.pixelsPerLens = framePixelsPerLens(capture, pixelsPerLens);
        return interruptible(
            [&] { return valueOrThrow(estimateFocusedDepth(capture.image, capture.calibration, request)); });
      },
      py::arg("capture"), py::kw_only(), py::arg("pixels_per_lens") = py::none(),
      "`lfcam depth` of a focused capture: the virtual depth of every pixel of the photograph's frame "
      "(pixels_per_lens per micro-image; default a quarter of its diameter) and its confidence.");
  m.def(
      "focused_distance",
      [](const FocusedCapture& capture, const py::array& virtualDepth) {
        const Image map = imageFromArray(virtualDepth, "virtual_depth");
        return valueOrThrow(focusedDistanceMap(capture.calibration, map, "focused_distance"));
      },
      py::arg("capture"), py::arg("virtual_depth"),
      "`lfcam depth --metric` of a focused capture: a virtual depth map as distances from the main lens, mm, "
      "through the optics its calibration holds (lfcam_optics; a simulated capture's has them).");
  m.def(
      "focused_photo",
      [](const FocusedCapture& capture, std::optional<double> pixelsPerLens, double virtualDepth, double aperture,
         std::pair<double, double> viewpoint, bool patches) {
        FocusedRenderRequest request;
        request.pixelsPerLens = framePixelsPerLens(capture, pixelsPerLens);
        request.virtualDepth = virtualDepth;
        request.aperture = aperture;
        request.viewpoint = {viewpoint.first, viewpoint.second};
        request.nearestLensOnly = patches;
        return interruptible([&] { return valueOrThrow(renderFocused(capture.image, capture.calibration, request)); });
      },
      py::arg("capture"), py::kw_only(), py::arg("pixels_per_lens") = py::none(), py::arg("virtual_depth"),
      py::arg("aperture") = 1.0, py::arg("viewpoint") = std::pair<double, double>{0, 0}, py::arg("patches") = false,
      "`lfcam refocus` of a focused capture: the photograph focused at virtual_depth through a disc of each "
      "micro-image (aperture: its radius, share of the usable radius; viewpoint: its centre, shares, x right, y "
      "down); patches: Lumsdaine and Georgiev's basic rendering (one patch per micro-image).");
  m.def(
      "focused_total_focus",
      [](const FocusedCapture& capture, std::optional<double> pixelsPerLens, std::optional<py::array> depth) {
        std::optional<Image> map;
        if (depth) map = imageFromArray(*depth, "depth");
        return interruptible([&] {
          return valueOrThrow(renderTotalFocus(capture.image, capture.calibration,
                                               framePixelsPerLens(capture, pixelsPerLens), map ? &*map : nullptr));
        });
      },
      py::arg("capture"), py::kw_only(), py::arg("pixels_per_lens") = py::none(), py::arg("depth") = py::none(),
      "`lfcam edof` of a focused capture: every pixel at its own virtual depth, from depth (an array on the "
      "frame, e.g. focused_depth(...).virtual_depth.array) or the map estimated.");
}

}  // namespace lfcam::python
