// The correspondence cost of depth's fine search (refineDisparity, fine_search.cpp), a row of one slice
// at a time: the reference view and every star view sampled bilinearly at each pixel's own
// disparity, their squared differences, less the interpolation-bias term, plus the noise
// interpolation removes (interpolation_terms.hpp), averaged over each subset of views. The fast
// kernel is SIMD across the row through Highway with run-time dispatch and gives the same bits as
// the scalar reference.
#pragma once

#include <vector>

#include "edof/interpolation_terms.hpp"

namespace lfcam::edof {

// Subsets of views a cost is taken over, at most (cost_volume.cpp's half-apertures, centre row, column).
constexpr int kMaxCostSubsets = 6;

struct FineCostViews {
  int ns = 0, nt = 0, channels = 1;
  // View 0 is the reference, the rest are compared with it. View i's channel c is the plane
  // planes[i * channels + c] of ns x nt floats; (uc[i], vc[i]) its steps from the aperture centre;
  // bit j of subsets[i] set when it counts in subset j (none for the reference).
  std::vector<const float*> planes;
  std::vector<double> uc, vc;
  std::vector<unsigned> subsets;
  std::vector<int> viewsIn;  // per subset, how many views count in it (at least one)
  // The interpolation-bias term's scale (0: none) and the reference view's second differences
  // (Ixx^2, Iyy^2, 2 Ixx Iyy, ns x nt floats each), read only when locking > 0.
  double locking = 0;
  const float *xx = nullptr, *yy = nullptr, *xy = nullptr;
  ViewNoise noise;
};

// Row y of each subset's cost at disparity disparity[x] + offset for x in [0, ns): out[j][x] for
// subset j. `disparity` is row y of the map.
void fineCostRow(const FineCostViews& views, int y, const float* disparity, double offset, float* const* out);

// The same, one pixel at a time in scalar code: the reference the fast kernel is tested against,
// and the path for rows narrower than a vector.
void fineCostRowReference(const FineCostViews& views, int y, const float* disparity, double offset, float* const* out);

}  // namespace lfcam::edof
