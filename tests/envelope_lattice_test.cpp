// The lattice refined by the envelope's phase, on images whose lattice is known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "lfcam/focused/envelope_lattice.hpp"

namespace lfcam {
namespace {

// Bright round spots on a hexagonal lattice (pitch 20 px, turned 0.01 rad), each times a random
// texture of 1-px grains, as a capture's micro-images are their vignetting times what they show.
Image texturedSpots(const MicroImageLattice& truth, int width, int height, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> grain(0.2f, 1.0f);
  Image image(width, height, 1);
  const double det = truth.e1[0] * truth.e2[1] - truth.e1[1] * truth.e2[0];
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // The nearest lattice point: lattice coordinates rounded, then their neighbours.
      const double dx = x + 0.5 - truth.reference[0], dy = y + 0.5 - truth.reference[1];
      const double m = (dx * truth.e2[1] - dy * truth.e2[0]) / det, n = (truth.e1[0] * dy - truth.e1[1] * dx) / det;
      double nearest = 1e9;
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b) {
          const double mm = std::round(m) + a, nn = std::round(n) + b;
          nearest = std::min(
              nearest, std::hypot(dx - mm * truth.e1[0] - nn * truth.e2[0], dy - mm * truth.e1[1] - nn * truth.e2[1]));
        }
      const double envelope = std::exp(-0.5 * std::pow(nearest / 6.0, 2));
      image.pixels()[std::size_t(y) * width + x] = float(envelope) * grain(random);
    }
  return image;
}

TEST(EnvelopeLattice, FindsAKnownHexagonalLatticeFromAStartOffInPitchAndPosition) {
  const double pitch = 20, turn = 0.01;
  auto rotated = [&](double a, double b) {
    return std::array<double, 2>{std::cos(turn) * a - std::sin(turn) * b, std::sin(turn) * a + std::cos(turn) * b};
  };
  const MicroImageLattice truth{
      .reference = {321.3, 240.8}, .e1 = rotated(pitch, 0), .e2 = rotated(pitch / 2, pitch * std::sqrt(3.0) / 2)};
  const Image image = texturedSpots(truth, 640, 480, 7);
  // 1 % long in pitch, 0.004 rad off, 1.5 px off in position.
  auto off = [&](const std::array<double, 2>& e) {
    const double c = std::cos(-0.004) * 1.01, s = std::sin(-0.004) * 1.01;
    return std::array<double, 2>{c * e[0] - s * e[1], s * e[0] + c * e[1]};
  };
  const MicroImageLattice start{
      .reference = {truth.reference[0] + 1.2, truth.reference[1] - 0.9}, .e1 = off(truth.e1), .e2 = off(truth.e2)};
  const MicroImageLattice found = refineLatticeByEnvelope(image, start, Packing::Hexagonal);
  // The farthest corner's centre, as found and as it is.
  double worst = 0;
  for (const auto& [m, n] : {std::array<int, 2>{-16, 0}, {16, 0}, {-8, -13}, {8, 13}, {-24, 13}, {24, -13}}) {
    const double fx = found.reference[0] + m * found.e1[0] + n * found.e2[0];
    const double fy = found.reference[1] + m * found.e1[1] + n * found.e2[1];
    const double tx = truth.reference[0] + m * truth.e1[0] + n * truth.e2[0];
    const double ty = truth.reference[1] + m * truth.e1[1] + n * truth.e2[1];
    worst = std::max(worst, std::hypot(fx - tx, fy - ty));
  }
  std::printf("worst centre error %.3f px\n", worst);
  EXPECT_LT(worst, 0.25);  // the grains: 0.166 px here, 0.002 px without them
  // The start itself was pixels off there: the test can fail.
  EXPECT_GT(std::hypot(start.reference[0] + 16 * start.e1[0] - truth.reference[0] - 16 * truth.e1[0],
                       start.reference[1] + 16 * start.e1[1] - truth.reference[1] - 16 * truth.e1[1]),
            3.0);
}

}  // namespace
}  // namespace lfcam
