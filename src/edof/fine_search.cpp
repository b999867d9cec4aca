// Step 5 of depth estimation (depth_stages.hpp): the fine search around a map.
#include <algorithm>

#include "core/parabola.hpp"
#include "core/parallel.hpp"
#include "edof/depth_stages.hpp"
#include "edof/fine_cost_row.hpp"

namespace lfcam::edof {

namespace {

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

}  // namespace

void refineDisparity(const LightField& grey, const edof::GuidedFilter& filter, float* disparity, double delta,
                     int steps, double locking, const edof::ViewNoise& noise, bool aggregateHalves, bool gateWanted,
                     StarChoice star, float* curvatureOut, float* residualOut) {
  const int ns = grey.ns(), nt = grey.nt();
  const std::size_t n = grey.shape().viewPixels();
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const std::vector<StarView> views = starViews(grey, referenceU, referenceV, star);
  int viewsIn[kHalves];
  const std::vector<int> subsets = subsetsWithViews(views, viewsIn);
  const int slices = 2 * steps + 1;
  edof::CostVolume cost(n * slices);
  // Subset i and slice k in plane i * slices + k.
  edof::CostVolume subsetCost(subsets.size() * slices * n);
  const SecondDifferences secondDiff =
      locking > 0 ? secondDifferences(grey.plane(referenceU, referenceV, 0), ns, nt) : SecondDifferences{};
  const edof::FineCostViews fineViews =
      fineCostViews(grey, views, subsets, viewsIn, locking, secondDiff, noise, star.fromReference);
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

}  // namespace lfcam::edof
