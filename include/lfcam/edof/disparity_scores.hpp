// The HCI 4D light field benchmark's scores of a disparity map against its ground truth (Honauer
// et al. 2016, evaluation toolkit), for lfcam's maps and anyone else's.
//
// Over the pixels at least `border` pixels inside the image (15 in the benchmark) whose ground
// truth is finite:
//   badPix = 100 * fraction with |estimate - truth| > threshold   (BadPix(0.07) for 0.07)
//   mse100 = 100 * mean (estimate - truth)^2                      (MSE x 100)
// A non-finite estimate is scored as an error of |truth| + 1, so that a hole cannot flatter.
//
// Bumpiness (the toolkit's "Bumpiness Planes"): 100 x the mean, over planar surfaces, of the
// Frobenius norm of the Hessian of (estimate - truth), each clipped at 0.05. The Hessian is the
// Scharr derivative (f(x + 1) - f(x - 1), twice the derivative, smoothed [3 10 3] / 16 across)
// applied twice, as the toolkit does with scikit-image: 4 x the second derivatives, with both mixed
// ones. An image border is repeated. Planar surfaces are the nonzero
// pixels of a mask (the benchmark's mask_planes.png) or, without one, the pixels where the same
// Hessian of the ground truth itself is below kPlanarTolerance: flat and slanted planes, a band of
// two pixels clear of every depth edge. A pixel where the estimate's Hessian is not finite counts
// as the clip.
#pragma once

#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct DisparityScores {
  double badPix = 0;
  double mse100 = 0;
  // The share (%) of the bad pixels that the estimate puts farther than the truth (lower
  // disparity): a method's errors fall on both sides, a bias or a second surface on one.
  double fartherShare = 0;
  long pixels = 0;
};
// Usage error when the sizes differ, no pixel has ground truth inside the border or the threshold
// is not positive.
Result<DisparityScores> scoreDisparity(const Image& estimate, const Image& truth, double threshold = 0.07,
                                       int border = 15);

// The toolkit's second-order roughness of the error on planes (above). `planes` empty: from the
// ground truth. Usage error when the sizes differ or no planar pixel lies inside the border.
inline constexpr double kPlanarTolerance = 1e-4;  // truth's Hessian norm, px per view step per px^2
Result<double> bumpiness(const Image& estimate, const Image& truth, const Image& planes = {}, int border = 15);
// The planar surfaces of a ground truth (above): 1 on planes, 0 elsewhere, same size.
Image planarMask(const Image& truth);

// Every score the benchmark reports for a disparity map's accuracy, as `lfcam score` prints them.
struct HciScores {
  double badPix001 = 0, badPix003 = 0, badPix007 = 0;
  double mse100 = 0;
  double bumpiness = 0;
  long pixels = 0;
};
Result<HciScores> scoreHci(const Image& estimate, const Image& truth, const Image& planes = {}, int border = 15);

// The name of BadPix at `threshold` in `lfcam score --json` and the Python module's scores:
// "badpix_0.07", "badpix_0.035".
std::string badPixKey(double threshold);

}  // namespace lfcam
