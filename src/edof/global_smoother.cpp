// Confidence-weighted fast global smoother (Min et al. 2014), edof_internal.hpp.
// The smoother S: weighted least squares  sum_p (u_p - f_p)^2 + lambda sum_pq w_pq (u_p - u_q)^2
// over the 4-neighbour grid, approximated by alternating 1D solves along rows and columns (each
// a tridiagonal system, exact in O(n)), with lambda decreasing over the iterations so that the
// separable passes do not leave streaks. With confidences c, the result S(c d) / S(c) (their
// sparse-data interpolation): low-confidence pixels take the values of their confident
// neighbours on the same side of an edge of the guide.
#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

// Solves (I + lambda L_w) u = b in place along one line of `count` samples spaced by
// `stride`: L_w the weighted path Laplacian with w[i] linking samples i and i + 1, a = 1.
// Thomas algorithm; the unit diagonal keeps the system diagonally dominant.
void solveLine(float* b, const float* w, int count, std::size_t stride, float lambda, float* scratch) {
  float previous = 0;  // lambda w[i - 1]
  float denominator = 1;
  for (int i = 0; i < count; ++i) {
    const float next = i + 1 < count ? lambda * w[std::size_t(i) * stride] : 0.0f;
    const float diagonal = 1.0f + previous + next;
    // Forward elimination: c'_i = -next / (diagonal + previous c'_{i-1}), with c'_{-1} = 0.
    denominator = diagonal - (i > 0 ? previous * scratch[i - 1] : 0.0f);
    scratch[i] = next / denominator;
    float& bi = b[std::size_t(i) * stride];
    bi = (bi + (i > 0 ? previous * b[std::size_t(i - 1) * stride] : 0.0f)) / denominator;
    previous = next;
  }
  for (int i = count - 2; i >= 0; --i) b[std::size_t(i) * stride] += scratch[i] * b[std::size_t(i + 1) * stride];
}

}  // namespace

void globalSmooth(const float* guide, int guideChannels, int width, int height, const float* confidence, float* values,
                  float lambda, float sigma, int iterations) {
  const std::size_t n = std::size_t(width) * height;
  if (n == 0 || iterations <= 0 || !(lambda > 0)) return;
  // Edge weights exp(-|I_p - I_q| / sigma) (L2 over channels), to the right and below.
  std::vector<float> right(n, 0.0f), down(n, 0.0f);
  parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t p = y * width + x;
        float dx = 0, dy = 0;
        for (int c = 0; c < guideChannels; ++c) {
          const float* plane = guide + std::size_t(c) * n;
          if (x + 1 < width) dx += (plane[p + 1] - plane[p]) * (plane[p + 1] - plane[p]);
          if (y + 1 < std::size_t(height)) dy += (plane[p + width] - plane[p]) * (plane[p + width] - plane[p]);
        }
        if (x + 1 < width) right[p] = std::exp(-std::sqrt(dx) / sigma);
        if (y + 1 < std::size_t(height)) down[p] = std::exp(-std::sqrt(dy) / sigma);
      }
  });
  // The normalised form: u = S(c d) / S(c), S the smoother with unit data weight, so that a
  // region without confidence is filled rather than pulled to zero.
  std::vector<float> weighted(n), mass(confidence, confidence + n);
  for (std::size_t p = 0; p < n; ++p) weighted[p] = confidence[p] * values[p];
  for (int t = 0; t < iterations; ++t) {
    // lambda_t = 1.5 lambda 4^(T - t - 1) / (4^T - 1) (Min et al., equation 9).
    const float lambdaT = float(1.5 * lambda * std::pow(4.0, iterations - t - 1) / (std::pow(4.0, iterations) - 1.0));
    for (std::vector<float>* target : {&weighted, &mass}) {
      float* data = target->data();
      parallelFor(0, std::size_t(height), 8, [&](std::size_t begin, std::size_t end) {
        std::vector<float> scratch(width);
        for (std::size_t y = begin; y < end; ++y)
          solveLine(data + y * width, right.data() + y * width, width, 1, lambdaT, scratch.data());
      });
      parallelFor(0, std::size_t(width), 8, [&](std::size_t begin, std::size_t end) {
        std::vector<float> scratch(height);
        for (std::size_t x = begin; x < end; ++x)
          solveLine(data + x, down.data() + x, height, std::size_t(width), lambdaT, scratch.data());
      });
    }
  }
  for (std::size_t p = 0; p < n; ++p)
    if (mass[p] > 1e-12f) values[p] = weighted[p] / mass[p];
}

}  // namespace lfcam::edof
