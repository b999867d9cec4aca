// lfcam.volume: the light-field microscope's reconstruction (volume_request.hpp), with the keywords,
// defaults, order of settings and messages of `lfcam volume` (tools/lfcam/cmd_volume.cpp), but a
// light field for the frame and a numpy array for the file.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "errors.hpp"
#include "interruptible.hpp"
#include "lfcam/lfm/volume_request.hpp"
#include "progress.hpp"

namespace py = pybind11;

namespace lfcam::python {

namespace {

const char* const volumeDoc = R"doc(
A 3D volume from a light-field microscope frame: Richardson-Lucy deconvolution through the
wave-optics PSF (Broxton et al. 2013), or the single back-projection; `lfcam volume` with a light
field for the frame and an array for the file.

light_field: the frame decoded to N x N views (colour averaged to grey), N within a quarter of
  pitch / pixel_size; its ns x nt views' pixels are the lenslets.
optics: napari-LF's metadata.txt or .lfc calibration, or lfcam's optics JSON (the same keys at the top level); the
  keywords below override it.
objective: "MAGx/NA/MEDIUM" as "60x/1.2/water" (medium: water, oil, glycerol, air or an index).
wavelength: emission, nm. pixel_size: camera pixel, um. pitch: microlens pitch, um.
microlens_focal_length: um. tube_lens: mm (default 200).
microlens_array: "square" (default) or "hexagonal": a hexagonal frame's lenslets each N x N pixels
  over a pitch x sqrt(3)/2 pitch brick, odd rows half a pitch toward +s; an odd last row is left out.
slices: number of z-slices. um_per_slice: their spacing in the specimen (default 1).
z_center: depth of the middle slice from the focal plane, um (default 0).
supersample: voxels across a lenslet (napari-LF's supersample; default 1).
iterations: Richardson-Lucy iterations at most (default 8). solver: "rl" or "backprojection".
background: light in every pixel that no voxel sends, in the frame's units (default 0).
tolerance: stop when the volume changes by less than this fraction (default 0: never).
tv: total-variation regularisation weight in [0, 1) (default 0).
psf: the PSF cache file (.h5): read when it holds these settings, refused when it holds others,
  computed and written when absent. None: computed and kept nowhere.
psf_energy: fraction of each PSF's energy kept (default 0.95).
progress: a callable of the fraction done (0..1), True for a tqdm bar, or None.

Returns a float32 numpy array (z, y, x) of slices x nt * supersample x ns * supersample voxels.
Its voxels are pitch / (M * supersample) um across (M the objective's magnification; a hexagonal
array's are sqrt(3)/2 of that high), and slice i
lies at depth z_center + (i - (slices - 1) / 2) * um_per_slice um (napari-LF's convention).
Wrong settings raise lfcam.UsageError with the command line's message; Ctrl-C stops the
iterations and raises KeyboardInterrupt.)doc";

}  // namespace

void bindVolume(py::module_& m) {
  m.def(
      "volume",
      [](const LightField& lf, std::optional<std::filesystem::path> opticsFile, std::optional<std::string> objective,
         std::optional<double> wavelength, std::optional<double> pixelSize, std::optional<double> pitch,
         std::optional<double> microlensFocalLength, std::optional<std::string> microlensArray,
         std::optional<double> tubeLens, std::optional<int> slices, std::optional<double> umPerSlice,
         std::optional<double> zCenter, std::optional<int> supersample, std::optional<int> iterations,
         const std::string& solver, std::optional<double> background, std::optional<double> tolerance,
         std::optional<double> tv, std::optional<std::filesystem::path> psf, std::optional<double> psfEnergy,
         const py::object& progress) {
        // As cmd_volume.cpp: the file, then the objective, then each keyword over them.
        LfmVolumeSettings settings{.opticsFile = opticsFile ? opticsFile->string() : std::string(),
                                   .objective = objective.value_or(""),
                                   .solver = solver,
                                   .microlensArray = microlensArray.value_or(""),
                                   .wavelengthNm = wavelength,
                                   .tubeLensMm = tubeLens,
                                   .pitchUm = pitch,
                                   .microlensFocalLengthUm = microlensFocalLength,
                                   .pixelSizeUm = pixelSize,
                                   .umPerSlice = umPerSlice,
                                   .zCenterUm = zCenter,
                                   .background = background,
                                   .tolerance = tolerance,
                                   .tvWeight = tv,
                                   .psfEnergy = psfEnergy,
                                   .slices = slices,
                                   .supersample = supersample,
                                   .iterations = iterations};
        LfmVolumeRequest request = valueOrThrow(volumeRequestFrom(settings));
        if (psf) request.psfPath = psf->string();

        const Progress report(progress, "volume");
        auto* volume = new Volume(interruptible([&] {
          return std::move(
              valueOrThrow(reconstructVolume(lf, request, "light field", report.callback())).reconstruction.volume);
        }));
        const py::capsule owner(volume, [](void* v) { delete static_cast<Volume*>(v); });
        return viewOf(volume->voxels().data(), {volume->depth(), volume->height(), volume->width()}, owner);
      },
      py::arg("light_field"), py::kw_only(), py::arg("optics") = py::none(), py::arg("objective") = py::none(),
      py::arg("wavelength") = py::none(), py::arg("pixel_size") = py::none(), py::arg("pitch") = py::none(),
      py::arg("microlens_focal_length") = py::none(), py::arg("microlens_array") = py::none(),
      py::arg("tube_lens") = py::none(), py::arg("slices") = py::none(), py::arg("um_per_slice") = py::none(),
      py::arg("z_center") = py::none(), py::arg("supersample") = py::none(), py::arg("iterations") = py::none(),
      py::arg("solver") = "rl", py::arg("background") = py::none(), py::arg("tolerance") = py::none(),
      py::arg("tv") = py::none(), py::arg("psf") = py::none(), py::arg("psf_energy") = py::none(),
      py::arg("progress") = py::none(), volumeDoc);
}

}  // namespace lfcam::python
