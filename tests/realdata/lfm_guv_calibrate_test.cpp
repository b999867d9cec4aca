// Calibration of the light-field microscope's radiometry image (../shared/data/lfm-guv): a square
// grid of about 15.4 px, compared with the napari-LF calibration shipped beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/io/image_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// geometry/reverseCoefficients of reference_outputs_napariLF/Calibration_GUVExperim1-10.lfc
// (HDF5; dumped once with the HDF5 C API): lenslet (s, t) -> pixel (x, y), terms 1, s, t, s^2,
// s t, t^2, s^3, s^2 t, s t^2, t^3, on a 28 x 27 lenslet grid. Integer (s, t) fall on the corners
// of the lenslets' squares (measured: lfcam's centres lie half a pitch from them), so the centre of
// lenslet (s, t) is the polynomial at (s + 1/2, t + 1/2); its pixel coordinates then agree with
// lfcam's (pixel edges at integers) to a few hundredths of a pixel.
constexpr double kReverse[2][10] = {
    {16.954258, 15.402829, 0.034109, -0.001017, -0.000121, -0.000157, 0.000017, 0.000013, -0.000002, 0.000004},
    {2.791466, -0.028330, 15.413337, 0.000039, -0.000435, -0.000045, 0.000003, 0.000000, 0.000010, 0.000003}};

std::array<double, 2> napariCentre(double s, double t) {
  s += 0.5;
  t += 0.5;
  const double terms[10] = {1, s, t, s * s, s * t, t * t, s * s * s, s * s * t, s * t * t, t * t * t};
  std::array<double, 2> p{0, 0};
  for (int k = 0; k < 10; ++k) {
    p[0] += kReverse[0][k] * terms[k];
    p[1] += kReverse[1][k] * terms[k];
  }
  return p;
}

TEST(LfmGuv, CalibratesTheRadiometryImage) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  auto white = readImage(folder / "Radiometry_GUVExperim1.tif");
  auto dark = readImage(folder / "DarkFrame_GUVExperim1.tif");
  ASSERT_TRUE(white.ok() && dark.ok());
  ASSERT_EQ(white->width(), 436);
  for (std::size_t k = 0; k < white->pixels().size(); ++k) white->pixels()[k] -= dark->pixels()[k];
  auto calibration = calibrateGridDetailed(*white, {}, "Radiometry_GUVExperim1.tif");
  ASSERT_TRUE(calibration.ok()) << calibration.error().message;
  const LensletGrid& grid = calibration->grid;
  // Against napari-LF: each of our microlens centres against its nearest napari-LF centre.
  double sum = 0, sumX = 0, sumY = 0;
  int count = 0;
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const auto c = grid.centre(i, j);
      double best = INFINITY;
      std::array<double, 2> offset{};
      for (int t = -1; t <= 28; ++t)
        for (int s = -1; s <= 29; ++s) {
          const auto n = napariCentre(s, t);
          const double d = std::hypot(c[0] - n[0], c[1] - n[1]);
          if (d < best) {
            best = d;
            offset = {c[0] - n[0], c[1] - n[1]};
          }
        }
      sum += best * best;
      sumX += offset[0];
      sumY += offset[1];
      ++count;
    }
  const double rms = std::sqrt(sum / count);
  std::printf(
      "lfm-guv: %s %d x %d, pitch %.4f x %.4f px, rotation %.4f deg, origin (%.3f, %.3f); fit %d found, %d "
      "used, residual RMS %.4f px, max %.4f px\n",
      packingName(grid.packing), grid.columns, grid.rows, grid.pitchX, grid.pitchY, grid.rotationRad * 180 / M_PI,
      grid.origin[0], grid.origin[1], grid.fit.lensletsFound, grid.fit.lensletsUsed, grid.fit.rmsResidualPx,
      grid.fit.maxResidualPx);
  std::printf(
      "lfm-guv vs napari-LF: pitch %.4f x %.4f px there; centres differ by %.4f px RMS, mean offset (%.4f, "
      "%.4f) px\n",
      kReverse[0][1], kReverse[1][2], rms, sumX / count, sumY / count);
  EXPECT_EQ(grid.packing, Packing::Square);
  EXPECT_NEAR(grid.pitchX, 15.4, 0.05);
  EXPECT_NEAR(grid.pitchY, 15.4, 0.05);
  EXPECT_NEAR(grid.columns, 28, 1);
  EXPECT_NEAR(grid.rows, 28, 1);
  EXPECT_LT(grid.fit.rmsResidualPx, 0.2);
  EXPECT_LT(rms, 0.3);
}

}  // namespace
}  // namespace lfcam
