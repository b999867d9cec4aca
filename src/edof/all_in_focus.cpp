// Extended depth of field by photomontage of a focal stack (all_in_focus.hpp).
#include "lfcam/edof/all_in_focus.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"
#include "lfcam/render/refocus.hpp"

namespace lfcam {

namespace {

// The focal stack's slices kept between the focus measure and the blend, at most.
constexpr std::size_t kHeldBytes = std::size_t(256) << 20;

// Focus measure of one slice: squared Laplacian of its luminance, window-averaged.
void focusMeasure(const Image& slice, int radius, float* out) {
  const Image grey = edof::luminance(slice);
  const int w = grey.width(), h = grey.height();
  std::vector<float> energy(grey.planeSize());
  edof::squaredLaplacian(grey, energy.data());
  boxFilter(energy.data(), out, w, h, radius);
}

// How many pixels take each of `slices` labels.
std::vector<std::size_t> labelCounts(const std::vector<int>& label, int slices) {
  std::vector<std::size_t> count(slices, 0);
  for (int l : label) ++count[l];
  return count;
}

}  // namespace

Result<AllInFocus> allInFocus(const LightField& lightField, const AllInFocusOptions& options) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "all-in-focus: the light field is empty");
  const int ns = lightField.ns(), nt = lightField.nt();
  const std::size_t n = lightField.shape().viewPixels();
  const Image* disparity = options.disparity;
  if (disparity && (disparity->width() != ns || disparity->height() != nt || disparity->channels() < 1))
    return makeError(ErrorCode::Usage, "all-in-focus: the depth map is " + std::to_string(disparity->width()) + "x" +
                                           std::to_string(disparity->height()) + " but the light field's views are " +
                                           std::to_string(ns) + "x" + std::to_string(nt));

  // 1. The focal stack's slopes.
  double dmin = lightField.metadata.disparityMin.value_or(-2.0), dmax = lightField.metadata.disparityMax.value_or(2.0);
  if (disparity) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < n; ++i) {
      const double d = disparity->plane(0)[i];
      if (std::isfinite(d)) lo = std::min(lo, d), hi = std::max(hi, d);
    }
    if (lo <= hi) dmin = lo, dmax = hi;
  }
  dmin = options.disparityMin.value_or(dmin);
  dmax = options.disparityMax.value_or(dmax);
  if (!(std::isfinite(dmin) && std::isfinite(dmax) && dmin <= dmax))
    return makeError(ErrorCode::Usage, "all-in-focus: the disparity range [" + std::to_string(dmin) + ", " +
                                           std::to_string(dmax) + "] is empty");
  const int views = std::max(lightField.nu(), lightField.nv());
  double step = options.sliceStep > 0 ? options.sliceStep : 1.0 / std::max(views - 1, 1);
  const int maxSlices = std::max(options.maxSlices, 1);
  if ((dmax - dmin) / step + 1 > maxSlices) step = (dmax - dmin) / std::max(maxSlices - 1, 1);
  const int slices = std::max(1, int(std::ceil((dmax - dmin) / step - 1e-9)) + 1);
  AllInFocus result;
  for (int k = 0; k < slices; ++k) result.slopes.push_back(dmin + k * step);

  // 2. A slice label per pixel. The slices refocused for it are kept for the blend (3) while they
  // fit in kHeldBytes, so that most are refocused once.
  std::vector<Image> held(slices);
  std::size_t heldBytes = 0;
  const auto hold = [&](int k, Image&& slice) {
    const std::size_t bytes = slice.pixels().size() * sizeof(float);
    if (heldBytes + bytes > kHeldBytes) return;
    held[k] = std::move(slice);
    heldBytes += bytes;
  };
  std::vector<int> label(n, slices / 2);
  if (disparity) {
    for (std::size_t i = 0; i < n; ++i) {
      const double d = disparity->plane(0)[i];
      if (std::isfinite(d)) label[i] = std::clamp(int(std::lround((d - dmin) / step)), 0, slices - 1);
    }
    if (slices > 1 && options.focusRadius >= 0) {
      // A depth map errs by a fraction of a slice step here and there (a few hundredths of a pixel
      // on aliased texture), enough to pick the neighbour of the right slice: of the nearest slice
      // and its two neighbours, keep the sharpest.
      const std::vector<std::size_t> count = labelCounts(label, slices);
      std::vector<int> candidates;
      std::vector<double> slopes;
      for (int k = 0; k < slices; ++k)
        if (count[k] > 0 || (k > 0 && count[k - 1] > 0) || (k + 1 < slices && count[k + 1] > 0))
          candidates.push_back(k), slopes.push_back(result.slopes[k]);
      std::vector<int> chosen(label);
      std::vector<float> best(n, -1.0f), focus(n);
      refocusEach(lightField, slopes, [&](std::size_t j, Image&& slice) {
        const int k = candidates[j];
        focusMeasure(slice, options.focusRadius, focus.data());
        for (std::size_t i = 0; i < n; ++i)
          if (std::abs(label[i] - k) <= 1 && focus[i] > best[i]) best[i] = focus[i], chosen[i] = k;
        hold(k, std::move(slice));
      });
      label = std::move(chosen);
    }
  } else if (slices > 1) {
    // Cost = minus the focus measure relative to its mean over the stack, pixel-major for the
    // optimisation: relative, so that faint texture (a backdrop) is judged by how its own
    // sharpness varies, not swamped by the penalties that strong texture elsewhere sets.
    edof::CostVolume volume(n * slices);
    std::vector<float> focus(n), mean(n, 0.0f);
    refocusEach(lightField, result.slopes, [&](std::size_t k, Image&& slice) {
      focusMeasure(slice, std::max(options.focusRadius, 0), focus.data());
      for (std::size_t i = 0; i < n; ++i) volume[i * slices + k] = focus[i], mean[i] += focus[i] / slices;
      hold(int(k), std::move(slice));
    });
    for (std::size_t i = 0; i < n; ++i) {
      const float inverse = 1.0f / std::max(mean[i], 1e-12f);
      for (int k = 0; k < slices; ++k) volume[i * slices + k] *= -inverse;
    }
    std::vector<float> continuous(n);
    if (options.smoothness > 0) {
      double contrast = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const float* c = &volume[i * slices];
        double sum = 0;
        for (int k = 0; k < slices; ++k) sum += c[k];
        contrast += sum / slices - *std::min_element(c, c + slices);
      }
      const double scale = std::max(contrast / double(n), 1e-20);
      const Image guide =
          edof::luminance(lightField.subApertureImage((lightField.nu() - 1) / 2, (lightField.nv() - 1) / 2));
      // The centre view is one ray per pixel and may be noisy; its edges matter only when they
      // stand well above that noise, hence the larger edge scale than depth's.
      const edof::CostVolume summed =
          edof::semiGlobalMatching(volume, ns, nt, slices, guide.plane(0), float(0.03 * scale * options.smoothness),
                                   float(0.6 * scale * options.smoothness), /*edgeScale=*/0.05f);
      edof::winnerTakesAll(summed, ns, nt, slices, continuous.data());
    } else {
      edof::winnerTakesAll(volume, ns, nt, slices, continuous.data());
    }
    for (std::size_t i = 0; i < n; ++i) label[i] = std::clamp(int(std::lround(continuous[i])), 0, slices - 1);
  }
  result.slope = Image(ns, nt, 1);
  for (std::size_t i = 0; i < n; ++i) result.slope.plane(0)[i] = float(result.slopes[label[i]]);

  // 3. Multi-band blending of the slices that some pixel chose.
  int levels = options.levels;
  if (levels <= 0) levels = std::clamp(int(std::floor(std::log2(std::max(std::min(ns, nt), 1)))) - 3, 1, 6);
  edof::PyramidBlender blender(ns, nt, lightField.channels(), levels);
  std::vector<float> mask(n);
  const auto blend = [&](int k, const Image& slice) {
    for (std::size_t i = 0; i < n; ++i) mask[i] = label[i] == k ? 1.0f : 0.0f;
    blender.add(slice, mask.data());
  };
  std::vector<int> missing;
  std::vector<double> missingSlopes;
  const std::vector<std::size_t> count = labelCounts(label, slices);
  for (int k = 0; k < slices; ++k) {
    if (count[k] == 0) continue;
    if (!held[k].empty()) {
      blend(k, held[k]);
      held[k] = Image();
    } else {
      missing.push_back(k), missingSlopes.push_back(result.slopes[k]);
    }
  }
  refocusEach(lightField, missingSlopes, [&](std::size_t j, Image&& slice) { blend(missing[j], slice); });
  result.photo = blender.result();
  return result;
}

}  // namespace lfcam
