// Digital refocusing by shift-and-add (Equation 6 with beta = 1, in the slope form of
// light_field.hpp). Two kernels with one meaning:
//   refocusReference  the formula of refocus.hpp, per output pixel, in float64: the test oracle.
//   refocus           the same sums reordered for speed: float32, one view at a time over whole
//                     rows, threaded over blocks of output rows.
#include "lfcam/refocus.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "render/bilinear_taps.hpp"
#include "render/references.hpp"
#include "render/row_blocks.hpp"
#include "render/shift_and_add.hpp"
#include "render/shift_and_add_rows.hpp"

namespace lfcam {

// ------------------------------------------------------------------------------------------------
// Reference: refocus.hpp's formula, term by term, at any slope per pixel.

Image refocusSlopeFieldReference(const LightField& lightField, const std::function<double(int x, int y)>& slopeAt,
                                 const KeepTap& keep) {
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns, shape.nt, shape.channels);
  if (lightField.empty()) return out;

  std::vector<double> sum(shape.channels);
  for (int y = 0; y < shape.nt; ++y) {
    for (int x = 0; x < shape.ns; ++x) {
      const double slope = slopeAt(x, y);
      if (!std::isfinite(slope)) continue;
      double weightSum = 0;
      const auto gather = [&](bool test) {
        std::fill(sum.begin(), sum.end(), 0.0);
        weightSum = 0;
        for (int v = 0; v < shape.nv; ++v) {
          const AxisShift sy = axisShift(lightField.vFromCentre(v), slope, shape.nt);
          for (int u = 0; u < shape.nu; ++u) {
            const AxisShift sx = axisShift(lightField.uFromCentre(u), slope, shape.ns);
            forEachBilinearTap(lightField, u, v, x, y, sx, sy, [&](int row, int column, double w) {
              if (test && !keep(u, v, row, column, x, y)) return;
              weightSum += w;
              for (int c = 0; c < shape.channels; ++c) sum[c] += w * lightField.at(u, v, column, row, c);
            });
          }
        }
      };
      gather(bool(keep));
      if (keep && weightSum == 0) gather(false);  // every ray left out: take them all
      // Normalise by the rays that contributed (section 5.2); no ray, no light.
      for (int c = 0; c < shape.channels; ++c) out.at(x, y, c) = weightSum > 0 ? float(sum[c] / weightSum) : 0.0f;
    }
  }
  return out;
}

Image refocusReference(const LightField& lightField, double slope) {
  return refocusSlopeFieldReference(lightField, [slope](int, int) { return slope; });
}

// ------------------------------------------------------------------------------------------------
// Fast kernel.
//
// It sums a list of terms (shift_and_add.hpp): for refocus, every view once with weight 1; for
// the synthetic camera's apertures and quadrature (synthetic_camera.cpp), views weighted by the
// aperture, or blends of neighbouring views at the shifts of aperture samples between them.
// For one view the shift is the same at every pixel, so its bilinear coefficients are constants:
// a view's contribution to an output row is four taps (two source rows, two neighbouring columns)
// with the same four coefficients at every pixel: one straight SIMD loop over the row, with the
// at most two columns whose taps leave the view done apart (shift_and_add_rows.hpp), so the loop
// has no per-pixel tests. Without a weight plane the weight sum factors:
//   sum_{u,v} wx_u(x) wy_v(y) = (sum_u wx_u(x)) (sum_v wy_v(y)),
// with wx_u(x) the bilinear coefficients of view column u's taps that fall inside the view, so it
// is computed once per column and once per row instead of accumulated per pixel.

namespace {

struct RefocusPlan {
  const LightField* lightField = nullptr;
  // The terms of the sum, each a view resampled at one constant shift, times a weight.
  std::vector<ShiftAndAddTerm> terms;
  std::vector<AxisShift> termColumnShift, termRowShift;  // per term
  // The plain refocus (every view once, weight 1) without a weight plane: the weight sums are
  // separable, per output column and per output row.
  bool separable = false;
  std::vector<float> columnWeight, rowWeight;
};

// sum over views of the bilinear coefficients whose tap lies inside the view, per output index.
std::vector<float> separableWeight(const std::vector<AxisShift>& shifts, int size) {
  std::vector<float> weight(size);
  for (int x = 0; x < size; ++x) {
    double sum = 0;
    for (const AxisShift& shift : shifts) {
      if (inside(x + shift.whole, size)) sum += 1 - shift.fraction;
      if (inside(x + shift.whole + 1, size)) sum += shift.fraction;
    }
    weight[x] = float(sum);
  }
  return weight;
}

// Output rows [y0, y1) of the refocused photograph: the whole algorithm for one block of rows.
// Views are the outer loop: each source row is read from memory once and reused, from cache, by
// the two output rows it is a tap of, while the block's accumulators stay in L2. One call per
// view and channel runs down the block's rows; the four bilinear taps of a row are one SIMD pass
// (shift_and_add_rows.hpp).
void refocusRows(const RefocusPlan& plan, int y0, int y1, Image& out) {
  const LightField& lightField = *plan.lightField;
  const int ns = lightField.ns(), nt = lightField.nt(), channels = lightField.channels();
  const bool lightFieldWeighted = lightField.hasWeight();
  // Accumulate the weight sum as one more plane unless it is separable.
  const bool weighted = !plan.separable;
  const int rows = y1 - y0;
  // Accumulators: one (rows x ns) plane per channel, then (weighted) one for the weight sum.
  const int planes = channels + (weighted ? 1 : 0);
  std::vector<float> accumulator(std::size_t(planes) * rows * ns, 0.0f);
  auto accumulatorRow = [&](int plane, int y) {
    return accumulator.data() + (std::size_t(plane) * rows + (y - y0)) * ns;
  };
  // Without a weight plane each tap weighs its coefficients alone: the weight sum accumulates a
  // row of ones. With one, the channels accumulate w * L, products formed a row at a time.
  std::vector<float> ones(weighted && !lightFieldWeighted ? ns : 0, 1.0f);
  std::vector<float> product0(lightFieldWeighted ? ns : 0), product1(lightFieldWeighted ? ns : 0);

  for (std::size_t term = 0; term < plan.terms.size(); ++term) {
    const int u = plan.terms[term].u, v = plan.terms[term].v;
    const float termWeight = plan.terms[term].weight;
    if (termWeight == 0.0f) continue;
    const AxisShift sx = plan.termColumnShift[term], sy = plan.termRowShift[term];
    // No output column has a tap in the view.
    if (sx.whole <= -ns - 1 || sx.whole >= ns) continue;
    const float ax0 = float(1 - sx.fraction), ax1 = float(sx.fraction);
    // The term's weight rides on the vertical coefficients (exactly 1 for plain refocus).
    const float top = float(1 - sy.fraction) * termWeight, bottom = float(sy.fraction) * termWeight;

    if (!lightFieldWeighted) {
      // The common case: each channel's rows in one call, which also prefetches the first
      // source row of the call after it.
      const auto firstRow = [&](std::size_t t, int c) {
        const int row = std::clamp(y0 + plan.termRowShift[t].whole, 0, nt - 1);
        return lightField.plane(plan.terms[t].u, plan.terms[t].v, c) + std::size_t(row) * ns;
      };
      for (int c = 0; c < channels; ++c) {
        const float* nextPass = c + 1 < channels               ? firstRow(term, c + 1)
                                : term + 1 < plan.terms.size() ? firstRow(term + 1, 0)
                                                               : nullptr;
        accumulateBilinearRows(accumulatorRow(c, y0), lightField.plane(u, v, c), ns, nt, y0, y1, sx.whole, ax0, ax1,
                               sy.whole, top, bottom, nextPass);
      }
      if (!weighted) continue;
    }
    // Row by row: the weight sum, and (with a weight plane) the channels as w * L.
    for (int y = y0; y < y1; ++y) {
      const VerticalTaps taps = verticalTaps(y, sy.whole, top, bottom, nt);
      if (taps.c0 == 0.0f) continue;
      const std::size_t offset0 = std::size_t(taps.row0) * ns, offset1 = std::size_t(taps.row1) * ns;
      const auto accumulate = [&](int plane, const float* first, const float* second) {
        accumulateBilinearRow(accumulatorRow(plane, y), first, second, sx.whole, taps.c0 * ax0, taps.c0 * ax1,
                              taps.c1 * ax0, taps.c1 * ax1, ns);
      };
      if (!lightFieldWeighted) {
        accumulate(channels, ones.data(), ones.data());
        continue;
      }
      // Each tap's weight is the bilinear coefficient times the light field's weight
      // (refocus.hpp), accumulated as one more channel.
      const float* weightPlane = lightField.weightPlane(u, v);
      accumulate(channels, weightPlane + offset0, weightPlane + offset1);
      for (int c = 0; c < channels; ++c) {
        const float* plane = lightField.plane(u, v, c);
        multiplyRows(product0.data(), weightPlane + offset0, plane + offset0, ns);
        multiplyRows(product1.data(), weightPlane + offset1, plane + offset1, ns);
        accumulate(c, product0.data(), product1.data());
      }
    }
  }

  // Divide by the weight of the rays that arrived (section 5.2).
  normaliseBlock(out, y0, y1, weighted, accumulatorRow, plan.columnWeight, plan.rowWeight);
}

}  // namespace

namespace {

Image runPlan(RefocusPlan& plan) {
  const LightField& lightField = *plan.lightField;
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns, shape.nt, shape.channels);
  for (const ShiftAndAddTerm& term : plan.terms) {
    plan.termColumnShift.push_back(shiftOf(term.shiftX, shape.ns));
    plan.termRowShift.push_back(shiftOf(term.shiftY, shape.nt));
  }

  forEachRowBlock(shape.nt, shape.ns, shape.channels + (plan.separable ? 0 : 1),
                  [&](int y0, int y1) { refocusRows(plan, y0, y1, out); });
  return out;
}

}  // namespace

Image refocus(const LightField& lightField, double slope) {
  const LightFieldShape& shape = lightField.shape();
  if (lightField.empty() || !std::isfinite(slope)) return Image(shape.ns, shape.nt, shape.channels);

  RefocusPlan plan;
  plan.lightField = &lightField;
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u)
      plan.terms.push_back({u, v, -lightField.uFromCentre(u) * slope, -lightField.vFromCentre(v) * slope, 1.0f});
  if (!lightField.hasWeight()) {
    std::vector<AxisShift> columnShift, rowShift;
    for (int u = 0; u < shape.nu; ++u) columnShift.push_back(axisShift(lightField.uFromCentre(u), slope, shape.ns));
    for (int v = 0; v < shape.nv; ++v) rowShift.push_back(axisShift(lightField.vFromCentre(v), slope, shape.nt));
    plan.separable = true;
    plan.columnWeight = separableWeight(columnShift, shape.ns);
    plan.rowWeight = separableWeight(rowShift, shape.nt);
  }
  return runPlan(plan);
}

Image shiftAndAdd(const LightField& lightField, std::vector<ShiftAndAddTerm> terms) {
  const LightFieldShape& shape = lightField.shape();
  if (lightField.empty()) return Image(shape.ns, shape.nt, shape.channels);
  RefocusPlan plan;
  plan.lightField = &lightField;
  std::erase_if(terms, [](const ShiftAndAddTerm& term) {
    return !(term.weight > 0) || !std::isfinite(term.shiftX) || !std::isfinite(term.shiftY);
  });
  plan.terms = std::move(terms);
  return runPlan(plan);
}

}  // namespace lfcam
