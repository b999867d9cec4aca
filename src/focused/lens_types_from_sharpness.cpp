#include "lfcam/focused/lens_types_from_sharpness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace lfcam {

namespace {

double median(std::vector<double> values) {
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The six neighbours of lens (i, j) on a hexagonal grid whose shifted rows sit half a pitch right.
std::array<std::array<int, 2>, 6> hexNeighbours(const LensletGrid& grid, int i, int j) {
  const bool shifted = (j + grid.hexParity) & 1;
  const int left = shifted ? i : i - 1;  // of the two neighbours in the rows above and below
  return {{{i - 1, j}, {i + 1, j}, {left, j - 1}, {left + 1, j - 1}, {left, j + 1}, {left + 1, j + 1}}};
}

}  // namespace

LensTypeFinding lensTypesFromSharpness(const FocusedCalibration& calibration, const LensTypeEvidence& evidence,
                                       double minSpread) {
  LensTypeFinding finding;
  finding.lensTypes = {LensType{{0, 0}, 1, 100}};
  const LensletGrid& grid = calibration.grid;
  const std::size_t count = std::size_t(grid.columns) * grid.rows;
  if (grid.packing != Packing::Hexagonal || evidence.sharpness.size() != count || evidence.virtualDepth.size() != count)
    return finding;

  // The three classes, named by Raytrix's offsets.
  FocusedCalibration classes = calibration;
  classes.lensTypes = {LensType{{0, 0}}, LensType{{1, 0}}, LensType{{-1, 0}}};
  // Per band of disparity, per class: the relative log sharpness of its lenses.
  std::map<int, std::array<std::vector<double>, 3>> bands;
  auto index = [&](int i, int j) { return std::size_t(j) * grid.columns + i; };
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const float s = evidence.sharpness[index(i, j)], v = evidence.virtualDepth[index(i, j)];
      if (!(s > 0 && v > 0)) continue;
      double neighbours = 0;
      int n = 0;
      for (const auto& [ni, nj] : hexNeighbours(grid, i, j))
        if (ni >= 0 && nj >= 0 && ni < grid.columns && nj < grid.rows && evidence.sharpness[index(ni, nj)] > 0) {
          neighbours += std::log(evidence.sharpness[index(ni, nj)]);
          ++n;
        }
      if (n < 3) continue;
      const int band = int(std::floor(calibration.diameterPx() / v));
      bands[band][std::size_t(classes.lensType(i, j))].push_back(std::log(s) - neighbours / n);
    }

  struct Band {
    double virtualDepth = 0, weight = 0;
    std::array<double, 3> median{};
  };
  std::vector<Band> kept;  // by increasing virtual depth (decreasing disparity)
  for (auto it = bands.rbegin(); it != bands.rend(); ++it) {
    const auto& [band, samples] = *it;
    if (std::any_of(samples.begin(), samples.end(), [](const auto& s) { return s.size() < 5; })) continue;
    Band b;
    b.virtualDepth = calibration.diameterPx() / (band + 0.5);
    for (int k = 0; k < 3; ++k) {
      b.median[std::size_t(k)] = median(samples[std::size_t(k)]);
      b.weight += double(samples[std::size_t(k)].size());
    }
    kept.push_back(b);
  }
  double weights = 0;
  for (const Band& b : kept) {
    finding.spread += b.weight * (*std::max_element(b.median.begin(), b.median.end()) -
                                  *std::min_element(b.median.begin(), b.median.end()));
    weights += b.weight;
  }
  finding.spread = weights > 0 ? finding.spread / weights : 0;
  if (finding.spread < minSpread) return finding;

  // Each kind is the sharpest over one range of depth: the order of the classes and the two cuts
  // between bands that let the classes' medians score best, the bands of a range counting for
  // its class (every range holding at least one band).
  if (kept.size() < 3) return finding;  // too few depths in the capture to order three kinds
  std::array<int, 3> order{0, 1, 2}, bestOrder = order;
  std::size_t bestFirst = 1, bestSecond = 2;
  double bestScore = -std::numeric_limits<double>::infinity();
  do {
    for (std::size_t first = 1; first + 1 < kept.size(); ++first)
      for (std::size_t second = first + 1; second < kept.size(); ++second) {
        double score = 0;
        for (std::size_t n = 0; n < kept.size(); ++n) {
          const int range = n < first ? 0 : n < second ? 1 : 2;
          score += kept[n].weight * kept[n].median[std::size_t(order[std::size_t(range)])];
        }
        if (score > bestScore) bestScore = score, bestOrder = order, bestFirst = first, bestSecond = second;
      }
  } while (std::next_permutation(order.begin(), order.end()));
  // A cut between bands n - 1 and n lies where the nearer class stops being the sharper of the
  // two, or half-way (in log depth) when their medians do not cross there.
  auto cut = [&](std::size_t n, int nearer, int farther) {
    const double before = kept[n - 1].median[std::size_t(nearer)] - kept[n - 1].median[std::size_t(farther)];
    const double after = kept[n].median[std::size_t(nearer)] - kept[n].median[std::size_t(farther)];
    const double t = before > 0 && after <= 0 ? before / (before - after) : 0.5;
    return std::exp((1 - t) * std::log(kept[n - 1].virtualDepth) + t * std::log(kept[n].virtualDepth));
  };
  order = bestOrder;
  const double first = std::clamp(cut(bestFirst, order[0], order[1]), 1.0, 100.0);
  const double second = std::clamp(cut(bestSecond, order[1], order[2]), first, 100.0);
  const std::array<double, 4> limits{1, first, second, 100};
  finding.lensTypes.clear();
  for (int n = 0; n < 3; ++n)
    finding.lensTypes.push_back(LensType{classes.lensTypes[std::size_t(order[std::size_t(n)])].offset,
                                         limits[std::size_t(n)], limits[std::size_t(n) + 1]});
  return finding;
}

}  // namespace lfcam
