// The light-field microscope's projectors against the dense float64 sum on random volumes, and
// Richardson-Lucy finding simulated beads where they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "lfcam/lfm/projector.hpp"
#include "lfcam/lfm/reconstruct.hpp"
#include "lfm/projector_reference.hpp"
#include "lfm_small_microscope.hpp"

namespace lfcam {
namespace lfm_projector_test {

// test::smallMicroscope with the frame rectified to 7 pixels a lenslet (computePsfSet's frameOptics
// does the same for other counts).
LfmOptics rectifiedMicroscope() { return frameOptics(test::smallMicroscope(), 7); }

double relativeDifference(std::span<const float> fast, const std::vector<double>& reference) {
  double difference = 0, norm = 0;
  for (std::size_t i = 0; i < reference.size(); ++i)
    difference += (fast[i] - reference[i]) * (fast[i] - reference[i]), norm += reference[i] * reference[i];
  return std::sqrt(difference / norm);
}

void reconstructBeads(MicrolensLayout layout) {
  const LfmGrid grid{.pixelsPerLenslet = 7, .voxelsPerLenslet = 3, .depthsUm = {-12, -9, -6, -3, 0, 3, 6, 9, 12}};
  LfmOptics microscope = rectifiedMicroscope();
  microscope.array = layout;
  const auto psf = computeSparsePsf(microscope, grid, 0.99);
  ASSERT_TRUE(psf) << psf.error().message;
  const LfmProjector projector(psf.value(), 12, 12);
  Volume truth = projector.emptyVolume();
  struct Bead {
    int x, y, z;
  };
  const Bead beads[] = {{9, 10, 1}, {25, 12, 7}, {14, 26, 2}, {27, 27, 6}};
  for (const Bead& b : beads) truth.at(b.x, b.y, b.z) = 1;
  const Image frame = simulateLfmFrame(projector, truth, 0.001, 20000, 7);
  LfmReconstructOptions options{.iterations = 30, .background = 0.001};
  const auto result = reconstructVolume(projector, frame, options);
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_EQ(result->iterations, 30);
  EXPECT_LT(result->residuals.back(), result->residuals.front());
  const Volume& v = result->volume;
  for (const Bead& b : beads) {
    // The centroid of the reconstruction within 3 voxels (laterally) and 2 slices of the bead.
    double sum = 0, cx = 0, cy = 0, cz = 0;
    for (int z = std::max(0, b.z - 2); z <= std::min(v.depth() - 1, b.z + 2); ++z)
      for (int y = std::max(0, b.y - 3); y <= std::min(v.height() - 1, b.y + 3); ++y)
        for (int x = std::max(0, b.x - 3); x <= std::min(v.width() - 1, b.x + 3); ++x) {
          const double value = v.at(x, y, z);
          sum += value, cx += value * x, cy += value * y, cz += value * z;
        }
    ASSERT_GT(sum, 0);
    cx /= sum, cy /= sum, cz /= sum;
    EXPECT_LT(std::abs(cx - b.x), 1.0) << b.x << " " << b.y << " " << b.z;
    EXPECT_LT(std::abs(cy - b.y), 1.0) << b.x << " " << b.y << " " << b.z;
    EXPECT_LT(std::abs(cz - b.z), 1.0) << b.x << " " << b.y << " " << b.z;
    std::printf("%s bead (%d, %d, %d): centroid (%.2f, %.2f, %.2f)\n", microlensLayoutName(layout), b.x, b.y, b.z, cx,
                cy, cz);
  }
  std::printf("%s: residual %.4f -> %.4f\n", microlensLayoutName(layout), result->residuals.front(),
              result->residuals.back());
}

}  // namespace lfm_projector_test

using namespace lfm_projector_test;

TEST(LfmProjector, MatchesTheDenseFloat64SumOnRandomVolumes) {
  std::mt19937 random(52);
  std::uniform_real_distribution<double> uniform(0, 1);
  // Lenslet counts off the 8-lenslet tiles; K = 1, an even K and K = N; an odd and an even N; a
  // hexagonal array's two-row period (its row counts even) over more than one tile.
  constexpr auto square = MicrolensLayout::Square, hexagonal = MicrolensLayout::Hexagonal;
  for (const auto& [layout, n, k, lx, ly] :
       {std::tuple{square, 7, 1, 11, 9}, std::tuple{square, 7, 2, 5, 4}, std::tuple{square, 7, 7, 3, 10},
        std::tuple{square, 6, 3, 9, 5}, std::tuple{hexagonal, 7, 1, 9, 18}, std::tuple{hexagonal, 6, 3, 5, 4},
        std::tuple{hexagonal, 7, 2, 3, 2}}) {
    const LfmGrid grid{.pixelsPerLenslet = n, .voxelsPerLenslet = k, .depthsUm = {-4, 0, 3}};
    LfmOptics microscope = rectifiedMicroscope();
    microscope.array = layout;
    const auto set = computePsfSet(frameOptics(microscope, n), grid);
    ASSERT_TRUE(set) << set.error().message;
    const LfmSparsePsf psf = sparsePsf(set.value(), 1);
    const LfmProjector projector(psf, lx, ly);
    Volume volume = projector.emptyVolume();
    ASSERT_EQ(volume.width(), lx * k);
    ASSERT_EQ(volume.depth(), 3);
    std::vector<double> volume64(volume.voxels().size());
    for (std::size_t i = 0; i < volume64.size(); ++i) volume.voxels()[i] = float(volume64[i] = uniform(random));
    const Image frame = projector.forward(volume);
    ASSERT_EQ(frame.width(), lx * n);
    const double forwardError = relativeDifference(frame.pixels(), lfm::forwardDirect(set.value(), volume64, lx, ly));
    EXPECT_LT(forwardError, 1e-6) << k;

    Image image(lx * n, ly * n, 1);
    std::vector<double> image64(image.pixels().size());
    for (std::size_t i = 0; i < image64.size(); ++i) image.pixels()[i] = float(image64[i] = uniform(random));
    const Volume back = projector.backward(image);
    const double backwardError = relativeDifference(back.voxels(), lfm::backwardDirect(set.value(), image64, lx, ly));
    EXPECT_LT(backwardError, 1e-6) << k;

    // The sensitivity is the back projection of ones.
    const std::vector<double> ones(image64.size(), 1.0);
    const double sensitivityError =
        relativeDifference(projector.sensitivity().voxels(), lfm::backwardDirect(set.value(), ones, lx, ly));
    EXPECT_LT(sensitivityError, 1e-6) << k;

    // The back projection is the forward one's transpose: <H v, f> = <v, H^T f>.
    double left = 0, right = 0;
    for (std::size_t i = 0; i < image64.size(); ++i) left += double(frame.pixels()[i]) * image64[i];
    for (std::size_t i = 0; i < volume64.size(); ++i) right += volume64[i] * back.voxels()[i];
    EXPECT_NEAR(left / right, 1, 1e-5) << k;
    std::printf(
        "%s, N %d, K %d, %d x %d lenslets: forward %.2g, backward %.2g from float64; <Hv,f>/<v,H'f> - 1 = %.2g\n",
        microlensLayoutName(layout), n, k, lx, ly, forwardError, backwardError, left / right - 1);
  }
}

TEST(LfmProjector, DroppedEnergyBoundsTheError) {
  // Splats holding 95 % of each PSF's energy: the frame of a uniform volume loses about 5 %.
  const LfmGrid grid{.pixelsPerLenslet = 7, .voxelsPerLenslet = 3, .depthsUm = {-4, 3}};
  const auto set = computePsfSet(rectifiedMicroscope(), grid);
  ASSERT_TRUE(set) << set.error().message;
  const LfmSparsePsf all = sparsePsf(set.value(), 1), most = sparsePsf(set.value(), 0.95);
  const LfmProjector exact(all, 8, 8), fast(most, 8, 8);
  Volume volume = exact.emptyVolume();
  std::fill(volume.voxels().begin(), volume.voxels().end(), 1.0f);
  const Image a = exact.forward(volume), b = fast.forward(volume);
  double sumA = 0, sumB = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) sumA += a.pixels()[i], sumB += b.pixels()[i];
  EXPECT_NEAR(sumB / sumA, 0.95, 0.01);
  EXPECT_LT(most.splats.size(), all.splats.size() / 2);
  std::printf("95 %% of the energy: %zu of %zu splats, frame total %.4f of the exact one\n", most.splats.size(),
              all.splats.size(), sumB / sumA);
}

TEST(LfmReconstruct, FindsSimulatedBeadsWithinAVoxel) {
  // Beads off the native plane (where a light-field microscope resolves least), imaged through
  // the forward model with Poisson noise of 2000 photons at a bead's brightest pixel order; a
  // square and a hexagonal microlens array.
  for (const MicrolensLayout layout : {MicrolensLayout::Square, MicrolensLayout::Hexagonal}) {
    SCOPED_TRACE(microlensLayoutName(layout));
    reconstructBeads(layout);
  }
}

TEST(LfmReconstruct, ToleranceStopsEarlyAndTotalVariationSmooths) {
  const LfmGrid grid{.pixelsPerLenslet = 7, .voxelsPerLenslet = 3, .depthsUm = {-6, -3, 3, 6}};
  const auto psf = computeSparsePsf(test::smallMicroscope(), grid, 0.99);
  ASSERT_TRUE(psf) << psf.error().message;
  const LfmProjector projector(psf.value(), 8, 8);
  Volume truth = projector.emptyVolume();
  truth.at(7, 8, 0) = truth.at(16, 12, 3) = 1;
  const Image frame = simulateLfmFrame(projector, truth, 0.001, 2000, 11);
  const auto plain = reconstructVolume(projector, frame, {.iterations = 20, .background = 0.001});
  const auto stopped = reconstructVolume(projector, frame, {.iterations = 20, .tolerance = 0.05, .background = 0.001});
  const auto smooth = reconstructVolume(projector, frame, {.iterations = 20, .background = 0.001, .tvWeight = 0.02});
  ASSERT_TRUE(plain && stopped && smooth);
  EXPECT_EQ(plain->iterations, 20);
  EXPECT_LT(stopped->iterations, 20);  // the change fell below 5 % of the volume sooner
  // Total variation of each: the regularised one's is lower.
  auto variation = [](const Volume& v) {
    double sum = 0;
    for (int z = 0; z < v.depth(); ++z)
      for (int y = 0; y + 1 < v.height(); ++y)
        for (int x = 0; x + 1 < v.width(); ++x)
          sum += std::hypot(v.at(x + 1, y, z) - v.at(x, y, z), v.at(x, y + 1, z) - v.at(x, y, z));
    return sum;
  };
  for (float value : smooth->volume.voxels()) ASSERT_TRUE(std::isfinite(value) && value >= 0);
  EXPECT_LT(variation(smooth->volume), variation(plain->volume));
  std::printf("tolerance 0.05: %d of 20 iterations; total variation %.4g plain, %.4g with TV 0.02\n",
              stopped->iterations, variation(plain->volume), variation(smooth->volume));
}

TEST(LfmReconstruct, ARadiometryScalesTheModel) {
  // A microscope whose pixels see the model's light times R (vignetting, a dimmer pupil rim, some
  // pixels dead): RL told R explains the frame; RL without it cannot.
  const LfmGrid grid{.pixelsPerLenslet = 7, .voxelsPerLenslet = 1, .depthsUm = {-4, 4}};
  const auto psf = computeSparsePsf(test::smallMicroscope(), grid, 0.99);
  ASSERT_TRUE(psf) << psf.error().message;
  const LfmProjector projector(psf.value(), 8, 8);
  Volume truth = projector.emptyVolume();
  truth.at(2, 3, 0) = truth.at(5, 5, 1) = 1;
  Image radiometry(56, 56, 1);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> gain(0.3f, 1.0f);
  for (float& r : radiometry.pixels()) r = random() % 10 == 0 ? 0.0f : gain(random);
  Image frame = projector.forward(truth);
  for (std::size_t i = 0; i < frame.pixels().size(); ++i) frame.pixels()[i] *= radiometry.pixels()[i];
  const auto told = reconstructVolume(projector, frame, {.iterations = 30}, {}, &radiometry);
  const auto untold = reconstructVolume(projector, frame, {.iterations = 30});
  ASSERT_TRUE(told && untold);
  EXPECT_LT(told->residuals.back(), 0.5 * untold->residuals.back());
  std::printf("residual after 30 iterations: %.4f with R, %.4f without\n", told->residuals.back(),
              untold->residuals.back());
}

TEST(LfmReconstruct, RefusesAFrameOfAnotherSize) {
  const LfmGrid grid{.pixelsPerLenslet = 7, .voxelsPerLenslet = 1, .depthsUm = {0}};
  const auto psf = computeSparsePsf(rectifiedMicroscope(), grid, 0.95);
  ASSERT_TRUE(psf);
  const LfmProjector projector(psf.value(), 4, 4);
  const auto result = reconstructVolume(projector, Image(30, 28, 1));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().message, "the frame is 30 x 28 x 1, not the projector's 28 x 28 x 1");
  EXPECT_FALSE(reconstructVolume(projector, Image(28, 28, 1), {.iterations = 0}));
}

}  // namespace lfcam
