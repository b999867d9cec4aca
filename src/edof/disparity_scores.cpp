// The HCI benchmark's scores of a disparity map (disparity_scores.hpp).
#include "lfcam/edof/disparity_scores.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace lfcam {
namespace {

constexpr double kBumpinessClip = 0.05;

Status sameSize(const Image& estimate, const Image& truth) {
  if (estimate.width() == truth.width() && estimate.height() == truth.height() && estimate.channels() >= 1 &&
      truth.channels() >= 1)
    return {};
  return makeError(ErrorCode::Usage, "scores: the estimate is " + std::to_string(estimate.width()) + "x" +
                                         std::to_string(estimate.height()) + " but the ground truth " +
                                         std::to_string(truth.width()) + "x" + std::to_string(truth.height()));
}

// A w x h plane of doubles, its border repeated when read outside.
struct Plane {
  int width, height;
  std::vector<double> values;
  double at(int x, int y) const {
    return values[std::size_t(std::clamp(y, 0, height - 1)) * std::size_t(width) +
                  std::size_t(std::clamp(x, 0, width - 1))];
  }
};

// Scharr derivative along x (alongX) or y: central difference along, [3 10 3] / 16 across.
Plane scharr(const Plane& in, bool alongX) {
  Plane out{in.width, in.height, std::vector<double>(in.values.size())};
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      double sum = 0;
      for (int across = -1; across <= 1; ++across) {
        const double weight = across == 0 ? 10.0 : 3.0;
        sum += alongX ? weight * (in.at(x + 1, y + across) - in.at(x - 1, y + across))
                      : weight * (in.at(x + across, y + 1) - in.at(x + across, y - 1));
      }
      out.values[std::size_t(y) * std::size_t(in.width) + std::size_t(x)] = sum / 16.0;
    }
  return out;
}

// Frobenius norm of the Hessian of `plane` per pixel, the toolkit's way (both mixed derivatives).
Plane hessianNorm(const Plane& plane) {
  const Plane dx = scharr(plane, true), dy = scharr(plane, false);
  const Plane dxx = scharr(dx, true), dxy = scharr(dx, false), dyy = scharr(dy, false), dyx = scharr(dy, true);
  Plane norm{plane.width, plane.height, std::vector<double>(plane.values.size())};
  for (std::size_t i = 0; i < norm.values.size(); ++i)
    norm.values[i] = std::sqrt(dxx.values[i] * dxx.values[i] + dxy.values[i] * dxy.values[i] +
                               dyy.values[i] * dyy.values[i] + dyx.values[i] * dyx.values[i]);
  return norm;
}

Plane truthPlane(const Image& truth) {
  Plane plane{truth.width(), truth.height(),
              std::vector<double>(std::size_t(truth.width()) * std::size_t(truth.height()))};
  for (int y = 0; y < truth.height(); ++y)
    for (int x = 0; x < truth.width(); ++x)
      plane.values[std::size_t(y) * std::size_t(truth.width()) + std::size_t(x)] = truth.at(x, y, 0);
  return plane;
}

}  // namespace

Result<DisparityScores> scoreDisparity(const Image& estimate, const Image& truth, double threshold, int border) {
  if (!(threshold > 0)) return makeError(ErrorCode::Usage, "scores: a BadPix threshold must be positive");
  LFCAM_TRY(sameSize(estimate, truth));
  DisparityScores scores;
  long bad = 0, farther = 0;
  double squares = 0;
  for (int y = border; y < truth.height() - border; ++y)
    for (int x = border; x < truth.width() - border; ++x) {
      const double t = truth.at(x, y, 0);
      if (!std::isfinite(t)) continue;
      const double e = estimate.at(x, y, 0);
      const double error = std::isfinite(e) ? std::abs(e - t) : std::abs(t) + 1;
      bad += error > threshold;
      farther += error > threshold && e < t;  // false for a missing estimate
      squares += error * error;
      ++scores.pixels;
    }
  if (scores.pixels == 0) return makeError(ErrorCode::Usage, "scores: no pixel with ground truth inside the border");
  scores.badPix = 100.0 * double(bad) / double(scores.pixels);
  scores.fartherShare = bad > 0 ? 100.0 * double(farther) / double(bad) : 0.0;
  scores.mse100 = 100.0 * squares / double(scores.pixels);
  return scores;
}

Image planarMask(const Image& truth) {
  const Plane curvature = hessianNorm(truthPlane(truth));
  Image mask(truth.width(), truth.height(), 1);
  for (int y = 0; y < truth.height(); ++y)
    for (int x = 0; x < truth.width(); ++x)
      mask.at(x, y, 0) = curvature.at(x, y) < kPlanarTolerance ? 1.0f : 0.0f;  // false for NaN
  return mask;
}

Result<double> bumpiness(const Image& estimate, const Image& truth, const Image& planes, int border) {
  LFCAM_TRY(sameSize(estimate, truth));
  if (!planes.empty()) LFCAM_TRY(sameSize(planes, truth));
  const Plane truthCurvature = hessianNorm(truthPlane(truth));  // where not finite, the truth says nothing
  Plane error = truthPlane(truth);
  for (int y = 0; y < truth.height(); ++y)
    for (int x = 0; x < truth.width(); ++x) {
      double& value = error.values[std::size_t(y) * std::size_t(truth.width()) + std::size_t(x)];
      value = double(estimate.at(x, y, 0)) - value;
    }
  const Plane roughness = hessianNorm(error);
  double sum = 0;
  long pixels = 0;
  for (int y = border; y < truth.height() - border; ++y)
    for (int x = border; x < truth.width() - border; ++x) {
      const double curvature = truthCurvature.at(x, y);
      const bool planar = planes.empty() ? curvature < kPlanarTolerance : planes.at(x, y, 0) != 0.0f;
      if (!planar || !std::isfinite(curvature)) continue;
      const double r = roughness.at(x, y);
      sum += std::isfinite(r) ? std::min(r, kBumpinessClip) : kBumpinessClip;
      ++pixels;
    }
  if (pixels == 0) return makeError(ErrorCode::Usage, "scores: no planar pixel inside the border");
  return 100.0 * sum / double(pixels);
}

Result<HciScores> scoreHci(const Image& estimate, const Image& truth, const Image& planes, int border) {
  HciScores scores;
  double* const badPix[] = {&scores.badPix001, &scores.badPix003, &scores.badPix007};
  const double thresholds[] = {0.01, 0.03, 0.07};
  for (int i = 0; i < 3; ++i) {
    LFCAM_ASSIGN_OR_RETURN(auto at, scoreDisparity(estimate, truth, thresholds[i], border));
    *badPix[i] = at.badPix;
    scores.mse100 = at.mse100;
    scores.pixels = at.pixels;
  }
  LFCAM_ASSIGN_OR_RETURN(auto rough, bumpiness(estimate, truth, planes, border));
  scores.bumpiness = rough;
  return scores;
}

std::string badPixKey(double threshold) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%g", threshold);
  return std::string("badpix_") + digits;
}

}  // namespace lfcam
