// lfcam.simulate: the simulated plenoptic camera, with the names and defaults of `lfcam simulate`.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "errors.hpp"
#include "interruptible.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "lfcam/simulate/simulate_setup.hpp"
#include "progress.hpp"

namespace py = pybind11;

namespace lfcam::python {

void bindSimulate(py::module_& m) {
  m.def(
      "simulate",
      [](const std::string& scene, const std::filesystem::path& output, std::optional<double> fNumber,
         std::optional<double> imageFNumber, std::optional<double> focusMm, std::optional<int> size,
         std::optional<double> pixelsPerLens, bool hexagonal, int samples, std::optional<std::uint64_t> seed,
         std::optional<double> exposure, bool conventional, std::optional<bool> noise, const std::string& rawFormat,
         std::optional<std::string> container, bool white, bool groundTruth, const py::object& progress) {
        if (samples < 1 || samples > 1024)
          throw LibraryError(ErrorCode::Usage,
                             "simulate: samples " + std::to_string(samples) + " is outside [1, 1024]");
        if (rawFormat != "png" && rawFormat != "tiff")
          throw LibraryError(ErrorCode::Usage, "simulate: raw_format '" + rawFormat + "' is not one of png, tiff");
        if (container && *container != "lfp" && *container != "lfr")
          throw LibraryError(ErrorCode::Usage, "simulate: container '" + *container + "' is not one of lfp, lfr");
        const Scene made = valueOrThrow(simulationScene(scene, {.fNumber = fNumber,
                                                                .imageFNumber = imageFNumber,
                                                                .focusMm = focusMm,
                                                                .size = size,
                                                                .pixelsPerLens = pixelsPerLens,
                                                                .hexagonal = hexagonal,
                                                                .conventional = conventional,
                                                                .seed = seed,
                                                                .exposure = exposure,
                                                                .noise = noise}));
        const CaptureOutputs outputs{.white = white, .groundTruth = groundTruth, .rawExtension = "." + rawFormat};
        const Progress report(progress, "simulate");
        interruptible([&] {
          throwIfError(
              writeSimulation(output, made, made.camera, {.samplesPerPixel = samples}, outputs, report.callback()));
          if (container)
            throwIfError(writeSimulationContainers(
                output, *container == "lfp" ? LytroStyle::FirstGeneration : LytroStyle::Illum));
        });
      },
      py::arg("scene"), py::arg("output"), py::kw_only(), py::arg("f_number") = py::none(),
      py::arg("image_f_number") = py::none(), py::arg("focus_mm") = py::none(), py::arg("size") = py::none(),
      py::arg("pixels_per_lens") = py::none(), py::arg("hexagonal") = false, py::arg("samples") = 16,
      py::arg("seed") = py::none(), py::arg("exposure") = py::none(), py::arg("conventional") = false,
      py::arg("noise") = py::none(), py::arg("raw_format") = "png", py::arg("container") = py::none(),
      py::arg("white") = true, py::arg("ground_truth") = true, py::arg("progress") = py::none(),
      "Captures a scene (a scene file, or built-in: people, chart, pinhole, white) with the simulated plenoptic "
      "camera, traced ray by ray, as `lfcam simulate SCENE -o OUTPUT` does: writes raw.png, white.png, camera.json, "
      "depth.pfm and ideal.lf.h5 into the folder `output`. The keywords override the scene's camera: f_number or "
      "image_f_number, focus_mm, size (sensor pixels across), pixels_per_lens, hexagonal, samples (ray samples per "
      "pixel), seed, exposure, conventional (no microlenses), noise (True/False; default: the camera's), raw_format "
      "('png' or 'tiff'), container ('lfp' or 'lfr': also a Lytro-style container); white=False and "
      "ground_truth=False skip white.png and depth.pfm with ideal.lf.h5; progress: a callable of the fraction done, or "
      "True for a tqdm bar. Read the result back with "
      "lfcam.read(output + '/ideal.lf.h5') or lfcam.decode(output + '/raw.png', white=output + '/white.png').");
}

}  // namespace lfcam::python
