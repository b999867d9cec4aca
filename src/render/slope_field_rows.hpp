// The fast kernel of a refocus whose slope changes from pixel to pixel (tilted focus,
// tilted_focus.hpp; focus spread, focus_spread.hpp), with an optional test per tap that leaves a
// ray out (an occluder). The float64 oracle is refocusSlopeFieldReference (references.hpp).
// Internal to the library.
#pragma once

#include <cmath>
#include <type_traits>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "render/bilinear_taps.hpp"
#include "render/occluders.hpp"
#include "render/ray_paths.hpp"
#include "render/row_blocks.hpp"
#include "render/shift_and_add_rows.hpp"

namespace lfcam {

// A tap test that keeps every ray.
struct KeepEveryTap {
  bool operator()(int, int, int, int, int, int) const { return true; }
};

// Output rows [y0, y1): each view in turn adds its four bilinear taps at every pixel's own shift
// into float32 accumulators that stay in cache while the views stream through (the order of
// refocus.cpp's fast kernel; only the shift is per pixel here, so its bilinear coefficients are).
// slopeAt(x, y) is the slope of output pixel (x, y) (pixel indices; not finite: the pixel is 0);
// keep(u, v, row, column, x, y) says whether the tap at (column, row) of view (u, v) counts for it;
// a pixel whose every tap it leaves out takes them all (the test misjudged that pixel: with an
// estimated depth map, a pixel read as farther than every surface its rays meet). viewWeights, when
// given, is the aperture's weight of each view (index v nu + u; views of weight 0 are skipped).
template <typename SlopeAt, typename Keep>
void refocusSlopeFieldRows(const LightField& lightField, const SlopeAt& slopeAt, const Keep& keep,
                           const std::vector<float>* viewWeights, int y0, int y1, Image& out) {
  const int ns = lightField.ns(), nt = lightField.nt(), channels = lightField.channels();
  const int rows = y1 - y0;
  // One (rows x ns) plane per channel, then one for the weight sum.
  std::vector<float> accumulator(std::size_t(channels + 1) * rows * ns, 0.0f);
  auto accumulatorRow = [&](int plane, int y) {
    return accumulator.data() + (std::size_t(plane) * rows + (y - y0)) * ns;
  };
  auto apertureWeight = [&](int u, int v) {
    return viewWeights ? (*viewWeights)[std::size_t(v) * lightField.nu() + u] : 1.0f;
  };
  std::vector<const float*> viewPlanes(channels);
  for (int v = 0; v < lightField.nv(); ++v) {
    const double vc = lightField.vFromCentre(v);
    for (int u = 0; u < lightField.nu(); ++u) {
      const double uc = lightField.uFromCentre(u);
      const float aperture = apertureWeight(u, v);
      if (aperture == 0.0f) continue;
      for (int c = 0; c < channels; ++c) viewPlanes[c] = lightField.plane(u, v, c);
      for (int y = y0; y < y1; ++y) {
        float* weightRow = accumulatorRow(channels, y);
        for (int x = 0; x < ns; ++x) {
          const double slope = slopeAt(x, y);
          if (!std::isfinite(slope)) continue;
          forEachBilinearTap(lightField, u, v, x, y, axisShift(uc, slope, ns), axisShift(vc, slope, nt),
                             [&](int row, int column, double w) {
                               if (!keep(u, v, row, column, x, y)) return;
                               const float tapWeight = aperture * float(w);
                               const std::size_t at = std::size_t(row) * ns + column;
                               weightRow[x] += tapWeight;
                               for (int c = 0; c < channels; ++c)
                                 accumulatorRow(c, y)[x] += tapWeight * viewPlanes[c][at];
                             });
        }
      }
    }
  }
  if constexpr (!std::is_same_v<Keep, KeepEveryTap>)
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < ns; ++x) {
        const double slope = slopeAt(x, y);
        if (accumulatorRow(channels, y)[x] != 0.0f || !std::isfinite(slope)) continue;
        for (int v = 0; v < lightField.nv(); ++v)
          for (int u = 0; u < lightField.nu(); ++u) {
            const float aperture = apertureWeight(u, v);
            if (aperture == 0.0f) continue;
            forEachBilinearTap(lightField, u, v, x, y, axisShift(lightField.uFromCentre(u), slope, ns),
                               axisShift(lightField.vFromCentre(v), slope, nt), [&](int row, int column, double w) {
                                 const std::size_t at = std::size_t(row) * ns + column;
                                 const float tapWeight = aperture * float(w);
                                 accumulatorRow(channels, y)[x] += tapWeight;
                                 for (int c = 0; c < channels; ++c)
                                   accumulatorRow(c, y)[x] += tapWeight * lightField.plane(u, v, c)[at];
                               });
          }
      }
  // Divide by the weight of the rays that arrived (section 5.2).
  for (int y = y0; y < y1; ++y)
    for (int c = 0; c < channels; ++c)
      normaliseRow(out.row(y, c), accumulatorRow(c, y), accumulatorRow(channels, y), ns);
}

// The photograph of refocusSlopeFieldRows over the whole image, threaded over blocks of rows.
template <typename SlopeAt, typename Keep = KeepEveryTap>
Image refocusSlopeField(const LightField& lightField, const SlopeAt& slopeAt, const Keep& keep = {},
                        const std::vector<float>* viewWeights = nullptr) {
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns, shape.nt, shape.channels);
  if (lightField.empty()) return out;
  forEachRowBlock(shape.nt, shape.ns, shape.channels + 1,
                  [&](int y0, int y1) { refocusSlopeFieldRows(lightField, slopeAt, keep, viewWeights, y0, y1, out); });
  return out;
}

// The photograph of `film` (a tilted plane, or a range with the rays `occluders` hide left out),
// through the aperture's weight of each view (nullptr: the whole lens): film_refocus.cpp.
Image refocusFilm(const LightField& lightField, const FilmSlopes& film, const Occluders* occluders,
                  const std::vector<float>* viewWeights);

}  // namespace lfcam
