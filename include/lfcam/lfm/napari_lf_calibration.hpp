// napari-LF's calibration file (.lfc, written by its calibrate step): HDF5 holding the microscope's
// optics as attributes of /optics (the "calibrate" keys of its metadata.txt: ulens_pitch,
// objective_na, ...) and the slices its PSF was made for as attributes of /rayspread
// (num_z_slices, um_per_z_slice, z_center). Its lenslet geometry, radiometry and pickled PSF are
// not read: lfcam rectifies frames and computes PSFs itself.
#pragma once

#include <filesystem>
#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam {

// The file's settings as napari-LF's metadata.txt holds them, {"calibrate": {...}}, for
// parseLfmSettings (volume_request.hpp) to read and check. ulens_profile is read when stored as a
// fixed-length string; napari-LF stores it variable-length, which lfcam does not read (libhdf5
// 1.10 overflows its buffer on a damaged one), and then it is left out. Format error, naming the
// file, when it is not such a file.
Result<std::string> napariLfCalibrationSettings(const std::filesystem::path& path);

}  // namespace lfcam
