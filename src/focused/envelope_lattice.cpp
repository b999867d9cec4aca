#include "lfcam/focused/envelope_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "core/parallel.hpp"

namespace lfcam {

namespace {

using Vec2 = std::array<double, 2>;

// The reciprocal basis: k_a . e_b = 1 when a = b, else 0.
std::array<Vec2, 2> reciprocal(const Vec2& e1, const Vec2& e2) {
  const double det = e1[0] * e2[1] - e1[1] * e2[0];
  return {{{e2[1] / det, -e2[0] / det}, {-e1[1] / det, e1[0] / det}}};
}

// Overlapping windows along one axis: `count` windows of `length` pixels, `stride` apart, each a
// Hann window, whose leakage from the image's mean and slow changes into the lattice's frequencies
// (a few windows' lengths' worth of cycles away) is negligible, unlike a box's.
struct Windows {
  int length = 0, stride = 0, count = 0;
  Windows(int size, int tile) {
    length = std::min(size, 2 * tile);
    stride = tile;
    count = std::max(1, (size - length) / stride + 1);
  }
  double centre(int n) const { return n * stride + 0.5 * length; }
  double weight(int offset) const {
    const double s = std::sin(std::numbers::pi * (offset + 0.5) / length);
    return s * s;
  }
};

// Per window (row-major, ys.count x xs.count): the sum of the image's channels times the window
// times exp(-2 pi i k . (x - reference)), x a pixel's centre.
std::vector<std::complex<double>> windowSums(const Image& image, const Vec2& k, const Vec2& reference,
                                             const Windows& xs, const Windows& ys) {
  const int w = image.width(), channels = image.channels();
  std::vector<std::complex<double>> columnPhase(static_cast<std::size_t>(w));
  for (int x = 0; x < w; ++x)
    columnPhase[std::size_t(x)] = std::polar(1.0, -2 * std::numbers::pi * k[0] * (x + 0.5 - reference[0]));
  std::vector<std::complex<double>> sums(std::size_t(xs.count) * ys.count, 0.0);
  parallelFor(0, std::size_t(ys.count), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> row(static_cast<std::size_t>(w));
    for (std::size_t wy = begin; wy < end; ++wy)
      for (int dy = 0; dy < ys.length; ++dy) {
        const int y = int(wy) * ys.stride + dy;
        std::fill(row.begin(), row.end(), 0.0);
        for (int c = 0; c < channels; ++c) {
          const float* pixels = image.row(y, c);
          for (int x = 0; x < w; ++x) row[std::size_t(x)] += pixels[x];
        }
        const auto rowFactor = ys.weight(dy) * std::polar(1.0, -2 * std::numbers::pi * k[1] * (y + 0.5 - reference[1]));
        for (int wx = 0; wx < xs.count; ++wx) {
          std::complex<double> sum = 0;
          for (int dx = 0; dx < xs.length; ++dx) {
            const std::size_t x = std::size_t(wx * xs.stride + dx);
            sum += xs.weight(dx) * row[x] * columnPhase[x];
          }
          sums[wy * xs.count + std::size_t(wx)] += sum * rowFactor;
        }
      }
  });
  return sums;
}

}  // namespace

MicroImageLattice refineLatticeByEnvelope(const Image& image, const MicroImageLattice& start, Packing packing,
                                          int iterations) {
  MicroImageLattice lattice = start;
  const double pitch = std::hypot(start.e1[0], start.e1[1]);
  // A tile holds about four micro-images across: enough to average what they show.
  const int tile = std::max(8, int(std::lround(4 * pitch)));
  const Windows xs(image.width(), tile), ys(image.height(), tile);
  // Coordinates of a tile's centre from the reference, in units of the image's size (conditioning).
  const double scale = std::max(image.width(), image.height());
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const auto [k1, k2] = reciprocal(lattice.e1, lattice.e2);
    std::vector<Vec2> fundamentals = {k1, k2};
    // The third shortest reciprocal vector of a hexagonal lattice with e2 = e1 rotated 60 degrees.
    if (packing == Packing::Hexagonal) fundamentals.push_back({k1[0] + k2[0], k1[1] + k2[1]});
    // Rows: k . a + k . B (x - reference) / scale = -phase / 2 pi, for the unknowns a and B.
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    for (const Vec2& k : fundamentals) {
      const auto sums = windowSums(image, k, lattice.reference, xs, ys);
      for (int wy = 0; wy < ys.count; ++wy)
        for (int wx = 0; wx < xs.count; ++wx) {
          const std::complex<double> z = sums[std::size_t(wy) * xs.count + wx];
          const double weight = std::abs(z);
          if (!(weight > 0)) continue;
          const double X = (xs.centre(wx) - lattice.reference[0]) / scale;
          const double Y = (ys.centre(wy) - lattice.reference[1]) / scale;
          Eigen::Matrix<double, 6, 1> row;
          row << k[0], k[1], k[0] * X, k[0] * Y, k[1] * X, k[1] * Y;
          const double shift = -std::arg(z) / (2 * std::numbers::pi);  // cycles, in (-1/2, 1/2]
          normal += weight * row * row.transpose();
          rhs += weight * shift * row;
        }
    }
    const Eigen::Matrix<double, 6, 1> p = normal.ldlt().solve(rhs);
    if (!p.allFinite()) break;
    // Centres move by a + B (x - reference): the reference by a, the basis by B.
    const double b00 = p[2] / scale, b01 = p[3] / scale, b10 = p[4] / scale, b11 = p[5] / scale;
    auto moved = [&](const Vec2& e) { return Vec2{e[0] + b00 * e[0] + b01 * e[1], e[1] + b10 * e[0] + b11 * e[1]}; };
    lattice.reference = {lattice.reference[0] + p[0], lattice.reference[1] + p[1]};
    lattice.e1 = moved(lattice.e1);
    lattice.e2 = moved(lattice.e2);
  }
  return lattice;
}

}  // namespace lfcam
