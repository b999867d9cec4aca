// The confidence-weighted fast global smoother used to fill unsure depth (src/edof/global_smoother.cpp):
// its line solve against a dense reference on random inputs, and the fill it is there for.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "edof/edof_internal.hpp"

namespace lfcam::edof {
namespace {

// Reference: (I + mu L_w) x = rhs by dense Gaussian elimination (no pivoting needed: the matrix
// is symmetric and diagonally dominant).
std::vector<double> denseSolve(const std::vector<double>& w, double mu, std::vector<double> rhs) {
  const int n = int(rhs.size());
  std::vector<double> a(std::size_t(n) * n, 0.0);
  for (int i = 0; i < n; ++i) a[std::size_t(i) * n + i] = 1.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double link = mu * w[i];
    a[std::size_t(i) * n + i] += link, a[std::size_t(i + 1) * n + i + 1] += link;
    a[std::size_t(i) * n + i + 1] -= link, a[std::size_t(i + 1) * n + i] -= link;
  }
  for (int k = 0; k < n; ++k)
    for (int i = k + 1; i < n; ++i) {
      const double f = a[std::size_t(i) * n + k] / a[std::size_t(k) * n + k];
      for (int j = k; j < n; ++j) a[std::size_t(i) * n + j] -= f * a[std::size_t(k) * n + j];
      rhs[i] -= f * rhs[k];
    }
  for (int i = n - 1; i >= 0; --i) {
    for (int j = i + 1; j < n; ++j) rhs[i] -= a[std::size_t(i) * n + j] * rhs[j];
    rhs[i] /= a[std::size_t(i) * n + i];
  }
  return rhs;
}

TEST(GlobalSmoother, OneRowMatchesADenseSolveOnRandomInputs) {
  std::mt19937 generator(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int trial = 0; trial < 20; ++trial) {
    const int width = 3 + int(generator() % 60);
    const float lambda = 0.1f + 20.0f * uniform(generator), sigma = 0.05f + 0.5f * uniform(generator);
    std::vector<float> guide(width), confidence(width), values(width);
    for (int x = 0; x < width; ++x)
      guide[x] = uniform(generator), confidence[x] = uniform(generator), values[x] = 4 * uniform(generator) - 2;
    // One iteration on a single row: the row pass with lambda_0 = lambda / 2, a column pass that
    // links nothing; the result is S(c d) / S(c).
    std::vector<float> fast = values;
    globalSmooth(guide.data(), 1, width, 1, confidence.data(), fast.data(), lambda, sigma, 1);
    std::vector<double> w(width - 1), weighted(width), mass(width);
    for (int x = 0; x + 1 < width; ++x) w[x] = std::exp(-std::abs(double(guide[x + 1]) - guide[x]) / sigma);
    for (int x = 0; x < width; ++x) weighted[x] = double(confidence[x]) * values[x], mass[x] = confidence[x];
    const std::vector<double> top = denseSolve(w, 0.5 * lambda, weighted), bottom = denseSolve(w, 0.5 * lambda, mass);
    for (int x = 0; x < width; ++x) ASSERT_NEAR(fast[x], top[x] / bottom[x], 2e-4) << "trial " << trial << " x " << x;
  }
}

TEST(GlobalSmoother, FillsHolesFromTheirOwnSideOfAnEdge) {
  // Left half dark at value 1, right half bright at value 3; a hole of zero confidence on each
  // side next to the edge, holding wrong values.
  const int width = 64, height = 32;
  std::vector<float> guide(std::size_t(width) * height), confidence(guide.size(), 1.0f), values(guide.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = std::size_t(y) * width + x;
      const bool right = x >= width / 2;
      guide[p] = right ? 0.8f : 0.2f;
      values[p] = right ? 3.0f : 1.0f;
      if (y >= 10 && y < 22 && std::abs(x - width / 2 + 0.5) < 8) confidence[p] = 0.0f, values[p] = 10.0f;
    }
  globalSmooth(guide.data(), 1, width, height, confidence.data(), values.data(), 50.0f, 0.02f, 3);
  for (int y = 10; y < 22; ++y)
    for (int x = width / 2 - 8; x < width / 2 + 8; ++x)
      ASSERT_NEAR(values[std::size_t(y) * width + x], x >= width / 2 ? 3.0f : 1.0f, 0.02f) << x << ", " << y;
}

}  // namespace
}  // namespace lfcam::edof
