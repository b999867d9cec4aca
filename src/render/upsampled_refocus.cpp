// Refocusing on a finer grid (upsampled_refocus.hpp). Two kernels with one meaning:
//   refocusUpsampledReference  every sample of every view splatted where it lands, in float64:
//                              the test oracle, literally the header's formula.
//   refocusUpsampled           the same sums gathered per fine pixel: float32, views outer,
//                              threaded over blocks of fine rows.
#include "lfcam/render/upsampled_refocus.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/target_clones.hpp"
#include "lfcam/render/refocus.hpp"
#include "render/references.hpp"
#include "render/row_blocks.hpp"
#include "render/shift_and_add_rows.hpp"

namespace lfcam {

namespace {

Status checkFactor(int factor) {
  if (factor < 1 || factor > kMaxUpsampleFactor)
    return makeError(ErrorCode::Usage, "upsampling factor " + std::to_string(factor) + ": expected 1 to " +
                                           std::to_string(kMaxUpsampleFactor));
  return {};
}

// Where sample index i of a view shifted by `shift` (the view is sampled at x + shift for output
// x, refocus.hpp) lands on the fine grid: at fine position i K + landing. Shifts beyond the view's
// size put every sample outside the image; clamping them keeps the arithmetic in range.
double landing(double shift, int factor, int size) {
  shift = std::clamp(shift, -(size + 2.0), size + 2.0);
  return (0.5 - shift) * factor - 0.5;
}

// The tent at `distance` fine pixels from a sample. A weight that only rounding makes non-zero (a
// sample right at the tent's reach) counts as zero, so that the two kernels, which add the same
// distances in different orders, agree on which samples reach a pixel.
double tent(double distance, double halfWidth) {
  const double weight = 1 - std::abs(distance) / halfWidth;
  return weight > 1e-9 ? weight : 0.0;
}

// One axis of the splat (columns: u and s; rows: v and t), upsampled_refocus.hpp's h and c.
struct AxisSplat {
  double halfWidth = 1;                                          // h, fine pixels
  std::vector<double> landing;                                   // per view, landing() of its shift
  std::vector<std::array<double, kMaxUpsampleFactor>> centring;  // c, per view and fine phase
};

AxisSplat axisSplat(const LightField& lightField, double slope, int factor, bool rows) {
  const int views = rows ? lightField.nv() : lightField.nu(), size = rows ? lightField.nt() : lightField.ns();
  std::vector<double> position(views);  // view steps from the aperture centre
  AxisSplat axis;
  for (int k = 0; k < views; ++k) {
    position[k] = rows ? lightField.vFromCentre(k) : lightField.uFromCentre(k);
    axis.landing.push_back(landing(-position[k] * slope, factor, size));
  }
  // Distance from fine phase r to view k's nearest landing sample, in [-K/2, K/2].
  const auto apart = [&](int k, int r) {
    const double d = r - axis.landing[k];
    return d - std::floor(d / factor + 0.5) * factor;
  };
  if (factor == 1) {
    axis.centring.assign(views, {1, 1, 1, 1});
    return axis;
  }
  double farthest = 0;
  for (int r = 0; r < factor; ++r) {
    double nearest = factor;
    for (int k = 0; k < views; ++k) nearest = std::min(nearest, std::abs(apart(k, r)));
    farthest = std::max(farthest, nearest);
  }
  axis.halfWidth = std::clamp(2 * farthest, 0.375 * factor, 0.5 * factor);
  axis.centring.resize(views);
  for (int r = 0; r < factor; ++r) {
    double first = 0, second = 0;  // moments of the views' positions under the tent's weights
    for (int k = 0; k < views; ++k) {
      const double w = tent(apart(k, r), axis.halfWidth);
      first += w * position[k];
      second += w * position[k] * position[k];
    }
    const double tilt = second > 0 ? -first / second : 0.0;
    for (int k = 0; k < views; ++k) axis.centring[k][r] = std::max(0.0, 1 + tilt * position[k]);
  }
  return axis;
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Reference: each sample splatted on the fine pixels within the tent's reach.

Result<Image> refocusUpsampledReference(const LightField& lightField, double slope, int factor) {
  LFCAM_TRY(checkFactor(factor));
  const LightFieldShape& shape = lightField.shape();
  const int width = shape.ns * factor, height = shape.nt * factor;
  Image out(width, height, shape.channels);
  if (lightField.empty() || !std::isfinite(slope)) return out;
  const AxisSplat columns = axisSplat(lightField, slope, factor, false),
                  rows = axisSplat(lightField, slope, factor, true);
  std::vector<double> sum(std::size_t(width) * height * shape.channels), weightSum(std::size_t(width) * height);
  for (int v = 0; v < shape.nv; ++v) {
    const double landY = rows.landing[v];
    for (int u = 0; u < shape.nu; ++u) {
      const double landX = columns.landing[u];
      for (int j = 0; j < shape.nt; ++j) {
        const double fineY = j * factor + landY;
        for (int i = 0; i < shape.ns; ++i) {
          const double fineX = i * factor + landX;
          const double w = lightField.hasWeight() ? lightField.weightPlane(u, v)[std::size_t(j) * shape.ns + i] : 1.0;
          for (int y = int(std::ceil(fineY - rows.halfWidth)); y <= int(std::floor(fineY + rows.halfWidth)); ++y) {
            if (y < 0 || y >= height) continue;
            const double wy = tent(y - fineY, rows.halfWidth) * rows.centring[v][y % factor];
            if (!(wy > 0)) continue;
            for (int x = int(std::ceil(fineX - columns.halfWidth)); x <= int(std::floor(fineX + columns.halfWidth));
                 ++x) {
              if (x < 0 || x >= width) continue;
              const double tap = w * wy * tent(x - fineX, columns.halfWidth) * columns.centring[u][x % factor];
              if (!(tap > 0)) continue;
              const std::size_t at = std::size_t(y) * width + x;
              weightSum[at] += tap;
              for (int c = 0; c < shape.channels; ++c)
                sum[std::size_t(c) * width * height + at] += tap * lightField.at(u, v, i, j, c);
            }
          }
        }
      }
    }
  }
  for (int c = 0; c < shape.channels; ++c)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t at = std::size_t(y) * width + x;
        out.at(x, y, c) = weightSum[at] > 0 ? float(sum[std::size_t(c) * width * height + at] / weightSum[at]) : 0.0f;
      }
  return out;
}

// ------------------------------------------------------------------------------------------------
// Fast kernel.
//
// For K >= 2 the tent is one view pixel wide, so along each axis a fine pixel is reached by at
// most one sample of a view: the nearest to land. The samples land K fine pixels apart, so which
// sample and with what weight repeats with period K: fine index q K + r takes sample q + offset[r]
// with weight weight[r]. A view's contribution to a fine row is then K strided multiply-adds of
// one source row, one tap per fine pixel (the plain refocus has four per pixel on a K^2 times
// smaller grid). Without a weight plane the weight sum factors into a column and a row term, as
// in refocus.cpp.

namespace {

struct PhaseTaps {
  std::array<int, kMaxUpsampleFactor> offset{};
  std::array<float, kMaxUpsampleFactor> weight{};
};

// Per view of one axis: fine phase r takes the view's nearest sample, weighted by the tent times c.
std::vector<PhaseTaps> phaseTaps(const AxisSplat& axis, int factor) {
  std::vector<PhaseTaps> views(axis.landing.size());
  for (std::size_t k = 0; k < views.size(); ++k)
    for (int r = 0; r < factor; ++r) {
      const double nearest = std::floor((r - axis.landing[k]) / factor + 0.5);
      views[k].offset[r] = int(nearest);
      views[k].weight[r] = float(tent(r - axis.landing[k] - nearest * factor, axis.halfWidth) * axis.centring[k][r]);
    }
  return views;
}

// sum over views of the weight reaching fine index q K + r from a sample inside the view.
std::vector<float> separableWeight(const std::vector<PhaseTaps>& views, int factor, int size) {
  std::vector<float> weight(std::size_t(size) * factor);
  for (int q = 0; q < size; ++q)
    for (int r = 0; r < factor; ++r) {
      double sum = 0;
      for (const PhaseTaps& taps : views)
        if (q + taps.offset[r] >= 0 && q + taps.offset[r] < size) sum += taps.weight[r];
      weight[std::size_t(q) * factor + r] = float(sum);
    }
  return weight;
}

template <int K>
inline __attribute__((always_inline)) void splatRowFixed(float* __restrict accumulator, const float* __restrict row,
                                                         int ns, const int* offset, const float* coefficient) {
  // Fine indices whose every phase has its sample inside the view: one branch-free loop.
  int begin = 0, end = ns;
  for (int r = 0; r < K; ++r) {
    begin = std::max(begin, -offset[r]);
    end = std::min(end, ns - offset[r]);
  }
  const auto edge = [&](int q) {
    for (int r = 0; r < K; ++r)
      if (q + offset[r] >= 0 && q + offset[r] < ns) accumulator[q * K + r] += coefficient[r] * row[q + offset[r]];
  };
  if (begin >= end) {
    for (int q = 0; q < ns; ++q) edge(q);
    return;
  }
  for (int q = 0; q < begin; ++q) edge(q);
  std::array<const float*, K> source;
  std::array<float, K> c;
  for (int r = 0; r < K; ++r) {
    source[r] = row + offset[r];
    c[r] = coefficient[r];
  }
  for (int q = begin; q < end; ++q)
    for (int r = 0; r < K; ++r) accumulator[q * K + r] += c[r] * source[r][q];
  for (int q = end; q < ns; ++q) edge(q);
}

// accumulator[q K + r] += coefficient[r] row[q + offset[r]] for q in [0, ns), taps outside the row dropped.
LFCAM_CLONES void splatRow(float* accumulator, const float* row, int ns, int factor, const int* offset,
                           const float* coefficient) {
  switch (factor) {
    case 2: return splatRowFixed<2>(accumulator, row, ns, offset, coefficient);
    case 3: return splatRowFixed<3>(accumulator, row, ns, offset, coefficient);
    default: return splatRowFixed<4>(accumulator, row, ns, offset, coefficient);
  }
}

struct UpsamplePlan {
  const LightField* lightField = nullptr;
  int factor = 2;
  std::vector<PhaseTaps> columnTaps, rowTaps;  // per view column u, per view row v
  bool separable = false;                      // no weight plane: weight sums per column and row
  std::vector<float> columnWeight, rowWeight;
};

// Fine rows [y0, y1): every view adds its taps, then each pixel is divided by the weight that
// arrived.
void upsampledRows(const UpsamplePlan& plan, int y0, int y1, Image& out) {
  const LightField& lightField = *plan.lightField;
  const int ns = lightField.ns(), nt = lightField.nt(), channels = lightField.channels(), factor = plan.factor;
  const int width = ns * factor, rows = y1 - y0;
  const bool weighted = !plan.separable;
  const int planes = channels + (weighted ? 1 : 0);
  std::vector<float> accumulator(std::size_t(planes) * rows * width, 0.0f);
  auto accumulatorRow = [&](int plane, int y) {
    return accumulator.data() + (std::size_t(plane) * rows + (y - y0)) * width;
  };
  std::vector<float> product(weighted ? ns : 0);
  std::array<float, kMaxUpsampleFactor> coefficient{};
  for (int v = 0; v < lightField.nv(); ++v) {
    const PhaseTaps& vertical = plan.rowTaps[v];
    for (int u = 0; u < lightField.nu(); ++u) {
      const PhaseTaps& horizontal = plan.columnTaps[u];
      for (int y = y0; y < y1; ++y) {
        const int phase = y % factor, row = y / factor + vertical.offset[phase];
        const float wy = vertical.weight[phase];
        if (row < 0 || row >= nt || wy == 0.0f) continue;
        for (int r = 0; r < factor; ++r) coefficient[r] = wy * horizontal.weight[r];
        const std::size_t offset = std::size_t(row) * ns;
        if (!weighted) {
          for (int c = 0; c < channels; ++c)
            splatRow(accumulatorRow(c, y), lightField.plane(u, v, c) + offset, ns, factor, horizontal.offset.data(),
                     coefficient.data());
          continue;
        }
        // Each tap's weight is the tent times the light field's weight, accumulated as one more channel.
        const float* weightRow = lightField.weightPlane(u, v) + offset;
        splatRow(accumulatorRow(channels, y), weightRow, ns, factor, horizontal.offset.data(), coefficient.data());
        for (int c = 0; c < channels; ++c) {
          multiplyRows(product.data(), weightRow, lightField.plane(u, v, c) + offset, ns);
          splatRow(accumulatorRow(c, y), product.data(), ns, factor, horizontal.offset.data(), coefficient.data());
        }
      }
    }
  }
  normaliseBlock(out, y0, y1, weighted, accumulatorRow, plan.columnWeight, plan.rowWeight);
}

}  // namespace

Result<Image> refocusUpsampled(const LightField& lightField, double slope, int factor) {
  LFCAM_TRY(checkFactor(factor));
  if (factor == 1) return refocus(lightField, slope);
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns * factor, shape.nt * factor, shape.channels);
  if (lightField.empty() || !std::isfinite(slope)) return out;
  UpsamplePlan plan;
  plan.lightField = &lightField;
  plan.factor = factor;
  plan.columnTaps = phaseTaps(axisSplat(lightField, slope, factor, false), factor);
  plan.rowTaps = phaseTaps(axisSplat(lightField, slope, factor, true), factor);
  plan.separable = !lightField.hasWeight();
  if (plan.separable) {
    plan.columnWeight = separableWeight(plan.columnTaps, factor, shape.ns);
    plan.rowWeight = separableWeight(plan.rowTaps, factor, shape.nt);
  }
  forEachRowBlock(out.height(), out.width(), shape.channels + (plan.separable ? 0 : 1),
                  [&](int y0, int y1) { upsampledRows(plan, y0, y1, out); });
  return out;
}

}  // namespace lfcam
