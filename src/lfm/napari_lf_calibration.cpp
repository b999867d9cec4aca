#include "lfcam/lfm/napari_lf_calibration.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>

#include "io/hdf5_support.hpp"
#include "io/io_support.hpp"

namespace lfcam {

namespace {

using hdf5::Handle;

// The optics keys napari-LF writes to /optics, each read as a number.
constexpr const char* kOpticsKeys[] = {"ulens_focal_length", "ulens_focal_distance",    "ulens_pitch",
                                       "pixel_size",         "objective_magnification", "objective_na",
                                       "medium_index",       "tubelens_focal_length",   "ulens_fill_factor",
                                       "center_wavelength"};

Result<std::string> readSettings(const std::filesystem::path& path) {
  Handle access = io::fileAccess();
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose);
  if (!file.valid()) return io::hdf5Error(ErrorCode::Format, path, "not a readable HDF5 file");
  if (H5Lexists(file.get(), "optics", H5P_DEFAULT) <= 0)
    return io::fileError(ErrorCode::Format, path, "not a napari-LF calibration: no /optics group");
  Handle optics(H5Gopen2(file.get(), "optics", H5P_DEFAULT), H5Gclose);
  if (!optics.valid()) return io::hdf5Error(ErrorCode::Format, path, "/optics is not a readable group");
  nlohmann::json calibrate = nlohmann::json::object();
  for (const char* key : kOpticsKeys) {
    LFCAM_ASSIGN_OR_RETURN(const std::optional<double> value, io::readNumberAttribute(path, optics.get(), key));
    if (value) calibrate[key] = *value;
  }
  // napari-LF writes the profile variable-length, which io refuses (Unsupported): then left out.
  const auto profile = io::readStringAttribute(path, optics.get(), "ulens_profile");
  if (!profile && profile.error().code != ErrorCode::Unsupported) return profile.error();
  if (profile && profile.value()) calibrate["ulens_profile"] = *profile.value();
  if (H5Lexists(file.get(), "rayspread", H5P_DEFAULT) > 0) {
    Handle rayspread(H5Gopen2(file.get(), "rayspread", H5P_DEFAULT), H5Gclose);
    if (!rayspread.valid()) return io::hdf5Error(ErrorCode::Format, path, "/rayspread is not a readable group");
    LFCAM_ASSIGN_OR_RETURN(const auto slices, io::readNumberAttribute(path, rayspread.get(), "num_z_slices"));
    LFCAM_ASSIGN_OR_RETURN(const auto spacing, io::readNumberAttribute(path, rayspread.get(), "um_per_z_slice"));
    LFCAM_ASSIGN_OR_RETURN(const auto centre, io::readNumberAttribute(path, rayspread.get(), "z_center"));
    if (slices) {
      if (*slices != std::round(*slices) || std::abs(*slices) > 1e6)
        return io::fileError(ErrorCode::Format, path, "/rayspread num_z_slices is not a whole number");
      calibrate["num_slices"] = int(*slices);
    }
    if (spacing) calibrate["um_per_slice"] = *spacing;
    if (centre) calibrate["z_center"] = *centre;
  }
  return nlohmann::json{{"calibrate", calibrate}}.dump();
}

}  // namespace

Result<std::string> napariLfCalibrationSettings(const std::filesystem::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  io::Hdf5Session session;
  // Its HDF5 calls first in a throwaway process, as every reader of a file from elsewhere.
  LFCAM_TRY(io::refuseWhatCrashesLibhdf5(path, [&] { (void)readSettings(path); }));
  return readSettings(path);
}

}  // namespace lfcam
