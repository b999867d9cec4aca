// Depth from a light field (depth.hpp): cost volume from the correspondence and defocus cues,
// guided-filter aggregation, semi-global optimisation, sub-label read-out, fine search, cleanup,
// confidence (the seven stages of depth.hpp, numbered alike below); distances.
#include "lfcam/depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "core/bilinear.hpp"
#include "core/parabola.hpp"
#include "core/quadratic_filter.hpp"
#include "core/target_clones.hpp"
#include "edof/depth_experiment.hpp"
#include "edof/edof_internal.hpp"
#include "edof/fine_cost_row.hpp"
#include "edof/interpolation_terms.hpp"
#include "lfcam/image_io.hpp"
#include "lfcam/parallel.hpp"
#include "lfcam/refocus.hpp"

namespace lfcam {

namespace {

// Subsets of views compared separately, as bits (a view may belong to several): four strict
// half-apertures for occlusion boundaries, u < 0, u > 0, v < 0, v > 0; and the centre row and
// the centre column alone, for surfaces strongly slanted in depth along one axis (a floor seen at
// a grazing angle is foreshortened differently in every view of a column, not of a row). The
// halves leave out the centre row or column: next to a slanted occluding edge, the views that
// move along the edge see the occluder too (measured on antinous: MSE x100 28 -> 14).
constexpr int kHalves = 6;

struct StarView {
  int u = 0, v = 0;
  double uc = 0, vc = 0;  // view steps from the aperture centre
  int halves = 0;         // bit h set: the view is in half-aperture h
};

// View steps of view (u, v) from the point the views are matched at: the aperture centre, or with
// `fromReference` the reference view ((nu - 1) / 2, (nv - 1) / 2; DepthExperiment::matchAtReference).
// They differ with an even number of views.
double stepsU(const LightField& lightField, int u, bool fromReference) {
  return fromReference ? u - (lightField.nu() - 1) / 2 : lightField.uFromCentre(u);
}
double stepsV(const LightField& lightField, int v, bool fromReference) {
  return fromReference ? v - (lightField.nv() - 1) / 2 : lightField.vFromCentre(v);
}

// The views compared with the reference: the star through the reference view (its row, its
// column, both diagonals). A star sees every edge orientation from both sides with a third of
// the views of the full aperture.
std::vector<StarView> starViews(const LightField& lightField, int referenceU, int referenceV, bool fromReference) {
  std::vector<StarView> views;
  for (int v = 0; v < lightField.nv(); ++v)
    for (int u = 0; u < lightField.nu(); ++u) {
      if (u == referenceU && v == referenceV) continue;
      const int du = u - referenceU, dv = v - referenceV;
      if (du != 0 && dv != 0 && std::abs(du) != std::abs(dv)) continue;
      StarView view{u, v, stepsU(lightField, u, fromReference), stepsV(lightField, v, fromReference), 0};
      if (du < 0) view.halves |= 1;
      if (du > 0) view.halves |= 2;
      if (dv < 0) view.halves |= 4;
      if (dv > 0) view.halves |= 8;
      if (dv == 0) view.halves |= 16;
      if (du == 0) view.halves |= 32;
      views.push_back(view);
    }
  return views;
}

// accumulator += (sample - reference)^2
LFCAM_CLONES void accumulateSquaredDifference(const float* __restrict sample, const float* __restrict reference,
                                              float* __restrict accumulator, int count) {
  for (int x = 0; x < count; ++x) {
    const float difference = sample[x] - reference[x];
    accumulator[x] += difference * difference;
  }
}

// Bilinear interpolation blurs a view sampled between pixels, by f (1 - f) / 2 times the second
// difference of the signal at fraction f, and that blur adds its square to the cost of every
// disparity that shifts views by fractions: the cost is biased towards whole-pixel shifts
// ("pixel locking"). The model of that term: per pixel the squared second differences of the
// reference view (it shows the same texture), per view and disparity the weights from
// interpolationBlur (interpolation_terms.hpp); the cost subtracts their product. The reference's
// own interpolation (an even grid) is left out.
struct SecondDifferences {
  std::vector<float> xx, yy, xy;  // Ixx^2, Iyy^2, 2 Ixx Iyy
};

SecondDifferences secondDifferences(const float* plane, int ns, int nt) {
  const std::size_t n = std::size_t(ns) * nt;
  SecondDifferences out{std::vector<float>(n), std::vector<float>(n), std::vector<float>(n)};
  parallelFor(0, std::size_t(nt), 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y) {
      const std::size_t up = y > 0 ? y - 1 : y, down = y + 1 < std::size_t(nt) ? y + 1 : y;
      for (int x = 0; x < ns; ++x) {
        const std::size_t p = y * ns + x;
        const int left = std::max(x - 1, 0), right = std::min(x + 1, ns - 1);
        const float ixx = plane[y * ns + left] - 2 * plane[p] + plane[y * ns + right];
        const float iyy = plane[up * ns + x] - 2 * plane[p] + plane[down * ns + x];
        out.xx[p] = ixx * ixx;
        out.yy[p] = iyy * iyy;
        out.xy[p] = 2 * ixx * iyy;
      }
    }
  });
  return out;
}

// The subsets of views with at least one view (all six unless the aperture is a single row or
// column), and how many views each has.
std::vector<int> subsetsWithViews(const std::vector<StarView>& views, int (&viewsIn)[kHalves]) {
  std::fill(viewsIn, viewsIn + kHalves, 0);
  for (const StarView& view : views)
    for (int h = 0; h < kHalves; ++h) viewsIn[h] += (view.halves >> h) & 1;
  std::vector<int> subsets;
  for (int h = 0; h < kHalves; ++h)
    if (viewsIn[h] > 0) subsets.push_back(h);
  return subsets;
}

// The correspondence cue for labels [labelBegin, labelEnd), n = ns * nt: the mean squared
// difference over each subset of views with views, out[((l - labelBegin) * subsets + i) * n + p]
// (subsetsWithViews' order). `locking` scales the interpolation-bias term removed (0: none); the
// noise variance that interpolation removes is added back (ViewNoise, interpolation_terms.hpp).
void correspondenceCost(const LightField& grey, const std::vector<double>& disparities, int labelBegin, int labelEnd,
                        double locking, const edof::ViewNoise& noise, bool fromReference, float* out) {
  const int ns = grey.ns(), nt = grey.nt();
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const std::vector<StarView> views = starViews(grey, referenceU, referenceV, fromReference);
  const double referenceUc = stepsU(grey, referenceU, fromReference),
               referenceVc = stepsV(grey, referenceV, fromReference);
  const std::size_t n = grey.shape().viewPixels();
  // The second differences only feed the interpolation-bias term.
  const SecondDifferences secondDiff =
      locking > 0 ? secondDifferences(grey.plane(referenceU, referenceV, 0), ns, nt) : SecondDifferences{};
  int viewsIn[kHalves];
  const std::vector<int> subsets = subsetsWithViews(views, viewsIn);

  double largestOffset = 0, largestDisparity = 0;
  for (const StarView& view : views) largestOffset = std::max({largestOffset, std::abs(view.uc), std::abs(view.vc)});
  for (double d : disparities) largestDisparity = std::max(largestDisparity, std::abs(d));
  const int pad = int(std::ceil(largestOffset * largestDisparity)) + 3;

  // Schedule: blocks of rows, every label and view inside a block, so that the accumulators
  // (4 x rows x ns floats) stay in cache while the views stream through.
  const int blockRows = 8;
  const std::size_t blocks = (std::size_t(nt) + blockRows - 1) / blockRows;
  parallelFor(0, blocks, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> padded(std::size_t(ns) + 2 * pad), sample(ns);
    const int channels = grey.channels();
    std::vector<float> reference(std::size_t(channels) * blockRows * ns);
    std::vector<float> accumulator(std::size_t(kHalves) * blockRows * ns);
    for (std::size_t block = begin; block < end; ++block) {
      const int y0 = int(block) * blockRows, y1 = std::min(nt, y0 + blockRows);
      for (int l = labelBegin; l < labelEnd; ++l) {
        const double d = disparities[l];
        // The reference view brought to the aperture centre's grid (no shift when it is the centre).
        for (int c = 0; c < channels; ++c)
          for (int y = y0; y < y1; ++y)
            edof::sampleShiftedRow(grey.plane(referenceU, referenceV, c), ns, nt, y, -referenceUc * d, -referenceVc * d,
                                   pad, padded.data(), reference.data() + (std::size_t(c) * blockRows + (y - y0)) * ns);
        std::fill(accumulator.begin(), accumulator.end(), 0.0f);
        for (const StarView& view : views) {
          for (int c = 0; c < channels; ++c)
            for (int y = y0; y < y1; ++y) {
              const float* referenceRow = reference.data() + (std::size_t(c) * blockRows + (y - y0)) * ns;
              edof::sampleShiftedRow(grey.plane(view.u, view.v, c), ns, nt, y, -view.uc * d, -view.vc * d, pad,
                                     padded.data(), sample.data());
              for (int h = 0; h < kHalves; ++h)
                if ((view.halves >> h) & 1)
                  accumulateSquaredDifference(sample.data(), referenceRow,
                                              accumulator.data() + (std::size_t(h) * blockRows + (y - y0)) * ns, ns);
            }
        }
        // The interpolation-bias weights of this label, and the noise it removes, per subset (mean
        // over its views).
        float wx[kHalves] = {}, wy[kHalves] = {}, wxy[kHalves] = {}, noiseLoss[kHalves] = {};
        const double referenceLoss = edof::interpolationNoiseLoss(noise, -referenceUc * d, -referenceVc * d);
        for (const StarView& view : views) {
          const double bx = edof::interpolationBlur(-view.uc * d), by = edof::interpolationBlur(-view.vc * d);
          const double loss = referenceLoss + edof::interpolationNoiseLoss(noise, -view.uc * d, -view.vc * d);
          for (int h = 0; h < kHalves; ++h)
            if ((view.halves >> h) & 1) {
              wx[h] += float(locking * bx * bx / viewsIn[h]);
              wy[h] += float(locking * by * by / viewsIn[h]);
              wxy[h] += float(locking * bx * by / viewsIn[h]);
              noiseLoss[h] += float(loss / viewsIn[h]);
            }
        }
        for (int y = y0; y < y1; ++y) {
          const std::size_t row = std::size_t(y) * ns;
          for (int x = 0; x < ns; ++x) {
            const float cxx = locking > 0 ? secondDiff.xx[row + x] : 0.0f,
                        cyy = locking > 0 ? secondDiff.yy[row + x] : 0.0f,
                        cxy = locking > 0 ? secondDiff.xy[row + x] : 0.0f;
            for (std::size_t i = 0; i < subsets.size(); ++i) {
              const int h = subsets[i];
              const float mean = accumulator[(std::size_t(h) * blockRows + (y - y0)) * ns + x] / viewsIn[h] -
                                 (wx[h] * cxx + wy[h] * cyy + wxy[h] * cxy) + noiseLoss[h];
              out[(std::size_t(l - labelBegin) * subsets.size() + i) * n + row + x] = mean;
            }
          }
        }
      }
    }
  });
}

// The best subset of views: at an occlusion boundary, the half-aperture that sees only the
// surface. out[p] = the lowest of `subsets` planes of n pixels, `stride` floats apart from `first`.
void lowestSubset(const float* first, std::size_t subsets, std::size_t stride, std::size_t n, float* out) {
  parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      float best = std::numeric_limits<float>::infinity();
      for (std::size_t i = 0; i < subsets; ++i) best = std::min(best, first[i * stride + p]);
      out[p] = std::isfinite(best) ? best : 0.0f;
    }
  });
}

// The centre row and the centre column of views are one-dimensional subsets: along an edge parallel
// to its baseline, a row's cost does not change with disparity, and as the lowest subset at every
// label it erases that edge's evidence (on noisy people at 256 px per view the optimiser then
// carried the backdrop's disparity into the checker card's flat squares, which only their edges
// place). So a one-dimensional subset joins the half-apertures' lowest cost, after aggregation,
// only at pixels where its cost has at least kOneDimensionalContrast times the contrast of theirs
// (mean less lowest over the slices), or where its lowest is below the lowest so far (theirs, and
// the row's if it joined) by more than kOneDimensionalNoiseMargin times the views' noise variance
// (ViewNoise; 0 for views matched as given), more than noise explains: a sheen or
// uneven light that views off the row see and the row does not (the steep, unevenly lit, glossy
// floor needs the row). Chosen on the development scenes, both sizes better: means of BadPix(0.07)
// 2.077 -> 1.986 % at 128 px per view, 2.353 -> 2.113 % at 256 (noisy people 18.54 -> 15.00 %;
// without: `depth_bench --no-one-dimensional-gate`).
// Measured with temporary switches, not kept: contrast share 0.3, 1: 2.014, 2.042 % at 128; margin
// 64: 1.969 and 2.133 %; the contrast alone (no margin) breaks that floor (2.89 -> 37.7 % at 128);
// the gate in the fine search only: 2.094 % at 128.
constexpr double kOneDimensionalContrast = 0.5, kOneDimensionalNoiseMargin = 16;

// Whether the gate above applies: asked for (`wanted`: DepthExperiment::oneDimensionalGate), and all
// four half-apertures and both one-dimensional subsets have views (subsetsWithViews' order puts the
// halves first).
bool gatesOneDimensional(const std::vector<int>& subsets, bool wanted) {
  return wanted && subsets == std::vector<int>{0, 1, 2, 3, 4, 5};
}

// Pixels [0, count) of `slices` planes n floats apart: each one's lowest value over the planes,
// and its contrast (mean less lowest). Loops over pixels inside loops over planes, which the
// compiler vectorises; per pixel the sums run over the planes in order.
LFCAM_CLONES void lowestAndContrast(const float* __restrict planes, int slices, std::size_t n, std::size_t count,
                                    float* __restrict least, double* __restrict contrast) {
  for (std::size_t i = 0; i < count; ++i) least[i] = planes[i], contrast[i] = 0;
  for (int k = 0; k < slices; ++k) {
    const float* plane = planes + std::size_t(k) * n;
    for (std::size_t i = 0; i < count; ++i) contrast[i] += plane[i], least[i] = std::min(least[i], plane[i]);
  }
  for (std::size_t i = 0; i < count; ++i) contrast[i] = contrast[i] / slices - least[i];
}

// Steps 3 and 5: the lowest aggregated cost per pixel and slice, `slices` planes of n pixels in
// `lowest` holding the half-apertures' lowest on entry; `oneDimensional`: each such subset's
// planes, n floats apart. Each joins the lowest where the gate above lets it.
void joinOneDimensional(float* lowest, const std::vector<const float*>& oneDimensional, int slices, std::size_t n,
                        double noiseVariance) {
  constexpr std::size_t kBlock = 256;  // pixels at a time: the slices' rows of a block stay in cache
  parallelFor(0, (n + kBlock - 1) / kBlock, 4, [&](std::size_t begin, std::size_t end) {
    float halvesLowest[kBlock], ownLowest[kBlock];
    double halvesContrast[kBlock], ownContrast[kBlock], lowestSoFar[kBlock];
    bool joins[kBlock];
    for (std::size_t block = begin; block < end; ++block) {
      const std::size_t first = block * kBlock, count = std::min(kBlock, n - first);
      lowestAndContrast(lowest + first, slices, n, count, halvesLowest, halvesContrast);
      for (std::size_t i = 0; i < count; ++i) lowestSoFar[i] = halvesLowest[i];
      for (const float* planes : oneDimensional) {
        lowestAndContrast(planes + first, slices, n, count, ownLowest, ownContrast);
        for (std::size_t i = 0; i < count; ++i) {
          joins[i] = !(ownContrast[i] < kOneDimensionalContrast * halvesContrast[i] &&
                       lowestSoFar[i] - ownLowest[i] <= kOneDimensionalNoiseMargin * noiseVariance);
          if (joins[i]) lowestSoFar[i] = std::min(lowestSoFar[i], double(ownLowest[i]));
        }
        for (int k = 0; k < slices; ++k) {
          float* target = lowest + std::size_t(k) * n + first;
          const float* own = planes + std::size_t(k) * n + first;
          for (std::size_t i = 0; i < count; ++i)
            if (joins[i]) target[i] = std::min(target[i], own[i]);
        }
      }
    }
  });
}

// Aggregation: each of `count` planes of n pixels replaced by its guided filter, in parallel.
void aggregatePlanes(const edof::GuidedFilter& filter, float* planes, std::size_t count, std::size_t n) {
  parallelFor(0, count, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> filtered(n);
    edof::GuidedFilter::Scratch scratch;
    for (std::size_t k = begin; k < end; ++k) {
      filter.apply(planes + k * n, filtered.data(), scratch);
      std::copy(filtered.begin(), filtered.end(), planes + k * n);
    }
  });
}

// The defocus cue's ceiling, as a multiple of the centre view's own squared Laplacian (below).
// Chosen on the development scenes at 128 and 256 px per view, before the slanted median: 1.5, 2
// and 3 gave means of 2.43, 2.45 and 2.59 % at 128 (the steep weak-textured floor and wall 4.11,
// 3.86, 5.35 %) and 3.65, 3.56, 3.41 % at 256 (none: 3.02 and 3.55 %).
constexpr float kDefocusCeiling = 2.0f;

// The defocus cue at each disparity d: the squared Laplacian of the full-aperture photograph, at most
// kDefocusCeiling times the centre view's (`centreEnergy`). Refocusing averages shifted copies of
// the views, so it cannot make a Lambertian scene sharper than the centre view, whose small
// aperture has everything in focus. Yet a photograph refocused far from a strong edge shows it
// as a staircase of shifted copies, one per row or column of views (the aperture is sampled, not
// continuous), whose Laplacian spills onto weak texture beside it and outweighs the texture's own:
// without the ceiling, a weakly textured floor and wall slanted by 0.04 px per pixel before a
// strongly textured backdrop took the range's nearest label along the backdrop's edge (11.98 %
// BadPix(0.07), with it 3.86 %, when it was chosen; since the cleanup follows slopes, which mends
// most of that, 1.26 against 0.96 %: `depth_bench --development-only --no-defocus-ceiling`).
// Without `centreEnergy`, no ceiling (DepthExperiment::defocusCeiling). Returns energy[l * n + p],
// the photographs refocused as a focal stack.
edof::CostVolume defocusEnergy(const LightField& grey, const std::vector<double>& disparities,
                               const float* centreEnergy) {
  const std::size_t n = grey.shape().viewPixels();
  edof::CostVolume energy(n * disparities.size());
  refocusEach(grey, disparities, [&](std::size_t l, Image&& photo) {
    float* out = energy.data() + l * n;
    edof::squaredLaplacian(photo, out);
    if (centreEnergy)
      for (std::size_t p = 0; p < n; ++p) out[p] = std::min(out[p], kDefocusCeiling * centreEnergy[p]);
  });
  return energy;
}

// Steps 2-3: per label, the correspondence cost of each subset of views less the defocus cue,
// aggregated, and the lowest subset kept. With `subsetsApart` each subset's slice is aggregated
// before the lowest is taken (the guided filter is linear, so the defocus cue is aggregated as
// on its own), as the fine search does (refineDisparity), and the one-dimensional subsets join
// it where joinOneDimensional lets them; else the lowest is taken per pixel first. `ceiling`: the
// defocus cue capped (defocusEnergy). Labels go in chunks so that only chunk x subsets slices are
// held besides the volume and the one-dimensional subsets' volumes; `gateWanted`: joinOneDimensional's
// (gatesOneDimensional). Returns cost[l * n + p].
edof::CostVolume aggregatedCost(const LightField& grey, const std::vector<double>& disparities,
                                const edof::GuidedFilter& filter, double defocusWeight, double locking,
                                const edof::ViewNoise& noise, bool subsetsApart, bool ceiling, bool gateWanted,
                                bool fromReference) {
  const std::size_t n = grey.shape().viewPixels();
  const int labels = int(disparities.size());
  int viewsIn[kHalves];
  const std::vector<int> subsetList =
      subsetsWithViews(starViews(grey, (grey.nu() - 1) / 2, (grey.nv() - 1) / 2, fromReference), viewsIn);
  const std::size_t subsets = subsetList.size();
  const bool gate = subsetsApart && gatesOneDimensional(subsetList, gateWanted);
  // The halves first (gatesOneDimensional), then the one-dimensional subsets, each a whole volume.
  const std::size_t halves = gate ? 4 : subsets;
  std::vector<edof::CostVolume> oneDimensional;
  for (std::size_t j = halves; j < subsets; ++j) oneDimensional.emplace_back(n * labels);
  constexpr int kChunk = 4;
  edof::CostVolume cost(n * labels), planes(std::size_t(kChunk) * subsets * n);
  std::vector<float> centreEnergy(n);
  if (defocusWeight > 0 && ceiling)
    edof::squaredLaplacian(grey.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2), centreEnergy.data());
  const edof::CostVolume energy = defocusWeight > 0
                                      ? defocusEnergy(grey, disparities, ceiling ? centreEnergy.data() : nullptr)
                                      : edof::CostVolume();
  for (int first = 0; first < labels; first += kChunk) {
    const int last = std::min(labels, first + kChunk);
    correspondenceCost(grey, disparities, first, last, locking, noise, fromReference, planes.data());
    if (!subsetsApart)
      for (int l = first; l < last; ++l)
        lowestSubset(planes.data() + std::size_t(l - first) * subsets * n, subsets, n, n,
                     cost.data() + std::size_t(l) * n);
    // The slices the defocus cue is taken from and the guided filter applied to.
    const std::size_t perLabel = subsetsApart ? subsets : 1;
    auto slice = [&](int l, std::size_t i) {
      return subsetsApart ? planes.data() + (std::size_t(l - first) * subsets + i) * n
                          : cost.data() + std::size_t(l) * n;
    };
    if (defocusWeight > 0)
      for (int l = first; l < last; ++l) {
        const float weight = float(defocusWeight);
        const float* labelEnergy = energy.data() + std::size_t(l) * n;
        parallelFor(0, perLabel, 1, [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) {
            float* target = slice(l, i);
            for (std::size_t p = 0; p < n; ++p) target[p] -= weight * labelEnergy[p];
          }
        });
      }
    aggregatePlanes(filter, slice(first, 0), std::size_t(last - first) * perLabel, n);
    if (subsetsApart)
      for (int l = first; l < last; ++l) {
        lowestSubset(slice(l, 0), halves, n, n, cost.data() + std::size_t(l) * n);
        for (std::size_t j = 0; j < oneDimensional.size(); ++j)
          std::copy(slice(l, halves + j), slice(l, halves + j) + n, oneDimensional[j].data() + std::size_t(l) * n);
      }
  }
  if (gate)
    joinOneDimensional(cost.data(), {oneDimensional[0].data(), oneDimensional[1].data()}, labels, n, noise.variance);
  return cost;
}

// The fine search's views for its row kernel: the reference first, then the star views, each
// counting in the subsets (subsetsWithViews' order) of its halves.
edof::FineCostViews fineCostViews(const LightField& grey, const std::vector<StarView>& views,
                                  const std::vector<int>& subsets, const int (&viewsIn)[kHalves], double locking,
                                  const SecondDifferences& secondDiff, const edof::ViewNoise& noise,
                                  bool fromReference) {
  edof::FineCostViews out{.ns = grey.ns(), .nt = grey.nt(), .channels = grey.channels()};
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const auto add = [&](int u, int v, unsigned inSubsets) {
    for (int c = 0; c < grey.channels(); ++c) out.planes.push_back(grey.plane(u, v, c));
    out.uc.push_back(stepsU(grey, u, fromReference));
    out.vc.push_back(stepsV(grey, v, fromReference));
    out.subsets.push_back(inSubsets);
  };
  add(referenceU, referenceV, 0);
  for (const StarView& view : views) {
    unsigned inSubsets = 0;
    for (std::size_t i = 0; i < subsets.size(); ++i) inSubsets |= unsigned((view.halves >> subsets[i]) & 1) << i;
    add(view.u, view.v, inSubsets);
  }
  for (int h : subsets) out.viewsIn.push_back(viewsIn[h]);
  out.locking = locking;
  out.xx = secondDiff.xx.data(), out.yy = secondDiff.yy.data(), out.xy = secondDiff.xy.data();
  out.noise = noise;
  return out;
}

// Fine search around a disparity map: the correspondence cost (as correspondenceCost) at
// disparity + k delta per pixel, k in [-steps, steps], each slice aggregated by `filter`, then
// the lowest with a parabola through its neighbours. Slices follow the map, so a window averages
// costs of neighbouring pixels at the same offset from their own disparities: a slanted surface
// stays sharp where fixed labels would step. With `aggregateHalves`, each subset's cost is
// aggregated on its own and the best subset taken per slice afterwards: a window then keeps to one
// subset, where the minimum of per-pixel costs picks whichever subset is lowest by chance at each
// pixel (measured on antinous, fine-search radius 8: BadPix(0.07) 14.2 -> 11.5 %, BadPix(0.03)
// 40.1 -> 28.9 %; issue 6, commit 0915025). Each pixel samples the views at its own disparity, so
// the cost is made a row of one slice at a time by fineCostRow (fine_cost_row.hpp), SIMD across
// the row, rather than from shifted rows as correspondenceCost's.
void refineDisparity(const LightField& grey, const edof::GuidedFilter& filter, float* disparity, double delta,
                     int steps, double locking, const edof::ViewNoise& noise, bool aggregateHalves, bool gateWanted,
                     bool fromReference, float* curvatureOut, float* residualOut) {
  const int ns = grey.ns(), nt = grey.nt();
  const std::size_t n = grey.shape().viewPixels();
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const std::vector<StarView> views = starViews(grey, referenceU, referenceV, fromReference);
  int viewsIn[kHalves];
  const std::vector<int> subsets = subsetsWithViews(views, viewsIn);
  const int slices = 2 * steps + 1;
  edof::CostVolume cost(n * slices);
  // Subset i and slice k in plane i * slices + k.
  edof::CostVolume subsetCost(subsets.size() * slices * n);
  const SecondDifferences secondDiff =
      locking > 0 ? secondDifferences(grey.plane(referenceU, referenceV, 0), ns, nt) : SecondDifferences{};
  const edof::FineCostViews fineViews =
      fineCostViews(grey, views, subsets, viewsIn, locking, secondDiff, noise, fromReference);
  parallelFor(0, std::size_t(nt), 4, [&](std::size_t begin, std::size_t end) {
    std::vector<float*> out(subsets.size());
    for (std::size_t y = begin; y < end; ++y)
      for (int k = 0; k < slices; ++k) {
        for (std::size_t i = 0; i < subsets.size(); ++i) out[i] = subsetCost.data() + (i * slices + k) * n + y * ns;
        edof::fineCostRow(fineViews, int(y), disparity + y * ns, (k - steps) * delta, out.data());
      }
  });
  // Every subset's slices aggregated, then the lowest subset per slice; or the lowest first.
  if (aggregateHalves) aggregatePlanes(filter, subsetCost.data(), subsets.size() * slices, n);
  const bool gate = aggregateHalves && gatesOneDimensional(subsets, gateWanted);
  for (int k = 0; k < slices; ++k)
    lowestSubset(subsetCost.data() + std::size_t(k) * n, gate ? 4 : subsets.size(), std::size_t(slices) * n, n,
                 cost.data() + std::size_t(k) * n);
  if (gate)
    joinOneDimensional(cost.data(), {subsetCost.data() + 4 * slices * n, subsetCost.data() + 5 * slices * n}, slices, n,
                       noise.variance);
  if (!aggregateHalves) aggregatePlanes(filter, cost.data(), std::size_t(slices), n);
  parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      int best = 0;
      for (int k = 1; k < slices; ++k)
        if (cost[std::size_t(k) * n + p] < cost[std::size_t(best) * n + p]) best = k;
      double offset = 0, curvature = 0;
      if (best > 0 && best + 1 < slices) {
        const double left = cost[std::size_t(best - 1) * n + p], centre = cost[std::size_t(best) * n + p],
                     right = cost[std::size_t(best + 1) * n + p];
        curvature = left - 2 * centre + right;
        offset = parabolaVertex(left, centre, right);
      }
      disparity[p] += float((best - steps + offset) * delta);
      curvatureOut[p] = float(std::max(curvature, 0.0));
      residualOut[p] = cost[std::size_t(best) * n + p];
    }
  });
}

// Edge-aware fill of the pixels whose fine search was unsure (depth.hpp, step 6): each disparity
// weighted by the curvature of its fine-search cost at the minimum (flat where there is no
// texture) over the cost left there (high where no disparity makes the views agree, as at
// occlusions), both relative to their means; the fast global smoother guided by the centre view
// in colour, so that edges of hue separate surfaces as well as edges of brightness. Its strength
// (DepthOptions::fillLambda) chosen on the development scenes once the cleanup followed slopes:
// 0.15, 0.25, 0.35, 0.5 gave means of 1.88, 1.86, 1.89, 1.93 % at 128 px per view and 3.25, 3.23,
// 3.24, 3.30 % at 256 (longer reaches, 5 to 500, were worse in an earlier round).
void fillUncertain(const Image& guide, const std::vector<float>& curvature, const std::vector<float>& residual,
                   const DepthOptions& options, float* disparity) {
  const std::size_t n = std::size_t(guide.width()) * guide.height();
  double meanCurvature = 0, meanResidual = 0;
  for (std::size_t p = 0; p < n; ++p) meanCurvature += curvature[p], meanResidual += std::max(residual[p], 0.0f);
  meanCurvature = std::max(meanCurvature / double(n), 1e-20);
  meanResidual = std::max(meanResidual / double(n), 1e-20);
  std::vector<float> confidence(n);
  for (std::size_t p = 0; p < n; ++p)
    confidence[p] = float(curvature[p] / meanCurvature / (std::max(residual[p], 0.0f) / meanResidual + 0.5));
  edof::globalSmooth(guide.plane(0), guide.channels(), guide.width(), guide.height(), confidence.data(), disparity,
                     float(options.fillLambda), float(std::max(options.fillSigma, 1e-6)), /*iterations=*/3);
}

// The cost volume's veto of the occlusion edges' reclaim (depthStages), asked after the first round,
// and in the first for parts narrower than the band only. The margin, for the later rounds, chosen
// on the development scenes as the only one not worse at either size: mean BadPix(0.07) without the
// veto 2.37 % at 128 px per view, 2.77 % at 256 (`depth_bench --no-reclaim-cost-check [--size 256]`);
// margin 1: 2.21, 2.77 % (`--no-first-round-cost-check`; narrow near parts 15.4 -> 12.7 % at 128,
// 6.0 -> 5.4 % at 256). Measured with a temporary switch, not kept: margin 0.5:
// 2.18, 2.82 %; 2: 2.37, 2.76 %; the same veto for every pixel of the first round too: 2.00 and
// 2.82 % (the glossy weak card 8.8 -> 10.6 % at 256: there the aggregated cost itself carries the
// fattening the first reclaim removes).
constexpr double kReclaimCostMargin = 1.0;

// A plane's gradient times `scale`, by central differences (the border pixels repeated beyond it).
void centralDifferences(const float* in, int ns, int nt, float scale, float* dx, float* dy) {
  for (int y = 0; y < nt; ++y) {
    const float *row = in + std::size_t(y) * ns, *up = in + std::size_t(std::max(y - 1, 0)) * ns,
                *down = in + std::size_t(std::min(y + 1, nt - 1)) * ns;
    for (int x = 0; x < ns; ++x) {
      dx[std::size_t(y) * ns + x] = 0.5f * scale * (row[std::min(x + 1, ns - 1)] - row[std::max(x - 1, 0)]);
      dy[std::size_t(y) * ns + x] = 0.5f * scale * (down[x] - up[x]);
    }
  }
}

// A half-resolution plane (each pixel the mean of 2 x 2) at full-resolution pixel (x, y), bilinear.
double sampleHalfResolution(const float* half, int halfWidth, int halfHeight, int x, int y) {
  return bilinearSample(half, halfWidth, halfHeight, 0.5 * x - 0.25, 0.5 * y - 0.25);
}

// An aggregated cost volume at half the resolution (ns x nt, the same labels): that of the view
// offsets' last half-resolution map (estimateDepth), whose views have a quarter of the noise variance.
struct CoarseCost {
  edof::CostVolume volume;
  int ns = 0, nt = 0;
};

// Noisy views (the automatic prefilter's second match): the coarse cost, upsampled, added to the
// full resolution's with a weight of kNoisyCoarseWeight where the centre view has no texture above
// its noise, less where it has (1 / (1 + texture / (kNoisyCoarseTexture noise))), texture the mean
// squared gradient over a box of radius 2 less the noise's share. At twice the pixels per view,
// Lytro-like noise outweighs the texture of weakly textured regions in the full resolution's cost,
// and its minimum wanders there (blobs of error on the noisy people's backdrop), while the coarse
// cost, averaged over 2 x 2 pixels before matching, still has the texture's minimum; where texture
// is strong the full resolution's keeps its edges. Chosen on the development scenes' four noisy
// ones at 128 and 256 px per view among weights 0.25, 0.5 and 1 everywhere and 0.5 and 1 gated by
// 0.25, 1 and 4; kept as the only one better at both sizes (design.md, "Depth").
constexpr double kNoisyCoarseWeight = 0.5, kNoisyCoarseTexture = 0.25;

void addCoarseCost(const CoarseCost& coarse, const LightField& grey, const edof::ViewNoise& noise,
                   edof::CostVolume& cost) {
  const int ns = grey.ns(), nt = grey.nt(), labels = int(cost.size() / grey.shape().viewPixels());
  const std::size_t n = grey.shape().viewPixels();
  const Image centre = grey.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2);
  std::vector<float> dx(n), dy(n), energy(n), texture(n), weight(n);
  centralDifferences(centre.plane(0), ns, nt, 1.0f, dx.data(), dy.data());
  for (std::size_t p = 0; p < n; ++p) energy[p] = dx[p] * dx[p] + dy[p] * dy[p];
  boxFilter(energy.data(), texture.data(), ns, nt, 2);
  for (std::size_t p = 0; p < n; ++p) {
    const double signal = std::max(double(texture[p]) - noise.variance, 0.0);
    weight[p] = float(kNoisyCoarseWeight / (1 + signal / (kNoisyCoarseTexture * noise.variance)));
  }
  parallelFor(0, std::size_t(labels), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      const float* half = coarse.volume.data() + l * std::size_t(coarse.ns) * coarse.nt;
      float* full = cost.data() + l * n;
      for (int y = 0; y < nt; ++y)
        for (int x = 0; x < ns; ++x) {
          const std::size_t p = std::size_t(y) * ns + x;
          full[p] += weight[p] * sampleHalfResolution(half, coarse.ns, coarse.nt, x, y);
        }
    }
  });
}

// How much the views disagree at the map a fine search found: its cost at the minimum per pixel
// (the mean squared difference between the views there) and the median over pixels; empty and 0
// without a fine search.
struct Residual {
  std::vector<float> perPixel;
  double median = 0;
};

// Stages 2-7 (depth.hpp) on `grey`, the sRGB luminance the views are matched on, steered by
// `guide` (its centre view before any prefilter) and `colours`, the centre view's sRGB colours.
// `noise`: that of `grey`'s samples, whose loss under interpolation the costs add back.
// `residual`: the first fine search's. `coarseIn`: the half resolution's cost, added on noisy views
// (addCoarseCost); `coarseOut`: this one's aggregated cost, `coarseIn`'s added.
DepthMap depthStages(const Image& colours, const LightField& grey, const Image& guide,
                     const std::vector<double>& disparities, const DepthOptions& options,
                     const edof::DepthExperiment& experiment, const edof::ViewNoise& noise, Residual* residualOut,
                     const CoarseCost* coarseIn = nullptr, CoarseCost* coarseOut = nullptr) {
  const int ns = grey.ns(), nt = grey.nt(), labels = int(disparities.size());
  const std::size_t n = grey.shape().viewPixels();
  const double dmin = disparities.front(), dmax = disparities.back(), step = (dmax - dmin) / (labels - 1);
  const edof::GuidedFilter filter(guide.plane(0), ns, nt, std::max(options.filterRadius, 0),
                                  std::max(options.filterEpsilon, 1e-12));
  const double locking = std::max(experiment.lockingCorrection, 0.0);
  // A map of labels (fractional between them) in disparity.
  const auto writeDisparities = [&](const std::vector<float>& labelOf, Image& map) {
    for (std::size_t p = 0; p < n; ++p) map.plane(0)[p] = float(dmin + labelOf[p] * step);
  };
  // 2. Cost: the correspondence cue over each subset of views, less the defocus cue (the
  // full-aperture photograph at each label, sharpest where it is right); 3. aggregation: guided
  // filter per slice, steered by the reference view; the lowest subset.
  edof::CostVolume cost =
      aggregatedCost(grey, disparities, filter, options.defocusWeight, locking, noise, experiment.aggregateSubsetsApart,
                     experiment.defocusCeiling, experiment.oneDimensionalGate, experiment.matchAtReference);
  if (coarseIn && !coarseIn->volume.empty() && noise.variance > 0 && experiment.noisyCoarseCost)
    addCoarseCost(*coarseIn, grey, noise, cost);

  // Pixel-major for the optimisation; and the typical depth of a cost minimum (mean over pixels
  // of mean - min), the scale of the penalties and of the confidence.
  edof::CostVolume volume(n * labels);
  parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p)
      for (int l = 0; l < labels; ++l) volume[p * labels + l] = cost[std::size_t(l) * n + p];
  });
  if (experiment.observeStage) {
    std::vector<float> lowest(n);
    edof::winnerTakesAll(volume, ns, nt, labels, lowest.data());
    Image map(ns, nt, 1);
    writeDisparities(lowest, map);
    experiment.observeStage("cost", map);
  }
  if (coarseOut) *coarseOut = {std::move(cost), ns, nt};  // no longer needed here: handed over, not copied
  cost.clear();
  cost.shrink_to_fit();
  // Each pixel's mean cost and contrast (mean less lowest), summed in pixel order.
  std::vector<float> meanCost(n), contrast(n);
  parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      const float* c = &volume[p * labels];
      double sum = 0;
      float lowest = c[0];
      for (int l = 0; l < labels; ++l) sum += c[l], lowest = std::min(lowest, c[l]);
      meanCost[p] = float(sum / labels);
      contrast[p] = meanCost[p] - lowest;
    }
  });
  double contrastSum = 0;
  for (std::size_t p = 0; p < n; ++p) contrastSum += contrast[p];
  const double scale = std::max(contrastSum / double(n), 1e-12);

  // 4. Regularisation: semi-global optimisation, then the read-out between labels.
  std::vector<float> label(n);
  // Penalties that follow the cost's contrast near each pixel: image-wide ones outweigh the faint
  // evidence of weak texture, so a confident surface's disparity runs over a weakly textured one
  // beside it for as long as that evidence takes to add up to a jump (halos several pixels wide
  // where texture is coarse). Each pixel's costs are scaled by sqrt(image contrast / local
  // contrast), the penalties' scale the geometric mean of both; the parabola below does not see
  // the scaling, the confidence undoes it.
  std::vector<float> gain(n, 1.0f);
  if (options.smoothness > 0 && options.contrastRadius > 0) {
    std::vector<float> local(n);
    boxFilter(contrast.data(), local.data(), ns, nt, options.contrastRadius);
    parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t p = begin; p < end; ++p) {
        gain[p] = float(std::sqrt(scale / std::max(double(local[p]), 1e-3 * scale)));
        for (int l = 0; l < labels; ++l) volume[p * labels + l] *= gain[p];
      }
    });
  }
  if (options.smoothness > 0) {
    // A small step penalty: slanted surfaces climb one label at a time (the fine search below
    // then smooths the steps); a large one for jumps, lowered across intensity edges.
    const float p1 = float(0.01 * scale * options.smoothness), p2 = float(0.6 * scale * options.smoothness);
    const edof::CostVolume summed =
        edof::semiGlobalMatching(volume, ns, nt, labels, guide.plane(0), p1, p2, /*edgeScale=*/0.01f);
    edof::winnerTakesAll(summed, ns, nt, labels, label.data());
    // Between labels: the parabola through the aggregated (not optimised) cost around the
    // optimiser's label, whose curve is not flattened by the penalties.
    parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t p = begin; p < end; ++p) {
        const int best = std::clamp(int(std::lround(label[p])), 0, labels - 1);
        const float* c = &volume[p * labels];
        double offset = 0;
        if (best > 0 && best + 1 < labels) offset = parabolaVertex(c[best - 1], c[best], c[best + 1]);
        label[p] = float(best + offset);
      }
    });
  } else {
    edof::winnerTakesAll(volume, ns, nt, labels, label.data());
  }

  DepthMap result{Image(ns, nt, 1), Image(ns, nt, 1), dmin, dmax, labels};
  // The fine search may step past the ends of the range searched, and the cleanup, carrying
  // disparities along slopes, reach past them; the map stays inside it.
  const auto keepInRange = [&] {
    for (std::size_t p = 0; p < n; ++p)
      result.disparity.plane(0)[p] = std::clamp(result.disparity.plane(0)[p], float(dmin), float(dmax));
  };
  writeDisparities(label, result.disparity);
  const auto observe = [&](const std::string& stage) {
    if (experiment.observeStage) experiment.observeStage(stage, result.disparity);
  };
  observe("optimised");
  // The cost volume's word on a move of the occlusion edges' reclaim: its aggregated cost (as the
  // optimisation saw it) at the farther disparity may exceed that at the pixel's own by at most
  // kReclaimCostMargin times the pixel's cost contrast. Run again from the boundary the first round
  // left, the reclaim ate narrow near parts of the background's colour (a finger's width within its
  // band), which the cost, on their texture, tells apart. In the first round only for a part
  // narrower than the band (no voter of its own surface beyond it): elsewhere the first reclaim
  // removes fattening that the aggregated cost carries too (development means 2.21 -> 2.02 % at 128
  // px per view, 2.78 -> 2.61 % at 256: narrow near parts 12.7 -> 9.1 % and 5.4 -> 4.0 %, the glossy
  // weak card 8.9 -> 7.1 % at 256; without: `depth_bench --no-first-round-cost-check`).
  const auto costAllows = [&](std::size_t p, float from, float to) {
    const float* c = &volume[p * labels];
    const auto at = [&](float d) {
      const double l = std::clamp((d - dmin) / step, 0.0, double(labels - 1));
      const int i = std::min(int(l), labels - 2);
      return c[i] + (l - i) * (c[i + 1] - c[i]);
    };
    const double scaledContrast = gain[p] * meanCost[p] - *std::min_element(c, c + labels);
    return at(to) - at(from) <= kReclaimCostMargin * scaledContrast;
  };
  // 5-6. Refinement and cleanup, `refineRounds` times: each round's fine search starts from the
  // map the previous round cleaned, a window's slices then follow the surface where the first
  // round's outliers (a slant's far end, a curved surface's outline) had bent them, and searches
  // at half the previous spacing (two rounds against one: development means 1.98 -> 1.65 % at
  // 128 px, 3.02 -> 2.60 % at 256; a third round at a quarter: 1.94 % at 128).
  std::vector<float> curvature(n, 1.0f), residual(n, 0.0f);
  *residualOut = {};
  const edof::GuidedFilter refineFilter(guide.plane(0), ns, nt, std::max(options.refineRadius, 0),
                                        std::max(options.filterEpsilon, 1e-12));
  const int rounds = options.refineSteps > 0 ? std::max(options.refineRounds, 1) : 1;
  for (int round = 0; round < rounds; ++round) {
    float* map = result.disparity.plane(0);
    // 5. Refinement: the fine search around the map.
    if (options.refineSteps > 0) {
      // Slices that follow a smoothed map: the fine search moves a whole window by one offset, so
      // it keeps the optimised map's own steps (labels climbing a slanted surface); a local fit
      // follows the slant without them. Only where it stays within a label of the map, so
      // occlusion edges keep their jumps (measured on antinous: floor 5.4 -> 4.5 points of
      // BadPix(0.07)). A quadratic fit, not a mean: a mean sags on a curved surface (a column, a
      // face) towards its far side, and the search, a fraction of a label wide, keeps some of that
      // (development scenes 1.81 -> 1.79 % at 128 px, 3.05 -> 3.00 % at 256; BadPix(0.03) 5.60 ->
      // 5.29 and 8.55 -> 7.89 %). Later rounds start from a cleaned map, which has no steps.
      if (round == 0 && options.refineSmoothRadius > 0) {
        std::vector<float> smooth(n);
        quadraticFitFilter(map, smooth.data(), ns, nt, options.refineSmoothRadius);
        for (std::size_t p = 0; p < n; ++p)
          if (std::abs(smooth[p] - map[p]) <= step) map[p] = smooth[p];
      }
      // A quarter of the correction in the fine search: its slices, a fraction of a label apart,
      // see far smaller differences of blur (measured on antinous: 1 there is worse than none).
      refineDisparity(grey, refineFilter, map, step / options.refineSteps / double(1 << round), options.refineSteps,
                      0.25 * std::max(experiment.lockingCorrection, 0.0), noise, experiment.refineAggregateHalves,
                      experiment.oneDimensionalGate, experiment.matchAtReference, curvature.data(), residual.data());
      keepInRange();
      observe("refined " + std::to_string(round + 1));
      // The first round's residual, the one the automatic prefilter's threshold was chosen on.
      if (round == 0) {
        std::vector<float> sorted(residual);
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        *residualOut = {residual, sorted[sorted.size() / 2]};
      }
    }
    // 6. Cleanup: the edge-aware fill, occlusion edges, the weighted median, each guided by the
    // centre view's sRGB colours.
    if (options.fillLambda > 0 && options.refineSteps > 0) fillUncertain(colours, curvature, residual, options, map);
    observe("filled " + std::to_string(round + 1));
    if (round == 0 || experiment.reclaimEveryRound) {
      const bool checked = experiment.reclaimCostCheck && labels > 1 && (round > 0 || experiment.firstRoundCostCheck);
      edof::reclaimOcclusionEdges(colours, options.occlusionBand, experiment.slantedCleanup, map,
                                  [&](std::size_t p, float from, float to, int ownVoters) {
                                    return !checked || (round == 0 && ownVoters > 0) || costAllows(p, from, to);
                                  });
    }
    observe("reclaimed " + std::to_string(round + 1));
    if (options.medianRadius > 0)
      edof::guidedWeightedMedian(colours, options.medianRadius, float(std::max(options.medianSigma, 1e-6)),
                                 experiment.slantedCleanup, map);
    keepInRange();
    observe("median " + std::to_string(round + 1));
  }
  // 7. Confidence.
  for (std::size_t p = 0; p < n; ++p) {
    const int chosen = std::clamp(int(std::lround(label[p])), 0, labels - 1);
    const double depthOfMinimum = meanCost[p] - volume[p * labels + chosen] / gain[p];
    result.confidence.plane(0)[p] = float(std::clamp(1.0 - std::exp(-std::max(depthOfMinimum, 0.0) / scale), 0.0, 1.0));
  }
  return result;
}

// Automatic prefilter (DepthOptions::prefilterSigma -1): the views count as noisy when the fine
// search's median residual (DepthMap::viewResidual) exceeds kNoisyResidual, the geometric middle
// between the development scenes without noise (up to 7.5e-6) and those with Lytro-like noise
// (from 2.4e-4; pixel-scale texture reads as noisy too); they are then smoothed by
// kNoisyPrefilterSigma, chosen on the development scenes (`depth_bench` prints both per scene).
constexpr double kNoisyResidual = 4e-5, kNoisyPrefilterSigma = 0.55;

// The share of a view's noise variance that bilinear sampling keeps, V kept(fx) kept(fy), averaged
// over the labels: with the fractions of the shifts spread evenly, 2/3 along an axis the view is
// shifted on (`uc`, `vc` view steps from where the views are matched) and 1 along one it is not.
double meanKept(double uc, double vc) { return (uc != 0 ? 2.0 / 3 : 1.0) * (vc != 0 ? 2.0 / 3 : 1.0); }

// The noise of views smoothed by a Gaussian of `sigma`, from `residual`, the median cost of their
// match as given: at the right disparity, the noise variance V kept by the reference's samples
// (`referenceKept`: 1 unless it is resampled, as with an even number of views matched at the
// aperture centre) plus that kept by an interpolated view's, so the residual is V (referenceKept +
// the mean kept over the star's views). Smoothing multiplies the variance by the sum of the squared
// taps along each axis and correlates neighbours.
edof::ViewNoise smoothedNoise(double residual, double sigma, const std::vector<StarView>& views, double referenceKept) {
  double kept = 0;
  for (const StarView& view : views) kept += meanKept(view.uc, view.vc);
  kept /= double(std::max<std::size_t>(views.size(), 1));
  const std::vector<float> taps = edof::gaussianTaps(sigma);
  double lag0 = 0, lag1 = 0;
  for (std::size_t i = 0; i < taps.size(); ++i) {
    lag0 += double(taps[i]) * taps[i];
    if (i + 1 < taps.size()) lag1 += double(taps[i]) * taps[i + 1];
  }
  return {residual / (referenceKept + kept) * lag0 * lag0, lag1 / lag0};
}

// The matching light field of DepthExperiment::gradientWeight a: channels sqrt(1 - a) I,
// sqrt(a) dI/dx, sqrt(a) dI/dy (central differences), so that the squared difference summed over
// channels is (1 - a) dI^2 + a |d grad I|^2.
LightField withGradients(const LightField& grey, double weight) {
  LightFieldShape shape = grey.shape();
  shape.channels = 3;
  LightField out(shape);
  out.metadata = grey.metadata;
  const int ns = grey.ns(), nt = grey.nt();
  const float intensity = float(std::sqrt(1 - weight)), gradient = float(std::sqrt(weight));
  parallelFor(0, shape.views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const int u = int(view % grey.nu()), v = int(view / grey.nu());
      const float* in = grey.plane(u, v, 0);
      float* level = out.plane(u, v, 0);
      for (std::size_t p = 0; p < grey.shape().viewPixels(); ++p) level[p] = intensity * in[p];
      centralDifferences(in, ns, nt, gradient, out.plane(u, v, 1), out.plane(u, v, 2));
    }
  });
  return out;
}

// A plane of width x height at half the resolution (means of 2x2 pixels; an odd last row or
// column left out): where the first maps of the view offsets are made.
void halvePlane(const float* in, int width, int height, float* out) {
  for (int y = 0; y < height / 2; ++y)
    for (int x = 0; x < width / 2; ++x) {
      const float* p = in + std::size_t(2 * y) * width + 2 * x;
      out[std::size_t(y) * (width / 2) + x] = 0.25f * (p[0] + p[1] + p[width] + p[width + 1]);
    }
}

LightField halfResolution(const LightField& in) {
  LightFieldShape shape = in.shape();
  shape.ns /= 2, shape.nt /= 2;
  LightField out(shape);
  out.metadata = in.metadata;
  parallelFor(0, shape.views() * std::size_t(shape.channels), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t index = begin; index < end; ++index) {
      const int c = int(index % std::size_t(shape.channels));
      const std::size_t view = index / std::size_t(shape.channels);
      const int u = int(view % in.nu()), v = int(view / in.nu());
      halvePlane(in.plane(u, v, c), in.ns(), in.nt(), out.plane(u, v, c));
    }
  });
  return out;
}

Image halfResolution(const Image& in) {
  Image out(in.width() / 2, in.height() / 2, in.channels());
  for (int c = 0; c < in.channels(); ++c) halvePlane(in.plane(c), in.width(), in.height(), out.plane(c));
  return out;
}

// A half-resolution map at full resolution: bilinear, each disparity doubled (twice the pixels per
// view step).
Image fullResolution(const Image& half, int width, int height) {
  Image out(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      out.at(x, y, 0) = 2 * sampleHalfResolution(half.plane(0), half.width(), half.height(), x, y);
  return out;
}

// The largest map error (pixels per view step) that mapError gives removeViewOffsets to take out:
// beyond it the fit meets an occlusion edge or no texture, not a small bias.
constexpr double kOffsetSlopeLimit = 0.5;

// The error of a map by which views were warped onto the reference, per pixel, as the part of
// each view's difference from the reference that the error explains: `slope(u, v)` (the
// reference's gradient along the view's baseline, times -1: an error e moves the view's samples by
// -e (u, v)) times the error, fitted to all views at once by least squares over a box of `radius`,
// with an offset and a gain per view free in it (a sheen adds to the texture and scales it), so
// that only texture decides. Clamped to +-kOffsetSlopeLimit.
template <typename Warp, typename Slope, typename IsReference>
std::vector<float> mapError(const LightField& grey, const std::vector<float>& reference, int radius, const Warp& warp,
                            const Slope& slope, const IsReference& isReference) {
  const int ns = grey.ns(), nt = grey.nt();
  const std::size_t n = grey.shape().viewPixels();
  std::vector<float> meanReference(n), meanSquare(n), square(n);
  boxFilter(reference.data(), meanReference.data(), ns, nt, radius);
  for (std::size_t i = 0; i < n; ++i) square[i] = reference[i] * reference[i];
  boxFilter(square.data(), meanSquare.data(), ns, nt, radius);
  // Sums over the views in an order that the threads do not change (the same map from every run):
  // views dealt by index to kSumGroups groups, each summed in order, then the groups in order.
  constexpr std::size_t kSumGroups = 8;
  std::vector<double> groupCovariance[kSumGroups], groupVariance[kSumGroups];
  const std::size_t views = grey.shape().views();
  parallelFor(0, kSumGroups, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> difference(n), g(n), product(n), mean[6];
    for (auto& m : mean) m.resize(n);
    const auto boxOfProduct = [&](const std::vector<float>& a, const std::vector<float>& b, std::vector<float>& out) {
      for (std::size_t i = 0; i < n; ++i) product[i] = a[i] * b[i];
      boxFilter(product.data(), out.data(), ns, nt, radius);
    };
    for (std::size_t group = begin; group < end; ++group) {
      std::vector<double>& localCovariance = groupCovariance[group];
      std::vector<double>& localVariance = groupVariance[group];
      localCovariance.assign(n, 0.0), localVariance.assign(n, 0.0);
      for (std::size_t view = group; view < views; view += kSumGroups) {
        if (isReference(view)) continue;
        const int u = int(view % grey.nu()), v = int(view / grey.nu());
        warp(u, v, difference.data());
        for (std::size_t i = 0; i < n; ++i) difference[i] -= reference[i];
        slope(u, v, g.data());
        boxFilter(difference.data(), mean[0].data(), ns, nt, radius);
        boxFilter(g.data(), mean[1].data(), ns, nt, radius);
        boxOfProduct(difference, g, mean[2]);
        boxOfProduct(g, g, mean[3]);
        boxOfProduct(difference, reference, mean[4]);
        boxOfProduct(g, reference, mean[5]);
        for (std::size_t i = 0; i < n; ++i) {
          // Covariances over the box; the reference's part (the gain) projected out where it varies.
          const double r = meanReference[i], rr = double(meanSquare[i]) - r * r;
          const double dg = double(mean[2][i]) - double(mean[0][i]) * mean[1][i];
          const double gg = double(mean[3][i]) - double(mean[1][i]) * mean[1][i];
          const double dr = double(mean[4][i]) - double(mean[0][i]) * r,
                       gr = double(mean[5][i]) - double(mean[1][i]) * r;
          const bool gain = rr > 1e-12;
          localCovariance[i] += gain ? dg - dr * gr / rr : dg;
          localVariance[i] += gain ? gg - gr * gr / rr : gg;
        }
      }
    }
  });
  std::vector<double> covariance(n, 0.0), variance(n, 0.0);
  for (std::size_t group = 0; group < kSumGroups; ++group)
    for (std::size_t i = 0; i < groupCovariance[group].size(); ++i)
      covariance[i] += groupCovariance[group][i], variance[i] += groupVariance[group][i];
  std::vector<float> error(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i)
    if (variance[i] > 0)
      error[i] = float(std::clamp(covariance[i] / variance[i], -kOffsetSlopeLimit, kOffsetSlopeLimit));
  return error;
}

// Where the centre view's texture is locally a ramp (features far wider than the box, the layered
// planes of coarse texture at 256 px per view), a map error e gives each view the difference e g
// with g constant over the box: mapError, which leaves each view an offset free, cannot see it,
// and the average takes it for an offset, which then cancels the views' disagreement at the
// wrong disparity and keeps it (that scene 32.73 % with the view offsets, 5.06 % without). The
// shrink (DepthExperiment::offsetShrink, off by default) keeps an offset only where it is larger
// than a map error of kOffsetMapErrorPx would make: before offsetsKept (below), development means
// 2.200 -> 1.921 % at 128 px per view and 3.175 -> 2.002 % at 256 (the coarse texture 12.55 ->
// 3.67 and 32.73 -> 8.19 %), but a sheen on texture is taken for a map error too (the glossy
// unevenly lit slants 3.40 -> 7.42 % at 128) and the tests of the view offsets refuse it
// (design.md, "Depth"). Among 0.15, 0.2, 0.3 and 1 px, 0.3 had the best means.
constexpr double kOffsetMapErrorPx = 0.3;

// Each view less its brightness offset from the reference view: their difference once the view is
// warped onto the reference by `disparity`, averaged by a guided filter that the map steers
// (`radius`, `epsilon` in squared disparity), so that a brightness that changes smoothly across
// the aperture (a sheen, devignetting left imperfect) cancels while texture stays, and the offsets
// of the two sides of an occlusion edge stay apart. With `slopeCorrected`, the part of each
// difference that the map's error explains (mapError) is taken out first: else, on weak texture,
// the error that a sheen caused in the map passes for part of the offsets and stays. With
// `shrunk`, each offset o is then scaled by o^2 / (o^2 + (kOffsetMapErrorPx g)^2), g the slope
// that a map error moves the view's samples along: kept where it is larger than a map error of
// kOffsetMapErrorPx would make, dropped where it is smaller. With `kept`, each offset is multiplied
// by it (per pixel, in [0, 1]) before it is removed.
void removeViewOffsets(LightField& grey, const Image& disparity, int radius, double epsilon, bool slopeCorrected,
                       bool shrunk, bool fromReference, const std::vector<float>* kept = nullptr) {
  const int ns = grey.ns(), nt = grey.nt();
  const std::size_t n = grey.shape().viewPixels();
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const auto warp = [&](int u, int v, float* out) {
    const float* plane = grey.plane(u, v, 0);
    const double uc = stepsU(grey, u, fromReference), vc = stepsV(grey, v, fromReference);
    for (int y = 0; y < nt; ++y)
      for (int x = 0; x < ns; ++x) {
        const double d = disparity.at(x, y, 0);
        out[std::size_t(y) * ns + x] = bilinearSample(plane, ns, nt, x - uc * d, double(y) - vc * d);
      }
  };
  const auto isReference = [&](std::size_t view) {
    return int(view % grey.nu()) == referenceU && int(view / grey.nu()) == referenceV;
  };
  const bool slopes = slopeCorrected || shrunk;
  std::vector<float> reference(n), dx(slopes ? n : 0), dy(slopes ? n : 0), error;
  warp(referenceU, referenceV, reference.data());
  const auto slope = [&](int u, int v, float* out) {
    const float uc = float(stepsU(grey, u, fromReference)), vc = float(stepsV(grey, v, fromReference));
    for (std::size_t i = 0; i < n; ++i) out[i] = -(uc * dx[i] + vc * dy[i]);
  };
  if (slopes) centralDifferences(reference.data(), ns, nt, 1.0f, dx.data(), dy.data());
  if (slopeCorrected) error = mapError(grey, reference, radius, warp, slope, isReference);
  const edof::GuidedFilter filter(disparity.plane(0), ns, nt, radius, epsilon);
  parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> difference(n), offset(n), g(dx.size());
    edof::GuidedFilter::Scratch scratch;
    for (std::size_t view = begin; view < end; ++view) {
      if (isReference(view)) continue;
      const int u = int(view % grey.nu()), v = int(view / grey.nu());
      warp(u, v, difference.data());
      for (std::size_t i = 0; i < n; ++i) difference[i] -= reference[i];
      if (slopes) slope(u, v, g.data());
      if (slopeCorrected)
        for (std::size_t i = 0; i < n; ++i) difference[i] -= error[i] * g[i];
      filter.apply(difference.data(), offset.data(), scratch);
      if (shrunk)
        for (std::size_t i = 0; i < n; ++i) {
          const double squared = double(offset[i]) * offset[i], explained = kOffsetMapErrorPx * g[i];
          if (squared > 0) offset[i] = float(offset[i] * squared / (squared + explained * explained));
        }
      float* plane = grey.plane(u, v, 0);
      for (std::size_t i = 0; i < n; ++i) plane[i] -= kept ? (*kept)[i] * offset[i] : offset[i];
    }
  });
}

// Where the view offsets are kept: where the half resolution's match after their removal leaves the
// views disagreeing no more than its match before, give or take kOffsetCheckTolerance times the
// median of `before` (`after` <= `before` + that, per half-resolution pixel), the share of such
// pixels over a box of kOffsetCheckRadius, at full resolution (bilinear). A sheen that the offsets
// cancel lets the views agree better; offsets that a map error put there (on texture that is
// locally a ramp, above) leave them agreeing worse, since each view keeps e (g - mean g). The first
// and second half-resolution maps of the coarse texture at 256 px score 5.97 and 24.12 %. Without
// the tolerance: development means 2.190 -> 1.707 % at 128 px and 3.191 -> 1.718 % at 256 (the
// coarse texture 12.52 -> 2.18 and 32.74 -> 5.91 %), the glossy unevenly lit slants 3.25 -> 5.77 %
// at 128 the most it cost. The tolerance, in the residual's own scale (a fixed one helped at 128 px
// and hurt at 256, where the residuals are smaller), lets a pixel whose residual barely moved keep
// its offsets: 1.707 -> 1.620 % at 128 px and 1.718 -> 1.696 % at 256 (the glossy unevenly lit
// slants 5.77 -> 4.25 %, the coarse texture at 256 5.91 -> 4.97 %); 0.1, 0.3, 1 and 2 gave 1.703 /
// 1.746, 1.600 / 1.710, 1.645 / 1.693 and 1.655 / 1.692 %. Other radii and soft shares measured
// worse (design.md, "Depth").
constexpr int kOffsetCheckRadius = 2;
constexpr double kOffsetCheckTolerance = 0.6;

std::vector<float> offsetsKept(const Residual& before, const std::vector<float>& after, int halfWidth, int halfHeight,
                               int width, int height) {
  const std::size_t n = before.perPixel.size();
  std::vector<float> agree(n), share(n), kept(std::size_t(width) * height);
  const double tolerance = kOffsetCheckTolerance * before.median;
  for (std::size_t i = 0; i < n; ++i) agree[i] = after[i] <= before.perPixel[i] + tolerance ? 1.0f : 0.0f;
  boxFilter(agree.data(), share.data(), halfWidth, halfHeight, kOffsetCheckRadius);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      kept[std::size_t(y) * width + x] = float(sampleHalfResolution(share.data(), halfWidth, halfHeight, x, y));
  return kept;
}

// Every view smoothed by a Gaussian of `sigma` pixels: sensor noise is white, while the views of
// a plenoptic camera are band-limited by its microlenses, so a light smoothing removes more noise
// than detail.
void blurViews(LightField& grey, double sigma) {
  parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view)
      for (int c = 0; c < grey.channels(); ++c)
        edof::gaussianBlur(grey.plane(int(view % grey.nu()), int(view / grey.nu()), c), grey.ns(), grey.nt(), sigma);
  });
}

}  // namespace

Result<DepthMap> estimateDepth(const LightField& lightField, const DepthOptions& options) {
  return edof::estimateDepth(lightField, options, {});
}

Result<DepthMap> edof::estimateDepth(const LightField& lightField, const DepthOptions& options,
                                     const DepthExperiment& experiment) {
  if (lightField.empty() || lightField.ns() < 2 || lightField.nt() < 2)
    return makeError(ErrorCode::Usage, "depth: the light field is empty");
  if (lightField.nu() * lightField.nv() < 2)
    return makeError(ErrorCode::Usage, "depth: the light field has a single view, so no parallax to measure");
  const double dmin = options.disparityMin.value_or(lightField.metadata.disparityMin.value_or(-2.0));
  const double dmax = options.disparityMax.value_or(lightField.metadata.disparityMax.value_or(2.0));
  if (!(std::isfinite(dmin) && std::isfinite(dmax) && dmin < dmax))
    return makeError(ErrorCode::Usage, "depth: the disparity range [" + std::to_string(dmin) + ", " +
                                           std::to_string(dmax) + "] is empty");
  // 1. Range: the candidate disparities.
  int labels = options.labels;
  if (labels <= 0) labels = std::clamp(int(std::ceil((dmax - dmin) / 0.1)) + 1, 16, 96);
  if (labels < 2) return makeError(ErrorCode::Usage, "depth: at least 2 candidate disparities are needed");
  std::vector<double> disparities(labels);
  const double step = (dmax - dmin) / (labels - 1);
  for (int l = 0; l < labels; ++l) disparities[l] = dmin + l * step;

  // Matching on sRGB-encoded luminance: roughly uniform in perceived contrast, so that texture in
  // the shadows counts as much as in the light (in linear light it nearly vanishes).
  LightField grey = edof::luminanceLightField(lightField);
  parallelFor(0, grey.samples().size(), 1 << 16, [&](std::size_t begin, std::size_t end) {
    const std::span<float> samples(grey.samples().data() + begin, end - begin);
    for (float& v : samples) v = std::max(v, 0.0f);
    srgbFromLinear(samples);
  });
  const Image guide = grey.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2);
  // The centre view's colours (linear) that steer the cleanup, sRGB-encoded as the matching.
  const Image centre = lightField.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2);
  const auto srgb = [](Image image) {
    for (float& v : image.pixels()) v = std::max(v, 0.0f);
    srgbFromLinear(image.pixels());
    return image;
  };
  const Image colours = srgb(centre.copy());
  if (experiment.highPassRadius > 0)
    parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
      std::vector<float> mean(grey.shape().viewPixels());
      for (std::size_t view = begin; view < end; ++view) {
        float* plane = grey.plane(int(view % grey.nu()), int(view / grey.nu()), 0);
        boxFilter(plane, mean.data(), grey.ns(), grey.nt(), experiment.highPassRadius);
        for (std::size_t i = 0; i < mean.size(); ++i) plane[i] -= mean[i];
      }
    });
  if (experiment.gradientWeight > 0) grey = withGradients(grey, experiment.gradientWeight);
  const double prefilter = options.prefilterSigma;
  if (prefilter > 0) blurViews(grey, prefilter);
  Residual residual;
  CoarseCost coarse;
  // View offsets: first maps at half resolution, each pass matching views whose offsets the
  // previous one removed; the last one's offsets removed from the views at full resolution (views
  // under 4 pixels across: none).
  if (options.offsetRadius > 0 && options.offsetPasses > 0 && grey.ns() >= 4 && grey.nt() >= 4) {
    const Image smallColours = srgb(halfResolution(centre));
    LightField small = halfResolution(grey);
    const Image smallGuide = small.subApertureImage((small.nu() - 1) / 2, (small.nv() - 1) / 2);
    std::vector<double> halved(disparities);
    for (double& d : halved) d *= 0.5;
    Image first;
    Residual withoutOffsets;
    for (int pass = 0; pass < options.offsetPasses; ++pass) {
      if (pass > 0)
        removeViewOffsets(small, first, std::max(options.offsetRadius / 2, 1), options.offsetEpsilon / 4,
                          experiment.offsetSlopeCorrection, experiment.offsetShrink, experiment.matchAtReference);
      CoarseCost* keep = pass + 1 == options.offsetPasses ? &coarse : nullptr;
      first = depthStages(smallColours, small, smallGuide, halved, options, experiment, {}, &residual, nullptr, keep)
                  .disparity;
      if (pass == 0) withoutOffsets = std::move(residual);
    }
    const bool checked = experiment.offsetResidualCheck && options.offsetPasses > 1 && !residual.perPixel.empty();
    const std::vector<float> kept =
        checked ? offsetsKept(withoutOffsets, residual.perPixel, small.ns(), small.nt(), grey.ns(), grey.nt())
                : std::vector<float>{};
    removeViewOffsets(grey, fullResolution(first, grey.ns(), grey.nt()), options.offsetRadius, options.offsetEpsilon,
                      experiment.offsetSlopeCorrection, experiment.offsetShrink, experiment.matchAtReference,
                      checked ? &kept : nullptr);
  }
  DepthMap map = depthStages(colours, grey, guide, disparities, options, experiment, {}, &residual, &coarse);
  map.prefilterSigma = std::max(prefilter, 0.0);
  map.viewResidual = prefilter > 0 ? 0.0 : residual.median;  // of the views as given only
  // Automatic: the views matched as they are, then, where they disagree at their best match by
  // more than clean views do (noise, or texture finer than the pixels), smoothed and matched again.
  if (prefilter < 0 && residual.median > kNoisyResidual) {
    blurViews(grey, kNoisyPrefilterSigma);
    const double asGiven = map.viewResidual;
    const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
    const bool atReference = experiment.matchAtReference;
    const edof::ViewNoise noise =
        experiment.noiseCorrection
            ? smoothedNoise(asGiven, kNoisyPrefilterSigma, starViews(grey, referenceU, referenceV, atReference),
                            meanKept(stepsU(grey, referenceU, atReference), stepsV(grey, referenceV, atReference)))
            : edof::ViewNoise{};
    map = depthStages(colours, grey, guide, disparities, options, experiment, noise, &residual, &coarse);
    map.prefilterSigma = kNoisyPrefilterSigma;
    map.viewResidual = asGiven;
  }
  return map;
}

std::optional<double> distanceFromDisparity(const Optics& optics, double disparity) {
  if (!optics.focalLengthMm || !(*optics.focalLengthMm > 0) || !(optics.lensToMicrolensMm > 0)) return std::nullopt;
  const double alpha = optics.alphaFromSlope(disparity);
  const double film = alpha * optics.lensToMicrolensMm;
  const double inverse = 1.0 / *optics.focalLengthMm - 1.0 / film;  // 1/z = 1/f - 1/(alpha F)
  if (!(alpha > 0) || !(inverse > 0)) return std::numeric_limits<double>::infinity();
  return 1.0 / inverse;
}

std::optional<double> disparityFromDistance(const Optics& optics, double distanceMm) {
  if (!optics.focalLengthMm || !(*optics.focalLengthMm > 0) || !(optics.lensToMicrolensMm > 0) ||
      !(distanceMm > *optics.focalLengthMm))
    return std::nullopt;
  // Thin lens: the image of the surface lies at alpha F behind the lens.
  const double film = 1.0 / (1.0 / *optics.focalLengthMm - 1.0 / distanceMm);
  return optics.slopeFromAlpha(film / optics.lensToMicrolensMm);
}

Result<Image> distanceMap(const LightFieldMetadata& metadata, const Image& disparity) {
  if (!metadata.optics || !metadata.optics->focalLengthMm)
    return makeError(ErrorCode::Usage,
                     "depth: the light field carries no optics with a focal length, so no metric distance");
  Image out(disparity.width(), disparity.height(), 1);
  for (std::size_t i = 0; i < out.planeSize(); ++i)
    out.plane(0)[i] = float(distanceFromDisparity(*metadata.optics, disparity.plane(0)[i]).value_or(0.0));
  return out;
}

}  // namespace lfcam
