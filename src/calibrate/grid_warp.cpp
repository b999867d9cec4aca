// The smooth warp of a grid (lenslet_grid.hpp's GridWarp), fitted to the centres the lattice fit
// left: a microscope's fluorescence frame showed residuals of 0.8 px RMS against the best lattice
// that were 0.055 px RMS from their neighbours' median, a smooth field no lattice holds
// (SelfCalibration.StanfordFluorescenceResidualIsASmoothField).
#include <Eigen/Dense>

#include <cmath>

#include "calibrate/calibrate_internal.hpp"

namespace lfcam::calibrate_detail {

void fitGridWarp(LensletGrid& grid, std::vector<DetectedCentre>& centres) {
  // A control point every kCell microlenses: cells hold hundreds of centres where there is signal,
  // and the first differences between neighbours (weight kSmooth) carry the warp across the rest.
  constexpr int kCell = 16;
  constexpr double kSmooth = 1.0;
  GridWarp& warp = grid.warp;
  warp.columns = std::max(2, int(std::lround((grid.columns - 1) / double(kCell))) + 1);
  warp.rows = std::max(2, int(std::lround((grid.rows - 1) / double(kCell))) + 1);
  const int unknowns = warp.columns * warp.rows;
  Eigen::MatrixXd normal = Eigen::MatrixXd::Identity(unknowns, unknowns) * 1e-9;
  Eigen::MatrixXd right = Eigen::MatrixXd::Zero(unknowns, 2);
  warp.offsets.assign(unknowns, {0, 0});  // centre() is the lattice's while fitting
  for (const DetectedCentre& c : centres) {
    if (!c.inlier) continue;
    const double u =
        std::clamp(double(c.i) * (warp.columns - 1) / std::max(1, grid.columns - 1), 0.0, warp.columns - 1.0);
    const double v = std::clamp(double(c.j) * (warp.rows - 1) / std::max(1, grid.rows - 1), 0.0, warp.rows - 1.0);
    const int p0 = std::min(int(u), warp.columns - 2), q0 = std::min(int(v), warp.rows - 2);
    const double fu = u - p0, fv = v - q0;
    const int index[4] = {q0 * warp.columns + p0, q0 * warp.columns + p0 + 1, (q0 + 1) * warp.columns + p0,
                          (q0 + 1) * warp.columns + p0 + 1};
    const double weight[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
    const auto lattice = grid.latticeCentre(c.i, c.j);
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) normal(index[a], index[b]) += weight[a] * weight[b];
      right(index[a], 0) += weight[a] * (c.x - lattice[0]);
      right(index[a], 1) += weight[a] * (c.y - lattice[1]);
    }
  }
  auto smooth = [&](int a, int b) {
    normal(a, a) += kSmooth, normal(b, b) += kSmooth, normal(a, b) -= kSmooth, normal(b, a) -= kSmooth;
  };
  for (int q = 0; q < warp.rows; ++q)
    for (int p = 0; p < warp.columns; ++p) {
      if (p + 1 < warp.columns) smooth(q * warp.columns + p, q * warp.columns + p + 1);
      if (q + 1 < warp.rows) smooth(q * warp.columns + p, (q + 1) * warp.columns + p);
    }
  const Eigen::MatrixXd solution = normal.ldlt().solve(right);
  for (int k = 0; k < unknowns; ++k) warp.offsets[k] = {solution(k, 0), solution(k, 1)};
  // The fit report is then against the warped grid: what decoding will use.
  double sum = 0, worst = 0;
  int used = 0;
  for (DetectedCentre& c : centres) {
    const auto p = grid.centre(c.i, c.j);
    c.residualPx = std::hypot(c.x - p[0], c.y - p[1]);
    if (!c.inlier) continue;
    sum += c.residualPx * c.residualPx, worst = std::max(worst, c.residualPx), ++used;
  }
  if (used > 0) grid.fit.rmsResidualPx = std::sqrt(sum / used), grid.fit.maxResidualPx = worst;
}

}  // namespace lfcam::calibrate_detail
