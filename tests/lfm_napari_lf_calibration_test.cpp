// napari-LF's .lfc calibration as microscope settings: its /optics and /rayspread attributes read
// into the request as its metadata.txt's keys are, and one-line refusals of other files.
#include <gtest/gtest.h>
#include <hdf5.h>  // to write calibrations by hand

#include <string>
#include <utility>
#include <vector>

#include "lfcam/lfm/napari_lf_calibration.hpp"
#include "lfcam/lfm/volume_request.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace lfm_napari_lf_calibration_test {

void writeDouble(hid_t object, const char* name, double value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(attribute);
  H5Sclose(space);
}

void writeText(hid_t object, const char* name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.size());
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, type, value.data());
  H5Aclose(attribute);
  H5Sclose(space);
  H5Tclose(type);
}

// A calibration as napari-LF writes one: /optics (the profile, when given, as a fixed-length
// string) and, when slices is set, /rayspread.
void writeCalibration(const std::filesystem::path& path, const std::vector<std::pair<const char*, double>>& optics,
                      const std::string& profile, int slices) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t group = H5Gcreate2(file, "optics", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (const auto& [name, value] : optics) writeDouble(group, name, value);
  if (!profile.empty()) writeText(group, "ulens_profile", profile);
  H5Gclose(group);
  if (slices > 0) {
    const hid_t rayspread = H5Gcreate2(file, "rayspread", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    writeDouble(rayspread, "num_z_slices", slices);
    writeDouble(rayspread, "um_per_z_slice", 2.5);
    writeDouble(rayspread, "z_center", -1);
    H5Gclose(rayspread);
  }
  H5Fclose(file);
}

const std::vector<std::pair<const char*, double>> kSmallMicroscope = {
    {"objective_magnification", 20}, {"objective_na", 0.5},          {"medium_index", 1.33},
    {"center_wavelength", 500},      {"tubelens_focal_length", 180}, {"ulens_pitch", 40},
    {"ulens_focal_length", 800},     {"ulens_focal_distance", 800},  {"pixel_size", 5},
    {"ulens_fill_factor", 0.9}};

}  // namespace lfm_napari_lf_calibration_test

using namespace lfm_napari_lf_calibration_test;

TEST(NapariLfCalibration, ReadsItsOpticsAndSlicesIntoTheRequest) {
  test::TempDir dir;
  writeCalibration(dir / "microscope.lfc", kSmallMicroscope, "rect", 7);
  const auto request = volumeRequestFrom({.opticsFile = (dir / "microscope.lfc").string()});
  ASSERT_TRUE(request) << request.error().message;
  const LfmOptics& optics = request->optics;
  EXPECT_EQ(optics.magnification, 20);
  EXPECT_EQ(optics.numericalAperture, 0.5);
  EXPECT_EQ(optics.immersionIndex, 1.33);
  EXPECT_EQ(optics.wavelengthNm, 500);
  EXPECT_EQ(optics.tubeFocalLengthMm, 180);
  EXPECT_EQ(optics.microlensPitchUm, 40);
  EXPECT_EQ(optics.microlensFocalLengthUm, 800);
  EXPECT_EQ(optics.pixelSizeUm, 5);
  EXPECT_EQ(optics.microlensFillFactor, 0.9);
  EXPECT_EQ(request->slices, 7);
  EXPECT_EQ(request->umPerSlice, 2.5);
  EXPECT_EQ(request->zCenterUm, -1);
  // The command line's values over the file's, as over a metadata.txt's.
  const auto changed = volumeRequestFrom({.opticsFile = (dir / "microscope.lfc").string(), .slices = 3});
  ASSERT_TRUE(changed) << changed.error().message;
  EXPECT_EQ(changed->slices, 3);
}

TEST(NapariLfCalibration, RefusesWhatItDoesNotModelInOneLine) {
  test::TempDir dir;
  auto refusal = [&](const std::filesystem::path& path) {
    const auto request = volumeRequestFrom({.opticsFile = path.string(), .slices = 3});
    return request ? std::string() : request.error().message;
  };
  writeCalibration(dir / "circles.lfc", kSmallMicroscope, "circ", 0);
  EXPECT_EQ(refusal(dir / "circles.lfc"), (dir / "circles.lfc").string() +
                                              ": calibrate.ulens_profile: only \"rect\" (apertures filling their "
                                              "cells) is modelled");
  auto tooWide = kSmallMicroscope;
  tooWide[1].second = 1.4;
  writeCalibration(dir / "wide.lfc", tooWide, "", 0);
  EXPECT_EQ(refusal(dir / "wide.lfc"),
            (dir / "wide.lfc").string() + ": NA 1.4 above the immersion index 1.33: no light reaches the objective");
  const hid_t other = H5Fcreate((dir / "other.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(other);
  const auto notCalibration = napariLfCalibrationSettings(dir / "other.h5");
  ASSERT_FALSE(notCalibration);
  EXPECT_EQ(notCalibration.error().code, ErrorCode::Format);
  EXPECT_NE(notCalibration.error().message.find("not a napari-LF calibration: no /optics group"), std::string::npos)
      << notCalibration.error().message;
  EXPECT_EQ(notCalibration.error().message.find('\n'), std::string::npos);
}

}  // namespace lfcam
