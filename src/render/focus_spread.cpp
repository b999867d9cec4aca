// Focus spread (focus_spread.hpp): a slope per pixel from the disparity map, clamped into the range,
// rendered by the slope-field kernel (slope_field_rows.hpp) without the rays of nearer surfaces.
#include "lfcam/focus_spread.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lfcam/parallel.hpp"
#include "render/slope_field_rows.hpp"

namespace lfcam {

namespace {

// What each view sees nearest at each of its pixels: the centre's disparity map warped into view
// (u, v) (a surface of disparity d at centre pixel x lies at x - u d there), each sample splatted
// onto the 2 x 2 pixels around where it lands, the nearest kept. Pixels no sample reaches (seen
// only from the side) are -infinity: nothing occludes there. nearest[(v nu + u) n + p].
std::vector<float> nearestSeenPerView(const LightField& lightField, const Image& disparity) {
  const int ns = lightField.ns(), nt = lightField.nt(), nu = lightField.nu();
  const std::size_t n = std::size_t(ns) * nt, views = std::size_t(nu) * lightField.nv();
  std::vector<float> nearest(views * n, -std::numeric_limits<float>::infinity());
  parallelFor(0, views, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const double uc = lightField.uFromCentre(int(view % nu)), vc = lightField.vFromCentre(int(view / nu));
      float* seen = nearest.data() + view * n;
      for (int y = 0; y < nt; ++y)
        for (int x = 0; x < ns; ++x) {
          const float d = disparity.at(x, y, 0);
          const double column = std::floor(x - uc * d), row = std::floor(y - vc * d);
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
              const double c = column + i, r = row + j;
              if (c < 0 || c >= ns || r < 0 || r >= nt) continue;
              float& at = seen[std::size_t(r) * ns + std::size_t(c)];
              at = std::max(at, d);
            }
        }
    }
  });
  return nearest;
}

}  // namespace

Result<Image> refocusSpread(const LightField& lightField, const Image& disparity, double farSlope, double nearSlope) {
  if (disparity.width() != lightField.ns() || disparity.height() != lightField.nt() || disparity.channels() != 1)
    return makeError(ErrorCode::Usage, "focus spread: the disparity map is " + std::to_string(disparity.width()) + "x" +
                                           std::to_string(disparity.height()) + "x" +
                                           std::to_string(disparity.channels()) + ", the views " +
                                           std::to_string(lightField.ns()) + "x" + std::to_string(lightField.nt()) +
                                           " (one channel needed)");
  if (!(std::isfinite(farSlope) && std::isfinite(nearSlope) && nearSlope >= farSlope))
    return makeError(ErrorCode::Usage, "focus spread: the near end of the range (slope " + std::to_string(nearSlope) +
                                           ") lies behind its far end (slope " + std::to_string(farSlope) +
                                           "); slopes grow towards the camera");
  for (float d : disparity.pixels())
    if (!std::isfinite(d)) return makeError(ErrorCode::Usage, "focus spread: the disparity map has non-finite values");
  if (lightField.empty()) return Image(lightField.ns(), lightField.nt(), lightField.channels());

  const std::vector<float> nearest = nearestSeenPerView(lightField, disparity);
  const int ns = lightField.ns(), nu = lightField.nu();
  const std::size_t n = std::size_t(ns) * lightField.nt();
  const float* map = disparity.plane(0);
  auto slopeAt = [&](int x, int y) { return std::clamp(double(map[std::size_t(y) * ns + x]), farSlope, nearSlope); };
  auto keep = [&](int u, int v, int row, int column, int x, int y) {
    return nearest[(std::size_t(v) * nu + u) * n + std::size_t(row) * ns + column] <=
           map[std::size_t(y) * ns + x] + float(kOccluderMargin);
  };
  return refocusSlopeField(lightField, slopeAt, keep);
}

}  // namespace lfcam
