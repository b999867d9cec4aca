// The centre of symmetry of a microlens image (refineSymmetric, calibrate_internal.hpp). Every
// sample sits at the centre plus an integer offset, so all of them share one sub-pixel phase: the
// fast path resamples the window once per step (a separable bilinear pass the compiler
// vectorises) and looks the samples up, where the reference interpolates each sample on its own.
// Both give the same floats (same arithmetic per sample); only the phase may differ in its last bit.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "calibrate/calibrate_internal.hpp"
#include "core/bilinear.hpp"

namespace lfcam::calibrate_detail {

namespace {

// The reference: each sample at (x + dx, y + dy) interpolated on its own.
class PointSampler {
 public:
  PointSampler(const Image& image, int) : data_(image.plane(0)), width_(image.width()), height_(image.height()) {}
  void moveTo(double x, double y) {
    x_ = x;
    y_ = y;
  }
  // Pixel centres at half-integers; the caller keeps the window inside the image.
  float at(int dx, int dy) const { return bilinearSample(data_, width_, height_, x_ + dx - 0.5, y_ + dy - 0.5); }

 private:
  const float* data_;
  int width_, height_;
  double x_ = 0, y_ = 0;
};

// The fast path: the (2 reach + 1)^2 window of offsets resampled at the centre's phase, the
// horizontal interpolation first (each row once), then the vertical, as bilinearSample does per sample.
class GridSampler {
 public:
  GridSampler(const Image& image, int reach)
      : data_(image.plane(0)), width_(image.width()), reach_(reach), size_(2 * reach + 1) {
    thread_local std::vector<float> rows, grid;
    rows.resize(std::size_t(size_) * (size_ + 1));
    grid.resize(std::size_t(size_) * size_);
    rows_ = rows.data();
    grid_ = grid.data();
  }
  void moveTo(double x, double y) {
    if (x == x_ && y == y_) return;
    x_ = x;
    y_ = y;
    const double fx = x - 0.5, fy = y - 0.5;
    const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
    const float ax = float(fx - ix), ay = float(fy - iy);
    for (int j = 0; j <= size_; ++j) {
      const float* p = data_ + std::size_t(iy - reach_ + j) * width_ + (ix - reach_);
      float* h = rows_ + std::size_t(j) * size_;
      for (int i = 0; i < size_; ++i) h[i] = p[i] + ax * (p[i + 1] - p[i]);
    }
    for (int j = 0; j < size_; ++j) {
      const float* top = rows_ + std::size_t(j) * size_;
      const float* bottom = top + size_;
      float* g = grid_ + std::size_t(j) * size_;
      for (int i = 0; i < size_; ++i) g[i] = top[i] + ay * (bottom[i] - top[i]);
    }
  }
  float at(int dx, int dy) const { return grid_[std::size_t(dy + reach_) * size_ + (dx + reach_)]; }

 private:
  const float* data_;
  int width_, reach_, size_;
  float* rows_;
  float* grid_;
  double x_ = NAN, y_ = NAN;
};

// Offsets over half the disc (d and -d give the same term), and each one's offset from the
// centre of the microlens image it falls on (the tilt's lever: brightness ramps about each image's
// own centre, so a neighbour's part of the window is no continuation of this image's ramp).
// Computed once per thread for a given radius and neighbours.
struct HalfDisc {
  std::vector<std::array<int, 2>> offsets;
  std::vector<std::array<double, 2>> levers;
  double radius = -1;
  std::vector<std::array<double, 2>> neighbours;
};

const HalfDisc& halfDisc(double radius, int reach, const std::vector<std::array<double, 2>>& neighbours) {
  thread_local HalfDisc disc;
  if (disc.radius == radius && disc.neighbours == neighbours) return disc;
  disc.offsets.clear();
  disc.levers.clear();
  for (int dy = 0; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      if (!(dy == 0 && dx <= 0) && dx * dx + dy * dy <= radius * radius) {
        disc.offsets.push_back({dx, dy});
        std::array<double, 2> lever{double(dx), double(dy)};
        for (const auto& n : neighbours)
          if (std::hypot(dx - n[0], dy - n[1]) < std::hypot(lever[0], lever[1])) lever = {dx - n[0], dy - n[1]};
        disc.levers.push_back(lever);
      }
  disc.radius = radius;
  disc.neighbours = neighbours;
  return disc;
}

template <class Sampler>
CentreEstimate symmetricCentre(const Image& image, double x, double y, double radius, int iterations,
                               const std::vector<std::array<double, 2>>& neighbours) {
  CentreEstimate estimate;
  const int width = image.width(), height = image.height();
  const int reach = int(std::ceil(radius));
  auto inside = [&] {
    return x - reach - 2 >= 0 && y - reach - 2 >= 0 && x + reach + 2 <= width && y + reach + 2 <= height;
  };
  if (!inside()) return estimate;
  const HalfDisc& disc = halfDisc(radius, reach, neighbours);
  const auto& offsets = disc.offsets;
  const auto& levers = disc.levers;
  // The samples reach one pixel beyond the disc (the Jacobian's central differences).
  Sampler sampler(image, reach + 1);
  // Gauss-Newton on the sum over offsets d of [I(c + d) - I(c - d) - (g . e)(I(c + d) + I(c - d))]^2
  // (e: d's lever, d itself without neighbours) over the centre c and a tilt g: a centrally
  // symmetric image S times a linear ramp (1 + g . d),
  // such as a microlens image under the cos^4 fall-off of the rays of an off-axis microlens, has
  // this residual zero at its true centre, where without g the ramp pulls the centre towards the
  // bright side (inwards). The Jacobian in c is taken once at the start (within a pixel or so).
  thread_local std::vector<double> jx, jy, plus, minus;
  jx.resize(offsets.size());
  jy.resize(offsets.size());
  plus.resize(offsets.size());
  minus.resize(offsets.size());
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  sampler.moveTo(x, y);
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    const int dx = offsets[k][0], dy = offsets[k][1];
    // The bilinear interpolation of the central differences, which is the central difference of
    // the bilinear interpolation (both linear): no gradient images needed.
    jx[k] =
        0.5 * (sampler.at(dx + 1, dy) - sampler.at(dx - 1, dy) - sampler.at(-dx + 1, -dy) + sampler.at(-dx - 1, -dy));
    jy[k] =
        0.5 * (sampler.at(dx, dy + 1) - sampler.at(dx, dy - 1) - sampler.at(-dx, -dy + 1) + sampler.at(-dx, -dy - 1));
    normal(0, 0) += jx[k] * jx[k];
    normal(0, 1) += jx[k] * jy[k];
    normal(1, 1) += jy[k] * jy[k];
  }
  if (!(normal(0, 0) * normal(1, 1) - normal(0, 1) * normal(0, 1) > 0)) return estimate;
  double gx = 0, gy = 0;
  double lastStep = INFINITY;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    if (!inside()) return estimate;
    sampler.moveTo(x, y);
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      plus[k] = sampler.at(offsets[k][0], offsets[k][1]);
      minus[k] = sampler.at(-offsets[k][0], -offsets[k][1]);
    }
    // d r / d c = grad I(c + d) - grad I(c - d) = (jx, jy) (the tilt's share neglected: g is
    // small); d r / d g = -d (I(c + d) + I(c - d)).
    normal.block<2, 2>(0, 2).setZero();
    normal.block<2, 2>(2, 2).setZero();
    Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const double dx = levers[k][0], dy = levers[k][1];
      const double level = plus[k] + minus[k];
      const double r = plus[k] - minus[k] - (gx * dx + gy * dy) * level;
      const double ggx = -dx * level, ggy = -dy * level;
      normal(0, 2) += jx[k] * ggx;
      normal(0, 3) += jx[k] * ggy;
      normal(1, 2) += jy[k] * ggx;
      normal(1, 3) += jy[k] * ggy;
      normal(2, 2) += ggx * ggx;
      normal(2, 3) += ggx * ggy;
      normal(3, 3) += ggy * ggy;
      rhs += Eigen::Vector4d(jx[k], jy[k], ggx, ggy) * r;
    }
    const Eigen::Matrix4d full = normal.selfadjointView<Eigen::Upper>();
    const Eigen::Vector4d step = -full.ldlt().solve(rhs);
    if (!step.allFinite()) return estimate;
    double stepX = step[0], stepY = step[1];
    const double length = std::hypot(stepX, stepY);
    if (length > 1.0) {
      stepX /= length;
      stepY /= length;
    }
    x += stepX;
    y += stepY;
    gx += step[2];
    gy += step[3];
    lastStep = std::hypot(stepX, stepY);
    if (lastStep < 1e-3) break;
  }
  estimate.x = x;
  estimate.y = y;
  estimate.ok = lastStep < 0.02;
  return estimate;
}

}  // namespace

CentreEstimate refineSymmetric(const Image& image, double x, double y, double radius, int iterations,
                               const std::vector<std::array<double, 2>>& neighbours) {
  return symmetricCentre<GridSampler>(image, x, y, radius, iterations, neighbours);
}

CentreEstimate refineSymmetricReference(const Image& image, double x, double y, double radius, int iterations,
                                        const std::vector<std::array<double, 2>>& neighbours) {
  return symmetricCentre<PointSampler>(image, x, y, radius, iterations, neighbours);
}

}  // namespace lfcam::calibrate_detail
