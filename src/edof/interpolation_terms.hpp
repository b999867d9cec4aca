// What bilinear sampling between pixels does to the correspondence cost, which the depth cost
// volume and fine search (fine_cost_row.hpp) correct for: it blurs the texture and lowers the
// noise of a view, both by amounts that depend on the fraction of its shift.
#pragma once

#include <cmath>

namespace lfcam::edof {

// f (1 - f) / 2 for the fraction f of a shift: the blur of bilinear sampling there.
inline double interpolationBlur(double shift) {
  const double f = shift - std::floor(shift);
  return 0.5 * f * (1 - f);
}

// The noise of the views matched, for the bias it gives the cost: bilinear sampling between
// pixels averages neighbouring samples, and so lowers the variance of their noise, most at half a
// pixel. Where the views show no texture, only noise, the cost is then lowest at shifts of half a
// pixel, whatever the depth (large flat regions of noisy views snapped to them). `variance` is the
// noise variance of a sample; `neighbourCorrelation` that of two neighbours along either axis
// (0 for white noise; more once the views are smoothed).
struct ViewNoise {
  double variance = 0;
  double neighbourCorrelation = 0;
};

// How much less noise variance a sample read at (x + shiftX, y + shiftY) has than one read on the
// grid: the variance of (1 - f) a + f b over both axes, f the fraction of each shift.
inline double interpolationNoiseLoss(const ViewNoise& noise, double shiftX, double shiftY) {
  if (!(noise.variance > 0)) return 0;
  const auto kept = [&](double shift) {
    const double f = shift - std::floor(shift);
    return 1 - 2 * f * (1 - f) * (1 - noise.neighbourCorrelation);
  };
  return noise.variance * (1 - kept(shiftX) * kept(shiftY));
}

}  // namespace lfcam::edof
