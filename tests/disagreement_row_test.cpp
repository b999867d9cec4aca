// Focused depth's SIMD row kernel (src/focused/disagreement_row.hpp) against its scalar reference,
// on every instruction set this CPU runs (Highway's dispatch forced to each in turn): random
// luminance, hexagonal and square grids of random diameter, slightly turned, upright and inverted,
// at random virtual depths and photograph frames, including discs that reach past the image, over
// random spans of random runs of rows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <hwy/targets.h>

#include "focused/disagreement_row.hpp"

namespace lfcam::focused_detail {
namespace {

TEST(DisagreementRow, MatchesTheScalarReferenceOnRandomInputs) {
  std::mt19937 random(50);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (int trial = 0; trial < 12; ++trial) {
    const int width = 120 + int(80 * unit(random)), height = 90 + int(60 * unit(random));
    Image grey(width, height, 1);
    for (float& x : grey.pixels()) x = float(unit(random));
    const double diameter = 10 + 14 * unit(random);
    FocusedCalibration calibration =
        focusedGrid({width * (0.4 + 0.2 * unit(random)), height * (0.4 + 0.2 * unit(random))}, diameter,
                    trial % 3 == 2 ? Packing::Square : Packing::Hexagonal, 0.02 * (unit(random) - 0.5), width, height);
    calibration.imageWidth = width;
    calibration.imageHeight = height;
    calibration.borderPx = 2 * unit(random);
    calibration.orientation = trial % 2 ? MicroImageOrientation::Inverted : MicroImageOrientation::Upright;
    const FocusedPhotoFrame frame = focusedPhotoFrame(calibration, 2 + (diameter / 2 - 2) * unit(random));
    const double v = 1.5 + 10 * unit(random);
    const MicroImageViews views(calibration);
    const int firstRow = int(0.3 * frame.height * unit(random)),
              endRow = frame.height - int(0.3 * frame.height * unit(random));
    const LensesByRow lenses(views, frame, v * views.usableRadius(), firstRow, endRow);
    std::vector<float> raw(std::size_t(frame.width)), seen(raw.size()), rawReference(raw.size()),
        seenReference(raw.size());
    DisagreementSums sums;
    for (const std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      for (int py = firstRow; py < endRow; ++py) {
        const int begin = int(0.3 * frame.width * unit(random)),
                  end = frame.width - int(0.3 * frame.width * unit(random));
        disagreementRowReference(grey, views, frame, v, py, begin, end, rawReference.data(), seenReference.data());
        disagreementRow(grey, lenses, frame, v, calibration.orientationSign(), py, begin, end, sums, raw.data(),
                        seen.data());
        for (int px = 0; px < end - begin; ++px) {
          ASSERT_EQ(seen[std::size_t(px)], seenReference[std::size_t(px)])
              << hwy::TargetName(target) << ", trial " << trial << ", pixel " << begin + px << ", " << py;
          ASSERT_NEAR(raw[std::size_t(px)], rawReference[std::size_t(px)], 2e-4)
              << hwy::TargetName(target) << ", trial " << trial << ", pixel " << begin + px << ", " << py;
        }
      }
    }
    hwy::SetSupportedTargetsForTest(0);  // back to the CPU's best
  }
}

}  // namespace
}  // namespace lfcam::focused_detail
