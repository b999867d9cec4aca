// Steps 2-3 of depth estimation (depth_stages.hpp): the views matched and their subsets, the
// correspondence and defocus cues per label, aggregation, the lowest subset.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.hpp"
#include "core/target_clones.hpp"
#include "edof/depth_stages.hpp"
#include "lfcam/render/refocus.hpp"

namespace lfcam::edof {

double stepsU(const LightField& lightField, int u, bool fromReference) {
  return fromReference ? u - (lightField.nu() - 1) / 2 : lightField.uFromCentre(u);
}

double stepsV(const LightField& lightField, int v, bool fromReference) {
  return fromReference ? v - (lightField.nv() - 1) / 2 : lightField.vFromCentre(v);
}

std::vector<StarView> starViews(const LightField& lightField, int referenceU, int referenceV, StarChoice star) {
  std::vector<StarView> views;
  for (int v = 0; v < lightField.nv(); ++v)
    for (int u = 0; u < lightField.nu(); ++u) {
      if (u == referenceU && v == referenceV) continue;
      const int du = u - referenceU, dv = v - referenceV;
      if (du != 0 && dv != 0 && std::abs(du) != std::abs(dv)) continue;
      if (std::max(std::abs(du), std::abs(dv)) % std::max(star.ringStep, 1) != 0) continue;
      StarView view{u, v, stepsU(lightField, u, star.fromReference), stepsV(lightField, v, star.fromReference), 0};
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

namespace {

// accumulator += (sample - reference)^2
LFCAM_CLONES void accumulateSquaredDifference(const float* __restrict sample, const float* __restrict reference,
                                              float* __restrict accumulator, int count) {
  for (int x = 0; x < count; ++x) {
    const float difference = sample[x] - reference[x];
    accumulator[x] += difference * difference;
  }
}

// A subset's mean squared difference over its `views`, less the interpolation-bias term (the
// reference's second differences xx, yy, xy weighted by wx, wy, wxy), plus the noise it removes,
// less the defocus cue (`energy` times `weight`).
LFCAM_CLONES void subsetMean(const float* __restrict sum, int views, const float* __restrict xx,
                             const float* __restrict yy, const float* __restrict xy, float wx, float wy, float wxy,
                             float noiseLoss, const float* __restrict energy, float weight, int count,
                             float* __restrict out) {
  for (int x = 0; x < count; ++x)
    out[x] = sum[x] / views - (wx * xx[x] + wy * yy[x] + wxy * xy[x]) + noiseLoss - weight * energy[x];
}

// The same without the bias term (its weights 0).
LFCAM_CLONES void subsetMean(const float* __restrict sum, int views, float noiseLoss, const float* __restrict energy,
                             float weight, int count, float* __restrict out) {
  for (int x = 0; x < count; ++x) out[x] = sum[x] / views + noiseLoss - weight * energy[x];
}

}  // namespace

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

std::vector<int> subsetsWithViews(const std::vector<StarView>& views, int (&viewsIn)[kHalves]) {
  std::fill(viewsIn, viewsIn + kHalves, 0);
  for (const StarView& view : views)
    for (int h = 0; h < kHalves; ++h) viewsIn[h] += (view.halves >> h) & 1;
  std::vector<int> subsets;
  for (int h = 0; h < kHalves; ++h)
    if (viewsIn[h] > 0) subsets.push_back(h);
  return subsets;
}

namespace {

// The correspondence cue for labels [labelBegin, labelEnd), n = ns * nt: the mean squared
// difference over each subset of views with views, out[((l - labelBegin) * subsets + i) * n + p]
// (subsetsWithViews' order). `locking` scales the interpolation-bias term removed (0: none); the
// noise variance that interpolation removes is added back (ViewNoise, interpolation_terms.hpp).
// Less `weight` times the defocus cue energy[l * n + p] (none without `energy`), in the same pass.
void correspondenceCost(const LightField& grey, const std::vector<double>& disparities, int labelBegin, int labelEnd,
                        double locking, const edof::ViewNoise& noise, StarChoice star, const float* energy,
                        float weight, float* out) {
  const int ns = grey.ns(), nt = grey.nt();
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const std::vector<StarView> views = starViews(grey, referenceU, referenceV, star);
  const double referenceUc = stepsU(grey, referenceU, star.fromReference),
               referenceVc = stepsV(grey, referenceV, star.fromReference);
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
    std::vector<float> accumulator(std::size_t(kHalves) * blockRows * ns), noEnergy(energy ? 0 : ns, 0.0f);
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
          for (std::size_t i = 0; i < subsets.size(); ++i) {
            const int h = subsets[i];
            const float* sum = accumulator.data() + (std::size_t(h) * blockRows + (y - y0)) * ns;
            float* target = out + (std::size_t(l - labelBegin) * subsets.size() + i) * n + row;
            const float* energyRow = energy ? energy + std::size_t(l) * n + row : noEnergy.data();
            if (locking > 0)
              subsetMean(sum, viewsIn[h], secondDiff.xx.data() + row, secondDiff.yy.data() + row,
                         secondDiff.xy.data() + row, wx[h], wy[h], wxy[h], noiseLoss[h], energyRow, weight, ns, target);
            else
              subsetMean(sum, viewsIn[h], noiseLoss[h], energyRow, weight, ns, target);
          }
        }
      }
    }
  });
}

}  // namespace

namespace {

// lowestSubset over pixels [0, count): a plane at a time, so that the loop over pixels vectorises.
LFCAM_CLONES void lowestOfPlanes(const float* __restrict first, std::size_t subsets, std::size_t stride,
                                 std::size_t count, float* __restrict out) {
  for (std::size_t p = 0; p < count; ++p) out[p] = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < subsets; ++i)
    for (std::size_t p = 0; p < count; ++p) out[p] = std::min(out[p], first[i * stride + p]);
  for (std::size_t p = 0; p < count; ++p) out[p] = std::isfinite(out[p]) ? out[p] : 0.0f;
}

}  // namespace

void lowestSubset(const float* first, std::size_t subsets, std::size_t stride, std::size_t n, float* out) {
  parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
    lowestOfPlanes(first + begin, subsets, stride, end - begin, out + begin);
  });
}

namespace {

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

}  // namespace

bool gatesOneDimensional(const std::vector<int>& subsets, bool wanted) {
  return wanted && subsets == std::vector<int>{0, 1, 2, 3, 4, 5};
}

namespace {

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

}  // namespace

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

void aggregatePlanes(const edof::GuidedFilter& filter, const std::vector<const float*>& in,
                     const std::vector<float*>& out) {
  parallelFor(0, in.size(), 1, [&](std::size_t begin, std::size_t end) {
    edof::GuidedFilter::Scratch scratch;
    for (std::size_t k = begin; k < end; ++k) filter.apply(in[k], out[k], scratch);
  });
}

void aggregatePlanes(const edof::GuidedFilter& filter, float* planes, std::size_t count, std::size_t n) {
  std::vector<float*> each(count);
  for (std::size_t k = 0; k < count; ++k) each[k] = planes + k * n;
  aggregatePlanes(filter, {each.begin(), each.end()}, each);
}

namespace {

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

}  // namespace

edof::CostVolume aggregatedCost(const LightField& grey, const std::vector<double>& disparities,
                                const edof::GuidedFilter& filter, double defocusWeight, double locking,
                                const edof::ViewNoise& noise, bool subsetsApart, bool ceiling, bool gateWanted,
                                StarChoice star) {
  const std::size_t n = grey.shape().viewPixels();
  const int labels = int(disparities.size());
  int viewsIn[kHalves];
  const std::vector<int> subsetList =
      subsetsWithViews(starViews(grey, (grey.nu() - 1) / 2, (grey.nv() - 1) / 2, star), viewsIn);
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
    // The defocus cue taken off each subset's slice (the lowest subset less it, when taken first).
    correspondenceCost(grey, disparities, first, last, locking, noise, star, energy.empty() ? nullptr : energy.data(),
                       float(defocusWeight), planes.data());
    if (!subsetsApart)
      for (int l = first; l < last; ++l)
        lowestSubset(planes.data() + std::size_t(l - first) * subsets * n, subsets, n, n,
                     cost.data() + std::size_t(l) * n);
    // The slices the guided filter is applied to.
    const std::size_t perLabel = subsetsApart ? subsets : 1;
    auto slice = [&](int l, std::size_t i) {
      return subsetsApart ? planes.data() + (std::size_t(l - first) * subsets + i) * n
                          : cost.data() + std::size_t(l) * n;
    };
    // Aggregated in place, the one-dimensional subsets' slices straight into their volumes.
    std::vector<const float*> in;
    std::vector<float*> out;
    for (int l = first; l < last; ++l)
      for (std::size_t i = 0; i < perLabel; ++i) {
        in.push_back(slice(l, i));
        out.push_back(i < halves || !subsetsApart ? slice(l, i)
                                                  : oneDimensional[i - halves].data() + std::size_t(l) * n);
      }
    aggregatePlanes(filter, in, out);
    if (subsetsApart)
      for (int l = first; l < last; ++l) lowestSubset(slice(l, 0), halves, n, n, cost.data() + std::size_t(l) * n);
  }
  if (gate)
    joinOneDimensional(cost.data(), {oneDimensional[0].data(), oneDimensional[1].data()}, labels, n, noise.variance);
  return cost;
}

}  // namespace lfcam::edof
