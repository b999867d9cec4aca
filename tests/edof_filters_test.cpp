// The filters of src/edof/filters.cpp against plain references on random inputs: boxFilter
// (double running sums) against the window average pixel by pixel; the guided filter (its own
// float box sums for small radii, boxFilter beyond) against He et al.'s formula with those plain
// averages; depth's row sampler against bilinearSample; the quadratic fit against a least-squares
// fit per pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/bilinear.hpp"
#include "core/parabola.hpp"
#include "core/quadratic_filter.hpp"
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

// The squared Laplacian, rows threaded and its interior without clamps, against the formula with
// every neighbour clamped to the image, bit for bit, down to 1-pixel images.
TEST(SquaredLaplacian, MatchesTheClampedFormula) {
  std::mt19937 generator(12);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (const std::pair<int, int>& size :
       std::vector<std::pair<int, int>>{{1, 1}, {1, 5}, {5, 1}, {2, 2}, {3, 7}, {17, 4}, {300, 211}}) {
    const int width = size.first, height = size.second;  // named, not bound: lambdas capture them
    Image image(width, height, 1);
    for (float& v : image.pixels()) v = uniform(generator);
    std::vector<float> out(image.planeSize());
    squaredLaplacian(image, out.data());
    const auto at = [&](int x, int y) {
      return image.at(std::clamp(x, 0, width - 1), std::clamp(y, 0, height - 1), 0);
    };
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const float lap = at(x - 1, y) + at(x + 1, y) + at(x, y - 1) + at(x, y + 1) - 4 * at(x, y);
        ASSERT_EQ(out[std::size_t(y) * width + x], lap * lap) << width << "x" << height << " at " << x << ", " << y;
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

// Reference: per pixel, the least-squares fit of c0 + c1 x + c2 y + c3 x^2 + c4 y^2 + c5 xy +
// c6 x^2 y + c7 x y^2 + c8 x^2 y^2 (the product of quadratics in x and y) to the window, the
// image's edge pixels repeated beyond it, solved by Gauss-Jordan elimination in double; its value
// at the centre, c0.
double fittedCentre(const std::vector<float>& in, int width, int height, int x, int y, int radius) {
  double normal[9][10] = {};
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const double basis[9] = {1,
                               double(dx),
                               double(dy),
                               double(dx * dx),
                               double(dy * dy),
                               double(dx * dy),
                               double(dx * dx * dy),
                               double(dx * dy * dy),
                               double(dx * dx * dy * dy)};
      const double value =
          in[std::size_t(std::clamp(y + dy, 0, height - 1)) * width + std::clamp(x + dx, 0, width - 1)];
      for (int i = 0; i < 9; ++i) {
        for (int j = 0; j < 9; ++j) normal[i][j] += basis[i] * basis[j];
        normal[i][9] += basis[i] * value;
      }
    }
  for (int i = 0; i < 9; ++i) {
    int pivot = i;
    for (int r = i + 1; r < 9; ++r)
      if (std::abs(normal[r][i]) > std::abs(normal[pivot][i])) pivot = r;
    std::swap(normal[i], normal[pivot]);
    for (int r = 0; r < 9; ++r)
      if (r != i) {
        const double factor = normal[r][i] / normal[i][i];
        for (int c = i; c < 10; ++c) normal[r][c] -= factor * normal[i][c];
      }
  }
  return normal[0][9] / normal[0][0];
}

TEST(QuadraticFitFilter, MatchesALeastSquaresFitPerPixelOnRandomInputs) {
  std::mt19937 generator(12);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (int trial = 0; trial < 12; ++trial) {
    const int width = 1 + int(generator() % 40), height = 1 + int(generator() % 40);
    const int radius = 2 + int(generator() % 3);
    std::vector<float> in(std::size_t(width) * height), out(in.size());
    for (float& v : in) v = uniform(generator);
    quadraticFitFilter(in.data(), out.data(), width, height, radius);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        ASSERT_NEAR(out[std::size_t(y) * width + x], fittedCentre(in, width, height, x, y, radius), 2e-5)
            << "trial " << trial << " at " << x << ", " << y << " radius " << radius;
  }
}

TEST(QuadraticFitFilter, KeepsACurvedSurfaceWhereABoxMeanSags) {
  // A dome, disparity 1 - 0.01 (x^2 + y^2) about the centre: the box mean over 5 x 5 lies 0.04
  // below it; the quadratic fit on it.
  const int size = 32;
  std::vector<float> dome(std::size_t(size) * size), fitted(dome.size()), mean(dome.size());
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      dome[std::size_t(y) * size + x] = 1.0f - 0.01f * float((x - 16) * (x - 16) + (y - 16) * (y - 16));
  quadraticFitFilter(dome.data(), fitted.data(), size, size, 2);
  boxFilter(dome.data(), mean.data(), size, size, 2);
  for (int y = 2; y < size - 2; ++y)
    for (int x = 2; x < size - 2; ++x) {
      const std::size_t p = std::size_t(y) * size + x;
      ASSERT_NEAR(fitted[p], dome[p], 1e-4) << x << ", " << y;
      ASSERT_NEAR(mean[p], dome[p] - 0.04f, 1e-4) << x << ", " << y;
    }
}

TEST(GuidedFilter, MatchesTheFormulaWithPlainMeansOnRandomInputsInPlaceToo) {
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
    std::vector<float> inPlace(in);  // the cost volume's slices are filtered in place
    filter.apply(inPlace.data(), inPlace.data(), scratch);
    ASSERT_EQ(inPlace, out) << "trial " << trial;
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
