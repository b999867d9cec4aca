// The lattice model, its robust least-squares fit, and the centroid of one microlens image (the
// centre of symmetry is in symmetric_centre.cpp).
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

namespace {

// kFast: only the disc's span of each row, and the square root only on its rim; otherwise every
// pixel of the window through the weight's formula (the reference). The same floats.
template <bool kFast>
CentreEstimate centroid(const Image& image, double x, double y, double radius, int iterations, double relax,
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
    // The weight is 1 well inside the disc and 0 outside it: the square root only on the rim (the
    // margins keep every weight what the formula gives; the zeros add nothing).
    const float inner2 = edge > 1 ? 0.9999f * (edge - 1) * (edge - 1) : -1.0f, outer2 = 1.0001f * edge * edge;
    double sum = 0, sumX = 0, sumY = 0;
    for (int py = y0; py < y1; ++py) {
      const float dy = py - cy;
      if (kFast && dy * dy >= outer2) continue;
      const float* row = data + std::size_t(py) * width;
      // The row's span of the disc, a pixel wide on each side.
      int from = x0, to = x1;
      if (kFast) {
        const float half = std::sqrt(outer2 - dy * dy);
        from = std::max(x0, int(std::floor(cx - half)) - 1);
        to = std::min(x1, int(std::ceil(cx + half)) + 2);
      }
      float rowSum = 0, rowX = 0;
      for (int px = from; px < to; ++px) {
        const float dx = px - cx;
        const float d2 = dx * dx + dy * dy;
        if (kFast && d2 >= outer2) continue;
        const float w = kFast && d2 <= inner2 ? 1.0f : std::clamp(edge - std::sqrt(d2), 0.0f, 1.0f);
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

}  // namespace

CentreEstimate refineCentre(const Image& image, double x, double y, double radius, int iterations, double relax,
                            double tolerance) {
  return centroid<true>(image, x, y, radius, iterations, relax, tolerance);
}

CentreEstimate refineCentreReference(const Image& image, double x, double y, double radius, int iterations,
                                     double relax, double tolerance) {
  return centroid<false>(image, x, y, radius, iterations, relax, tolerance);
}

}  // namespace lfcam::calibrate_detail
