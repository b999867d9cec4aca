// The whole file chain keeps the scene upright: `lfcam simulate --container lfr` stores its raw as
// a camera does (the scene upright in its lenslet layout), and `lfcam decode` of the Lytro
// container (grid calibrated from its white image) gives views that lie as the ideal light
// field's, not turned by 180 degrees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli_support.hpp"
#include "lenslet_means.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "test_support.hpp"

namespace lfcam::test {
namespace {

// The channel mean of the centre view.
Image centreView(const LightField& lf) {
  const Image view = lf.subApertureImage(lf.nu() / 2, lf.nv() / 2);
  Image grey(view.width(), view.height(), 1);
  for (int y = 0; y < view.height(); ++y)
    for (int x = 0; x < view.width(); ++x) {
      double sum = 0;
      for (int c = 0; c < view.channels(); ++c) sum += view.at(x, y, c);
      grey.at(x, y, 0) = float(sum / view.channels());
    }
  return grey;
}

// The best correlation of `a` with `b` (turned by 180 degrees or not) over whole-sample shifts of
// up to 3 each way: the calibrated grid may start a microlens or two in from the simulator's.
double bestCorrelation(const Image& a, const Image& b, bool turned) {
  double best = -1;
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      Correlation correlation;
      for (int y = 1; y + 1 < a.height(); ++y)
        for (int x = 1; x + 1 < a.width(); ++x) {
          int bx = x + dx, by = y + dy;
          if (turned) bx = b.width() - 1 - bx, by = b.height() - 1 - by;
          if (bx >= 1 && by >= 1 && bx + 1 < b.width() && by + 1 < b.height())
            correlation.add(a.at(x, y, 0), b.at(bx, by, 0));
        }
      if (correlation.count() >= 100) best = std::max(best, correlation.value());
    }
  return best;
}

TEST(DecodeOrientation, LytroContainerOfASimulatorCaptureDecodesUpright) {
  TempDir dir;
  const std::string sim = (dir / "sim").string();
  // A card in the plane of focus, its smooth noise several microlenses wide: what 17 x 17 samples hold.
  writeBytes(dir / "card.json", R"({"planes": [{"centre_mm": [0, 0, 457.2], "size_mm": [40, 40],
                                    "texture": {"type": "noise", "period_mm": 1.2, "seed": 3}}]})");
  auto simulate = runLfcam({"simulate", (dir / "card.json").string(), "--size", "240", "--pixels-per-lens", "13.37",
                            "--samples", "4", "--noise", "off", "--container", "lfr", "-o", sim},
                           dir.path());
  ASSERT_EQ(simulate.exitStatus, 0) << simulate.err;
  const std::string out = (dir / "out.lf.h5").string();
  auto decode = runLfcam({"decode", sim + "/raw.lfr", "--white", sim + "/white.lfr", "-o", out}, dir.path());
  ASSERT_EQ(decode.exitStatus, 0) << decode.err;
  auto decoded = readLightField(out);
  auto ideal = readLightField(sim + "/ideal.lf.h5");
  ASSERT_TRUE(decoded.ok() && ideal.ok());
  const Image a = centreView(*decoded), b = centreView(*ideal);
  const double asTheyLie = bestCorrelation(a, b, false), turned = bestCorrelation(a, b, true);
  // The frame itself: its lenslet means lie as the ideal centre view does.
  auto raw = readRaw(sim + "/raw.lfr");
  auto white = readRaw(sim + "/white.lfr");
  ASSERT_TRUE(raw.ok() && white.ok());
  auto grid = calibrateGrid(*white, CalibrationOptions{}, "white.lfr");
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  const Image means = lensletMeans(*raw, *white, *grid).means;
  const double rawAsTheyLie = bestCorrelation(means, b, false), rawTurned = bestCorrelation(means, b, true);
  std::printf(
      "[ decode  ] raw.lfr of a simulator capture against the ideal centre view, correlation as they lie / "
      "turned by 180 degrees: decoded centre view %.3f / %.3f, the frame's lenslet means %.3f / %.3f\n",
      asTheyLie, turned, rawAsTheyLie, rawTurned);
  EXPECT_GT(asTheyLie, 0.9);
  EXPECT_GT(asTheyLie, turned + 0.2);
  EXPECT_GT(rawAsTheyLie, 0.9);
  EXPECT_GT(rawAsTheyLie, rawTurned + 0.2);
}

}  // namespace
}  // namespace lfcam::test
