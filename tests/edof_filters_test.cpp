// The filters of src/edof/filters.cpp against plain references on random inputs: boxFilter
// (double running sums) against the window average pixel by pixel; the guided filter (its own
// float box sums for small radii, boxFilter beyond) against He et al.'s formula with those plain
// averages; depth's row sampler against bilinearSample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/bilinear.hpp"
#include "core/parabola.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {
namespace {

// Reference: the mean over the window clipped to the image, each pixel on its own, in double.
std::vector<double> plainBox(const std::vector<float>& in, int width, int height, int radius) {
  std::vector<double> out(in.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0;
      int count = 0;
      for (int yy = std::max(0, y - radius); yy <= std::min(height - 1, y + radius); ++yy)
        for (int xx = std::max(0, x - radius); xx <= std::min(width - 1, x + radius); ++xx)
          sum += in[std::size_t(yy) * width + xx], ++count;
      out[std::size_t(y) * width + x] = sum / count;
    }
  return out;
}

TEST(ParabolaVertex, FindsTheMinimumOfAParabolaBetweenSamples) {
  for (const double vertex : {-0.4, -0.1, 0.0, 0.3, 0.5}) {
    const auto cost = [vertex](double x) { return 2.0 * (x - vertex) * (x - vertex) + 1.0; };
    EXPECT_NEAR(parabolaVertex(cost(-1), cost(0), cost(1)), vertex, 1e-12) << vertex;
  }
  EXPECT_EQ(parabolaVertex(1.0, 1.0, 1.0), 0.0) << "flat: no minimum between the samples";
  EXPECT_EQ(parabolaVertex(0.0, 1.0, 0.0), 0.0) << "a maximum is no minimum";
  EXPECT_EQ(parabolaVertex(3.0, 0.0, -2.0), 0.5) << "beyond the next sample: clamped to half a step";
}

// Rows shifted by random amounts, sampled a row at a time, against each sample on its own; shifts
// reach past the borders, where both clamp.
TEST(SampleShiftedRow, MatchesBilinearSampleOnRandomInputs) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> value(-1, 1);
  for (const auto& [ns, nt] : {std::pair{37, 23}, std::pair{2, 2}, std::pair{64, 5}}) {
    std::vector<float> plane(std::size_t(ns) * nt);
    for (float& v : plane) v = value(random);
    const int pad = 12;
    std::uniform_real_distribution<double> shift(-(pad - 2), pad - 2);
    std::vector<float> padded(std::size_t(ns) + 2 * pad), out(ns);
    for (int trial = 0; trial < 50; ++trial) {
      const int y = trial % nt;
      const double shiftX = trial == 0 ? 0.0 : shift(random), shiftY = trial == 0 ? 0.0 : shift(random);
      sampleShiftedRow(plane.data(), ns, nt, y, shiftX, shiftY, pad, padded.data(), out.data());
      for (int x = 0; x < ns; ++x)
        ASSERT_NEAR(out[x], bilinearSample(plane.data(), ns, nt, x + shiftX, y + shiftY), 1e-5)
            << ns << "x" << nt << " y " << y << " shift " << shiftX << ", " << shiftY << " x " << x;
    }
  }
}

TEST(BoxFilter, MatchesThePlainWindowMeanOnRandomInputs) {
  std::mt19937 generator(11);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (int trial = 0; trial < 40; ++trial) {
    // Sizes from 1 to 70, some below the window.
    const int width = 1 + int(generator() % 70), height = 1 + int(generator() % 70);
    const int radius = int(generator() % 11);
    std::vector<float> in(std::size_t(width) * height), out(in.size());
    for (float& v : in) v = uniform(generator);
    boxFilter(in.data(), out.data(), width, height, radius);
    const std::vector<double> reference = plainBox(in, width, height, radius);
    for (std::size_t i = 0; i < in.size(); ++i)
      ASSERT_NEAR(out[i], reference[i], 2e-6) << "trial " << trial << " pixel " << i << " radius " << radius;
  }
}

TEST(GuidedFilter, MatchesTheFormulaWithPlainMeansOnRandomInputs) {
  std::mt19937 generator(12);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int trial = 0; trial < 30; ++trial) {
    // Sizes from 1, some below the window; radii 0 to 10 (beyond 8 the whole-plane path).
    const int width = 1 + int(generator() % 40), height = 1 + int(generator() % 40), radius = int(generator() % 11);
    const double epsilon = 1e-3;
    const std::size_t n = std::size_t(width) * height;
    std::vector<float> guide(n), in(n), out(n), product(n);
    for (std::size_t i = 0; i < n; ++i) guide[i] = uniform(generator), in[i] = uniform(generator);
    const GuidedFilter filter(guide.data(), width, height, radius, epsilon);
    GuidedFilter::Scratch scratch;
    filter.apply(in.data(), out.data(), scratch);
    // He et al. 2010, algorithm 1, with plain means.
    std::vector<float> squares(n);
    for (std::size_t i = 0; i < n; ++i) product[i] = guide[i] * in[i], squares[i] = guide[i] * guide[i];
    const auto meanI = plainBox(guide, width, height, radius), meanP = plainBox(in, width, height, radius),
               meanIp = plainBox(product, width, height, radius), meanII = plainBox(squares, width, height, radius);
    std::vector<float> a(n), b(n);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = float((meanIp[i] - meanI[i] * meanP[i]) / (meanII[i] - meanI[i] * meanI[i] + epsilon));
      b[i] = float(meanP[i] - a[i] * meanI[i]);
    }
    const auto meanA = plainBox(a, width, height, radius), meanB = plainBox(b, width, height, radius);
    for (std::size_t i = 0; i < n; ++i)
      ASSERT_NEAR(out[i], meanA[i] * guide[i] + meanB[i], 1e-4) << "trial " << trial << " pixel " << i;
  }
}

}  // namespace
}  // namespace lfcam::edof
