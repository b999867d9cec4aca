// The lattice model, its robust least-squares fit, and the sub-pixel centre of one microlens.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "calibrate/calibrate_internal.hpp"

namespace lfcam::calibrate_detail {

std::array<double, 2> Lattice::centre(int k, int n) const {
  const double a = (k + shift(n)) * pitchX, b = n * pitchY;
  const double c = std::cos(theta), s = std::sin(theta);
  return {ox + c * a - s * b, oy + s * a + c * b};
}

double Lattice::neighbourDistance() const {
  if (packing == Packing::Hexagonal) return std::min(pitchX, std::hypot(0.5 * pitchX, pitchY));
  return std::min(pitchX, pitchY);
}

std::vector<std::array<double, 2>> Lattice::neighbourOffsets() const {
  const double c = std::cos(theta), s = std::sin(theta);
  std::vector<std::array<double, 2>> offsets;
  const auto add = [&](double a, double b) { offsets.push_back({c * a - s * b, s * a + c * b}); };
  for (int n = -1; n <= 1; ++n)
    for (int k = -1; k <= 1; ++k) {
      if (packing == Packing::Hexagonal) {
        // Rows above and below are half a pitch off, whichever the row's parity.
        if (n == 0 && k != 0) add(k * pitchX, 0);
        if (n != 0 && k != 0) add(0.5 * k * pitchX, n * pitchY);
      } else if (n != 0 || k != 0) {
        add(k * pitchX, n * pitchY);
      }
    }
  return offsets;
}

namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// A few Gauss-Newton steps on the inliers; the model is nearly linear, so they converge at once.
void gaussNewton(const std::vector<Sample>& samples, const std::vector<char>& inlier, Lattice& l) {
  for (int iteration = 0; iteration < 4; ++iteration) {
    Eigen::Matrix<double, 5, 5> normal = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> rhs = Eigen::Matrix<double, 5, 1>::Zero();
    const double c = std::cos(l.theta), s = std::sin(l.theta);
    for (std::size_t m = 0; m < samples.size(); ++m) {
      if (!inlier[m]) continue;
      const Sample& p = samples[m];
      const double a = p.k + l.shift(p.n), b = p.n;
      const double u = a * l.pitchX, v = b * l.pitchY;
      const double ex = p.x - (l.ox + c * u - s * v), ey = p.y - (l.oy + s * u + c * v);
      // Rows of the Jacobian for x and y over (ox, oy, theta, pitchX, pitchY).
      const Eigen::Matrix<double, 5, 1> jx(1, 0, -s * u - c * v, c * a, -s * b);
      const Eigen::Matrix<double, 5, 1> jy(0, 1, c * u - s * v, s * a, c * b);
      normal.noalias() += jx * jx.transpose() + jy * jy.transpose();
      rhs += jx * ex + jy * ey;
    }
    const Eigen::Matrix<double, 5, 1> step = normal.ldlt().solve(rhs);
    if (!step.allFinite()) return;
    l.ox += step[0];
    l.oy += step[1];
    l.theta += step[2];
    l.pitchX += step[3];
    l.pitchY += step[4];
    if (step.cwiseAbs().maxCoeff() < 1e-12) return;
  }
}

}  // namespace

LatticeFit fitLattice(const std::vector<Sample>& samples, const Lattice& start) {
  LatticeFit fit;
  fit.lattice = start;
  fit.inlier.assign(samples.size(), 1);
  fit.residual.assign(samples.size(), 0.0);
  for (int round = 0; round < 12; ++round) {
    gaussNewton(samples, fit.inlier, fit.lattice);
    std::vector<double> inlierResiduals;
    for (std::size_t m = 0; m < samples.size(); ++m) {
      const auto c = fit.lattice.centre(samples[m].k, samples[m].n);
      fit.residual[m] = std::hypot(samples[m].x - c[0], samples[m].y - c[1]);
      if (fit.inlier[m]) inlierResiduals.push_back(fit.residual[m]);
    }
    // The median of 2D Gaussian residual lengths is 1.1774 sigma; 4 sigma keeps 99.97% of them.
    const double sigma = median(inlierResiduals) / 1.1774;
    const double threshold = std::max(4.0 * sigma, 1e-3);
    bool changed = false;
    for (std::size_t m = 0; m < samples.size(); ++m) {
      const char keep = fit.residual[m] <= threshold;
      changed |= keep != fit.inlier[m];
      fit.inlier[m] = keep;
    }
    if (!changed) break;
  }
  double sum = 0;
  fit.used = 0;
  fit.max = 0;
  for (std::size_t m = 0; m < samples.size(); ++m) {
    if (!fit.inlier[m]) continue;
    ++fit.used;
    sum += fit.residual[m] * fit.residual[m];
    fit.max = std::max(fit.max, fit.residual[m]);
  }
  fit.rms = fit.used ? std::sqrt(sum / fit.used) : 0;
  return fit;
}

CentreEstimate refineCentre(const Image& image, double x, double y, double radius, int iterations, double relax,
                            double tolerance) {
  CentreEstimate estimate;
  const int width = image.width(), height = image.height();
  const float* data = image.plane(0);
  const double outer = radius + 0.5;
  float level = 0;
  double lastStep = INFINITY;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const int x0 = int(std::floor(x - outer)), x1 = int(std::ceil(x + outer));
    const int y0 = int(std::floor(y - outer)), y1 = int(std::ceil(y + outer));
    if (x0 < 0 || y0 < 0 || x1 > width || y1 > height) return estimate;
    if (iteration == 0) {
      float lo = INFINITY, hi = -INFINITY;
      for (int py = y0; py < y1; ++py)
        for (int px = x0; px < x1; ++px) {
          lo = std::min(lo, data[std::size_t(py) * width + px]);
          hi = std::max(hi, data[std::size_t(py) * width + px]);
        }
      if (!(hi > lo)) return estimate;
      estimate.contrast = hi - lo;
      level = lo + 0.1f * (hi - lo);
    }
    // Soft disc: weight = covered fraction of the pixel, approximated by a one-pixel ramp.
    const float cx = float(x - 0.5), cy = float(y - 0.5), edge = float(outer);
    double sum = 0, sumX = 0, sumY = 0;
    for (int py = y0; py < y1; ++py) {
      const float dy = py - cy;
      const float* row = data + std::size_t(py) * width;
      float rowSum = 0, rowX = 0;
      for (int px = x0; px < x1; ++px) {
        const float dx = px - cx;
        const float w = std::clamp(edge - std::sqrt(dx * dx + dy * dy), 0.0f, 1.0f);
        const float v = w * std::max(row[px] - level, 0.0f);
        rowSum += v;
        rowX += v * dx;
      }
      sum += rowSum;
      sumX += rowX;
      sumY += double(rowSum) * dy;
    }
    if (!(sum > 0)) return estimate;
    const double stepX = relax * sumX / sum, stepY = relax * sumY / sum;
    x += stepX;
    y += stepY;
    lastStep = std::hypot(stepX, stepY);
    if (lastStep < tolerance) break;
  }
  estimate.x = x;
  estimate.y = y;
  estimate.ok = lastStep < std::max(0.02, 2 * tolerance);
  return estimate;
}

namespace {

// Bilinear sample at continuous position (x, y) (pixel centres at half-integers); the caller keeps
// it inside the image.
inline float bilinear(const float* data, int width, double x, double y) {
  const double fx = x - 0.5, fy = y - 0.5;
  const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
  const float ax = float(fx - ix), ay = float(fy - iy);
  const float* p = data + std::size_t(iy) * width + ix;
  return (1 - ay) * ((1 - ax) * p[0] + ax * p[1]) + ay * ((1 - ax) * p[width] + ax * p[width + 1]);
}

}  // namespace

CentreEstimate refineSymmetric(const Image& image, double x, double y, double radius, int iterations,
                               const std::vector<std::array<double, 2>>& neighbours) {
  CentreEstimate estimate;
  const int width = image.width(), height = image.height();
  const int reach = int(std::ceil(radius));
  auto inside = [&] { return x - reach - 2 >= 0 && y - reach - 2 >= 0 && x + reach + 2 <= width && y + reach + 2 <= height; };
  if (!inside()) return estimate;
  // Offsets over half the disc (d and -d give the same term), and each one's offset from the
  // centre of the microlens image it falls on (the tilt's lever: brightness ramps about each image's
  // own centre, so a neighbour's part of the window is no continuation of this image's ramp).
  thread_local std::vector<std::array<int, 2>> offsets;
  thread_local std::vector<std::array<double, 2>> levers;
  thread_local double offsetsRadius = -1;
  thread_local std::vector<std::array<double, 2>> offsetsNeighbours;
  if (offsetsRadius != radius || offsetsNeighbours != neighbours) {
    offsets.clear();
    levers.clear();
    for (int dy = 0; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx)
        if (!(dy == 0 && dx <= 0) && dx * dx + dy * dy <= radius * radius) {
          offsets.push_back({dx, dy});
          std::array<double, 2> lever{double(dx), double(dy)};
          for (const auto& n : neighbours)
            if (std::hypot(dx - n[0], dy - n[1]) < std::hypot(lever[0], lever[1])) lever = {dx - n[0], dy - n[1]};
          levers.push_back(lever);
        }
    offsetsRadius = radius;
    offsetsNeighbours = neighbours;
  }
  // Gauss-Newton on the sum over offsets d of [I(c + d) - I(c - d) - (g . e)(I(c + d) + I(c - d))]^2
  // (e: d's lever, d itself without neighbours) over the centre c and a tilt g: a centrally
  // symmetric image S times a linear ramp (1 + g . d),
  // such as a microlens image under the cos^4 fall-off of the rays of an off-axis microlens, has
  // this residual zero at its true centre, where without g the ramp pulls the centre towards the
  // bright side (inwards). The Jacobian in c is taken once at the start (within a pixel or so).
  const float* data = image.plane(0);
  thread_local std::vector<double> jx, jy, plus, minus;
  jx.resize(offsets.size());
  jy.resize(offsets.size());
  plus.resize(offsets.size());
  minus.resize(offsets.size());
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    const double px = x + offsets[k][0], py = y + offsets[k][1], qx = x - offsets[k][0], qy = y - offsets[k][1];
    // The bilinear interpolation of the central differences, which is the central difference of
    // the bilinear interpolation (both linear): no gradient images needed.
    jx[k] = 0.5 * (bilinear(data, width, px + 1, py) - bilinear(data, width, px - 1, py) -
                   bilinear(data, width, qx + 1, qy) + bilinear(data, width, qx - 1, qy));
    jy[k] = 0.5 * (bilinear(data, width, px, py + 1) - bilinear(data, width, px, py - 1) -
                   bilinear(data, width, qx, qy + 1) + bilinear(data, width, qx, qy - 1));
    normal(0, 0) += jx[k] * jx[k];
    normal(0, 1) += jx[k] * jy[k];
    normal(1, 1) += jy[k] * jy[k];
  }
  if (!(normal(0, 0) * normal(1, 1) - normal(0, 1) * normal(0, 1) > 0)) return estimate;
  double gx = 0, gy = 0;
  double lastStep = INFINITY;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    if (!inside()) return estimate;
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      plus[k] = bilinear(data, width, x + offsets[k][0], y + offsets[k][1]);
      minus[k] = bilinear(data, width, x - offsets[k][0], y - offsets[k][1]);
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

}  // namespace lfcam::calibrate_detail
