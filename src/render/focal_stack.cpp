// Focal stacks, refocus at a pixel, and focus conversions: focal_stack.hpp.
#include "lfcam/render/focal_stack.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/bilinear.hpp"
#include "core/parabola.hpp"

namespace lfcam {

std::vector<double> evenlySpaced(double first, double last, int n) {
  std::vector<double> values;
  for (int i = 0; i < n; ++i) values.push_back(n == 1 ? first : first + (last - first) * i / double(n - 1));
  return values;
}

Result<std::vector<double>> parseEvenlySpaced(const std::string& text, const std::string& option) {
  double first = 0, last = 0;
  int n = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf:%d%c", &first, &last, &n, &end) != 3 || !std::isfinite(first) ||
      !std::isfinite(last) || n < 1 || n > 100000)
    return makeError(ErrorCode::Usage, option + ": expected FIRST:LAST:COUNT (count 1 to 100000), got '" + text + "'");
  return evenlySpaced(first, last, n);
}

Status renderFocalStack(const LightField& lightField, const std::vector<double>& slopes, const SyntheticCamera& camera,
                        const RenderOptions& options,
                        const std::function<Status(int index, double slope, Image&& photo)>& sink) {
  SyntheticCamera slice = camera;
  for (std::size_t i = 0; i < slopes.size(); ++i) {
    slice.slope = slopes[i];
    LFCAM_ASSIGN_OR_RETURN(auto photo, renderSyntheticPhoto(lightField, slice, options));
    LFCAM_TRY(sink(int(i), slopes[i], std::move(photo)));
  }
  return {};
}

namespace {

// Bilinear sample of view (u, v), channel c at index position (px, py); false outside the view.
bool sampleView(const LightField& lightField, int u, int v, int c, double px, double py, double& value) {
  const int ns = lightField.ns(), nt = lightField.nt();
  if (!(px >= 0 && py >= 0 && px <= ns - 1 && py <= nt - 1)) return false;
  value = bilinearSample(lightField.plane(u, v, c), ns, nt, px, py);
  return true;
}

// Mean over the window of the variance across views of the samples refocusing at `slope` adds
// up at each pixel (channels summed); infinity when no pixel has two views.
double angularVariance(const LightField& lightField, int x, int y, int radius, double slope) {
  double total = 0;
  int pixels = 0;
  for (int wy = y - radius; wy <= y + radius; ++wy)
    for (int wx = x - radius; wx <= x + radius; ++wx) {
      if (wx < 0 || wy < 0 || wx >= lightField.ns() || wy >= lightField.nt()) continue;
      double variance = 0;
      bool enough = true;
      for (int c = 0; c < lightField.channels() && enough; ++c) {
        double sum = 0, sumSquares = 0;
        int count = 0;
        for (int v = 0; v < lightField.nv(); ++v)
          for (int u = 0; u < lightField.nu(); ++u) {
            if (lightField.hasWeight() && lightField.weightPlane(u, v)[std::size_t(wy) * lightField.ns() + wx] <= 0)
              continue;
            double value = 0;
            if (!sampleView(lightField, u, v, c, wx - lightField.uFromCentre(u) * slope,
                            wy - lightField.vFromCentre(v) * slope, value))
              continue;
            sum += value, sumSquares += value * value, ++count;
          }
        if (count < 2)
          enough = false;
        else
          variance += sumSquares / count - (sum / count) * (sum / count);
      }
      if (!enough) continue;
      total += variance, ++pixels;
    }
  return pixels ? total / pixels : INFINITY;
}

}  // namespace

Result<double> slopeAtPixel(const LightField& lightField, double x, double y, const FocusSearch& search) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "focus at a pixel: empty light field");
  if (!(x >= 0 && y >= 0 && x < lightField.ns() && y < lightField.nt()))
    return makeError(ErrorCode::Usage, "focus at a pixel: (" + std::to_string(x) + ", " + std::to_string(y) +
                                           ") lies outside the " + std::to_string(lightField.ns()) + "x" +
                                           std::to_string(lightField.nt()) + " image");
  if (lightField.shape().views() < 2)
    return makeError(ErrorCode::Usage, "focus at a pixel: a single view has no focus");
  double lowest = search.minSlope.value_or(lightField.metadata.disparityMin.value_or(-4.0));
  double highest = search.maxSlope.value_or(lightField.metadata.disparityMax.value_or(4.0));
  if (!(lowest < highest) || search.steps < 3 || search.radius < 0)
    return makeError(ErrorCode::Usage, "focus at a pixel: need a slope range min < max and at least 3 steps");
  const std::vector<double> slopes = evenlySpaced(lowest, highest, search.steps);
  std::vector<double> cost(slopes.size());
  for (std::size_t i = 0; i < slopes.size(); ++i)
    cost[i] = angularVariance(lightField, int(x), int(y), search.radius, slopes[i]);
  const std::size_t best = std::size_t(std::min_element(cost.begin(), cost.end()) - cost.begin());
  if (!std::isfinite(cost[best])) return makeError(ErrorCode::Usage, "focus at a pixel: no view sees that point");
  // Parabola through the best and its neighbours.
  double slope = slopes[best];
  if (best > 0 && best + 1 < slopes.size() && std::isfinite(cost[best - 1]) && std::isfinite(cost[best + 1])) {
    slope += parabolaVertex(cost[best - 1], cost[best], cost[best + 1]) * (slopes[1] - slopes[0]);
  }
  return slope;
}

Result<double> focusDistanceMmFromAlpha(const Optics& optics, double alpha) {
  if (!optics.focalLengthMm || !(*optics.focalLengthMm > 0) || !(optics.lensToMicrolensMm > 0))
    return makeError(ErrorCode::Usage, "focus distance: the light field's optics give no focal length");
  const double f = *optics.focalLengthMm, image = alpha * optics.lensToMicrolensMm;
  if (!(image > f)) return makeError(ErrorCode::Usage, "focus distance: that film plane focuses beyond infinity");
  return 1.0 / (1.0 / f - 1.0 / image);
}

Result<double> alphaFromFocusDistanceMm(const Optics& optics, double distanceMm) {
  if (!optics.focalLengthMm || !(*optics.focalLengthMm > 0) || !(optics.lensToMicrolensMm > 0))
    return makeError(ErrorCode::Usage, "focus distance: the light field's optics give no focal length");
  const double f = *optics.focalLengthMm;
  if (!(distanceMm > f)) return makeError(ErrorCode::Usage, "focus distance: an object nearer than f has no image");
  return 1.0 / (1.0 / f - 1.0 / distanceMm) / optics.lensToMicrolensMm;
}

}  // namespace lfcam
