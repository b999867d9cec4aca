// Digital refocusing by shift-and-add (Equation 6 with beta = 1, in the slope form of
// light_field.hpp). Two kernels with one meaning:
//   refocusReference  the formula of refocus.hpp, per output pixel, in float64: the test oracle.
//   refocus           the same sums reordered for speed: float32, one view at a time over whole
//                     rows, threaded over blocks of output rows; for a focal stack, each block at
//                     every slope in turn.
#include "lfcam/render/refocus.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <span>
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
// For one view the shift is the same at every pixel, so its bilinear coefficients are constants,
// and the terms that share a vertical shift (a row of views, for refocus) share the vertical
// coefficients top and bottom of every output row y, whose taps are source rows y + whole and
// y + whole + 1. So the bilinear sum splits: first the horizontal taps of every term of the group
// summed per source row,
//   G(r)[x] = sum_k (ax0_k L_k(x + whole_k, r) + ax1_k L_k(x + whole_k + 1, r)),
// then each output row from two of those: E(y) += top G(y + whole) + bottom G(y + whole + 1).
// Each G(r) serves two output rows, so a sample costs two multiply-adds instead of four, and the
// accumulator row is loaded and stored once per group instead of once per view
// (shift_and_add_rows.hpp). Without a weight plane the weight sum factors:
//   sum_{u,v} wx_u(x) wy_v(y) = (sum_u wx_u(x)) (sum_v wy_v(y)),
// with wx_u(x) the bilinear coefficients of view column u's taps that fall inside the view, so it
// is computed once per column and once per row instead of accumulated per pixel.

namespace {

// Terms [begin, end) of a plan, which share one vertical shift.
struct TermGroup {
  std::size_t begin = 0, end = 0;
};

struct RefocusPlan {
  const LightField* lightField = nullptr;
  // The terms of the sum, each a view resampled at one constant shift, times a weight, sorted by
  // vertical shift and grouped by it.
  std::vector<ShiftAndAddTerm> terms;
  std::vector<AxisShift> termColumnShift, termRowShift;  // per term
  std::vector<TermGroup> groups;
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
// Per group of terms and per plane (each channel, then the weight sum unless it is separable), the
// source rows y0 + whole to y1 + whole stream from memory once, each view's rows in order, into
// the horizontal sums G of the comment above; the block's accumulator plane stays in L2 meanwhile.
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
  // G of the source row above and of the one below the output row being summed.
  std::vector<float> sums(2 * std::size_t(ns));
  // Without a weight plane each tap weighs its coefficients alone: the weight sum adds rows of
  // ones. With one, the channels add w * L, products formed a row at a time, one per term.
  std::vector<float> ones(weighted && !lightFieldWeighted ? ns : 0, 1.0f);
  std::vector<float> products;
  std::vector<std::size_t> live;  // the group's terms with a column in the view
  std::vector<ShiftedRow> shifted;

  for (const TermGroup& group : plan.groups) {
    const AxisShift sy = plan.termRowShift[group.begin];
    const float top = float(1 - sy.fraction), bottom = float(sy.fraction);
    // The terms with a column in the view, their weight riding on the horizontal coefficients.
    live.clear(), shifted.clear();
    for (std::size_t term = group.begin; term < group.end; ++term) {
      const AxisShift sx = plan.termColumnShift[term];
      const float termWeight = plan.terms[term].weight;
      if (termWeight == 0.0f || sx.whole <= -ns - 1 || sx.whole >= ns) continue;
      live.push_back(term);
      shifted.push_back({nullptr, sx.whole, float(1 - sx.fraction) * termWeight, float(sx.fraction) * termWeight});
    }
    if (shifted.empty()) continue;
    if (lightFieldWeighted) products.resize(shifted.size() * ns);
    for (int plane = 0; plane < planes; ++plane) {
      float* above = sums.data();
      float* below = above + ns;
      // Source row y + whole + 1: the lower tap of output row y, the upper tap of row y + 1.
      for (int y = y0 - 1; y < y1; ++y) {
        const int row = y + sy.whole + 1;
        const OutputRow output{y >= y0 ? accumulatorRow(plane, y) : nullptr, above, top, bottom};
        // Outside the view, or the last row's lower tap when it weighs nothing: G = 0.
        const bool read = inside(row, nt) && (y + 1 < y1 || bottom != 0.0f);
        if (read) {
          const std::size_t offset = std::size_t(row) * ns;
          for (std::size_t k = 0; k < live.size(); ++k) {
            const int u = plan.terms[live[k]].u, v = plan.terms[live[k]].v;
            const float* source = plane < channels ? lightField.plane(u, v, plane) + offset : ones.data();
            if (lightFieldWeighted) {
              // Each tap weighs its bilinear coefficient times the light field's weight.
              const float* weightRow = lightField.weightPlane(u, v) + offset;
              if (plane < channels) {
                multiplyRows(products.data() + k * ns, weightRow, source, ns);
                source = products.data() + k * ns;
              } else {
                source = weightRow;
              }
            }
            shifted[k].row = source;
          }
        }
        sumShiftedRows(below, shifted.data(), read ? int(shifted.size()) : 0, ns, y >= y0 ? &output : nullptr);
        std::swap(above, below);
      }
    }
  }

  // Divide by the weight of the rays that arrived (section 5.2).
  normaliseBlock(out, y0, y1, weighted, accumulatorRow, plan.columnWeight, plan.rowWeight);
}

}  // namespace

namespace {

// Sorts the plan's terms by vertical shift and groups those that share one.
void preparePlan(RefocusPlan& plan) {
  const LightFieldShape& shape = plan.lightField->shape();
  std::stable_sort(plan.terms.begin(), plan.terms.end(),
                   [](const ShiftAndAddTerm& a, const ShiftAndAddTerm& b) { return a.shiftY < b.shiftY; });
  for (const ShiftAndAddTerm& term : plan.terms) {
    plan.termColumnShift.push_back(shiftOf(term.shiftX, shape.ns));
    plan.termRowShift.push_back(shiftOf(term.shiftY, shape.nt));
  }
  for (std::size_t term = 0; term < plan.terms.size(); ++term) {
    const AxisShift& sy = plan.termRowShift[term];
    if (plan.groups.empty() || plan.termRowShift[plan.groups.back().begin].whole != sy.whole ||
        plan.termRowShift[plan.groups.back().begin].fraction != sy.fraction)
      plan.groups.push_back({term, term});
    plan.groups.back().end = term + 1;
  }
}

// Each plan's photograph: *out[k] of plans[k]. One accumulator plane is summed into at a time. Each
// block of rows is summed for every plan before the next: its views' rows, read from memory for
// the first plan, are still in cache for the next ones when their shifts are alike (a focal stack).
void runPlans(std::vector<RefocusPlan>& plans, const std::vector<Image*>& out) {
  if (plans.empty()) return;
  for (RefocusPlan& plan : plans) preparePlan(plan);
  const LightFieldShape& shape = plans.front().lightField->shape();
  forEachRowBlock(shape.nt, shape.ns, 1, [&](int y0, int y1) {
    for (std::size_t k = 0; k < plans.size(); ++k) refocusRows(plans[k], y0, y1, *out[k]);
  });
}

RefocusPlan refocusPlan(const LightField& lightField, double slope) {
  const LightFieldShape& shape = lightField.shape();
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
  return plan;
}

}  // namespace

std::vector<Image> refocus(const LightField& lightField, std::span<const double> slopes) {
  const LightFieldShape& shape = lightField.shape();
  std::vector<Image> photos;
  for (std::size_t k = 0; k < slopes.size(); ++k) photos.emplace_back(shape.ns, shape.nt, shape.channels);
  std::vector<RefocusPlan> plans;
  std::vector<Image*> out;
  for (std::size_t k = 0; k < slopes.size(); ++k)
    if (!lightField.empty() && std::isfinite(slopes[k])) {
      plans.push_back(refocusPlan(lightField, slopes[k]));
      out.push_back(&photos[k]);
    }
  runPlans(plans, out);
  return photos;
}

void refocusEach(const LightField& lightField, std::span<const double> slopes,
                 const std::function<void(std::size_t, Image&&)>& use, std::size_t budgetBytes) {
  const std::size_t photoBytes =
      std::max<std::size_t>(lightField.shape().viewPixels() * lightField.channels(), 1) * sizeof(float);
  const std::size_t batch = std::max<std::size_t>(budgetBytes / photoBytes, 1);
  for (std::size_t first = 0; first < slopes.size(); first += batch) {
    std::vector<Image> photos = refocus(lightField, slopes.subspan(first, std::min(batch, slopes.size() - first)));
    for (std::size_t k = 0; k < photos.size(); ++k) use(first + k, std::move(photos[k]));
  }
}

Image refocus(const LightField& lightField, double slope) {
  return std::move(refocus(lightField, std::span<const double>(&slope, 1)).front());
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
  std::vector<RefocusPlan> plans;
  plans.push_back(std::move(plan));
  Image photo(shape.ns, shape.nt, shape.channels);
  runPlans(plans, {&photo});
  return photo;
}

}  // namespace lfcam
