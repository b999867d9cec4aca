// A focused plenoptic capture calibrated from itself or its white image, against the simulator's
// calibration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_self_calibration.hpp"

namespace lfcam {
namespace {

// Found types against true ones, lens by lens: the share of lenses whose found type is the one
// most lenses of their true type got (1 when the found types split the lenses as the true ones do),
// and whether that correspondence keeps the order of the types' ranges (nearest-focused first).
struct TypeMatch {
  double agreement = 0;
  bool sameOrder = false;
};

TypeMatch matchTypes(const FocusedCalibration& found, const FocusedCalibration& truth) {
  const std::size_t types = truth.lensTypes.size();
  std::vector<std::vector<int>> counts(types, std::vector<int>(found.lensTypes.size(), 0));
  int count = 0;
  for (int j = 0; j < truth.grid.rows; ++j)
    for (int i = 0; i < truth.grid.columns; ++i) {
      const auto t = truth.grid.centre(i, j);
      for (int fj = 0; fj < found.grid.rows; ++fj)
        for (int fi = 0; fi < found.grid.columns; ++fi) {
          const auto f = found.grid.centre(fi, fj);
          if (std::hypot(f[0] - t[0], f[1] - t[1]) > 1) continue;
          ++counts[std::size_t(truth.lensType(i, j))][std::size_t(found.lensType(fi, fj))];
          ++count;
        }
    }
  TypeMatch match;
  std::vector<std::size_t> image(types);
  int agreeing = 0;
  for (std::size_t t = 0; t < types; ++t) {
    image[t] = std::size_t(std::max_element(counts[t].begin(), counts[t].end()) - counts[t].begin());
    agreeing += counts[t][image[t]];
  }
  match.agreement = count > 0 ? double(agreeing) / count : 0;
  match.sameOrder = true;
  for (std::size_t a = 0; a < types; ++a)
    for (std::size_t b = 0; b < types; ++b)
      if (truth.lensTypes[a].minVirtualDepth < truth.lensTypes[b].minVirtualDepth &&
          !(found.lensTypes[image[a]].minVirtualDepth < found.lensTypes[image[b]].minVirtualDepth))
        match.sameOrder = false;
  return match;
}

void print(const char* what, const FocusedSelfCalibration& s, const FocusedCalibration& truth) {
  const test::CentreErrors errors = test::centreErrors(s.calibration, truth);
  std::printf(
      "%s: diameter %.4f (true %.4f), rotation %.5f rad (true %.5f), centre error worst %.3f px, RMS %.3f "
      "px (per-lens fit RMS %.3f px); confidence upright %.3f, inverted %.3f; type spread %.3f\n",
      what, s.calibration.diameterPx(), truth.diameterPx(), s.calibration.grid.rotationRad, truth.grid.rotationRad,
      errors.worst, errors.rms, s.gridFit.rmsResidualPx, s.confidenceUpright, s.confidenceInverted, s.lensTypeSpread);
  for (const LensType& type : truth.lensTypes)
    std::printf("  true type offset (%g, %g): virtual depths %.2f to %.2f\n", type.offset[0], type.offset[1],
                type.minVirtualDepth, type.maxVirtualDepth);
  for (const LensType& type : s.calibration.lensTypes)
    std::printf("  type offset (%g, %g): virtual depths %.2f to %.2f\n", type.offset[0], type.offset[1],
                type.minVirtualDepth, type.maxVirtualDepth);
}

TEST(FocusedSelfCalibration, FindsTheGridTheWayUpAndTheLensTypesOfAGalileanCapture) {
  const test::FocusedCapture& c = test::galileanCapture();
  auto found = calibrateFocusedCapture(c.raw, nullptr, {}, "galilean");
  ASSERT_TRUE(found) << found.error().message;
  print("from the capture", *found, c.calibration);
  const test::CentreErrors errors = test::centreErrors(found->calibration, c.calibration);
  EXPECT_LT(errors.worst, 0.5);
  EXPECT_LT(errors.rms, 0.25);
  EXPECT_EQ(found->calibration.orientation, MicroImageOrientation::Upright);
  ASSERT_EQ(found->calibration.lensTypes.size(), 3u);
  const TypeMatch match = matchTypes(found->calibration, c.calibration);
  EXPECT_GT(match.agreement, 0.99);
  EXPECT_TRUE(match.sameOrder);
  // Each range ends between the true neighbouring ranges' starts and ends.
  const auto& types = found->calibration.lensTypes;
  for (std::size_t n = 0; n + 1 < types.size(); ++n) {
    EXPECT_GT(types[n].maxVirtualDepth, 2.28);
    EXPECT_LT(types[n].maxVirtualDepth, 7.78);
  }
}

TEST(FocusedSelfCalibration, TheWhiteImageGivesTheGrid) {
  const test::FocusedCapture& c = test::galileanCapture();
  auto found = calibrateFocusedCapture(c.image, &c.white, {}, "galilean");
  ASSERT_TRUE(found) << found.error().message;
  print("from the white image", *found, c.calibration);
  EXPECT_LT(test::centreErrors(found->calibration, c.calibration).worst, 0.1);
  const TypeMatch match = matchTypes(found->calibration, c.calibration);
  EXPECT_GT(match.agreement, 0.99);
  EXPECT_TRUE(match.sameOrder);
}

TEST(FocusedSelfCalibration, AKeplerianOneFocusCaptureIsInvertedWithOneType) {
  const test::FocusedCapture c = test::simulateFocused({.galilean = false, .multiFocus = false}, {4.0, 2.8, 2.2});
  auto found = calibrateFocusedCapture(c.raw, nullptr, {}, "keplerian");
  ASSERT_TRUE(found) << found.error().message;
  print("keplerian", *found, c.calibration);
  const test::CentreErrors errors = test::centreErrors(found->calibration, c.calibration);
  EXPECT_LT(errors.worst, 0.5);
  EXPECT_LT(errors.rms, 0.25);
  EXPECT_EQ(found->calibration.orientation, MicroImageOrientation::Inverted);
  EXPECT_EQ(found->calibration.lensTypes.size(), 1u);
}

TEST(FocusedSelfCalibration, RefusesAWhiteOfAnotherSize) {
  const test::FocusedCapture& c = test::galileanCapture();
  const Image small(10, 10, 1);
  const auto found = calibrateFocusedCapture(c.raw, &small, {}, "galilean.png");
  ASSERT_FALSE(found);
  EXPECT_NE(found.error().message.find("galilean.png"), std::string::npos);
}

}  // namespace
}  // namespace lfcam
