// Tilted focus (tilted_focus.hpp): the plane from three points or a tilt, the fast per-pixel
// slope-field kernel, and its float64 oracle.
#include "lfcam/tilted_focus.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "render/bilinear_taps.hpp"
#include "render/references.hpp"
#include "render/row_blocks.hpp"
#include "render/shift_and_add_rows.hpp"

namespace lfcam {

namespace {

FocusPlane centredPlane(const LightField& lightField) {
  FocusPlane plane;
  plane.centreX = 0.5 * lightField.ns();
  plane.centreY = 0.5 * lightField.nt();
  return plane;
}

std::string pointText(const ImagePoint& point) { return std::to_string(point[0]) + "," + std::to_string(point[1]); }

// Output rows [y0, y1): each view in turn adds its four bilinear taps at every pixel's own shift
// into float32 accumulators that stay in cache while the views stream through (the order of
// refocus.cpp's fast kernel; only the shift is per pixel here, so its bilinear coefficients are).
void refocusTiltedRows(const LightField& lightField, const FocusPlane& plane, int y0, int y1, Image& out) {
  const int ns = lightField.ns(), nt = lightField.nt(), channels = lightField.channels();
  const int rows = y1 - y0;
  // One (rows x ns) plane per channel, then one for the weight sum.
  std::vector<float> accumulator(std::size_t(channels + 1) * rows * ns, 0.0f);
  auto accumulatorRow = [&](int plane, int y) {
    return accumulator.data() + (std::size_t(plane) * rows + (y - y0)) * ns;
  };
  std::vector<const float*> viewPlanes(channels);
  for (int v = 0; v < lightField.nv(); ++v) {
    const double vc = lightField.vFromCentre(v);
    for (int u = 0; u < lightField.nu(); ++u) {
      const double uc = lightField.uFromCentre(u);
      for (int c = 0; c < channels; ++c) viewPlanes[c] = lightField.plane(u, v, c);
      for (int y = y0; y < y1; ++y) {
        float* weightRow = accumulatorRow(channels, y);
        for (int x = 0; x < ns; ++x) {
          const double slope = plane.slopeAt(x + 0.5, y + 0.5);
          if (!std::isfinite(slope)) continue;
          forEachBilinearTap(lightField, u, v, x, y, axisShift(uc, slope, ns), axisShift(vc, slope, nt),
                             [&](int row, int column, double w) {
                               const float tapWeight = float(w);
                               const std::size_t at = std::size_t(row) * ns + column;
                               weightRow[x] += tapWeight;
                               for (int c = 0; c < channels; ++c)
                                 accumulatorRow(c, y)[x] += tapWeight * viewPlanes[c][at];
                             });
        }
      }
    }
  }
  // Divide by the weight of the rays that arrived (section 5.2).
  for (int y = y0; y < y1; ++y)
    for (int c = 0; c < channels; ++c)
      normaliseRow(out.row(y, c), accumulatorRow(c, y), accumulatorRow(channels, y), ns);
}

}  // namespace

Result<FocusPlane> focusPlaneThroughPoints(const LightField& lightField, const std::array<ImagePoint, 3>& points,
                                           const FocusSearch& search) {
  for (const ImagePoint& point : points)
    if (!(point[0] >= 0 && point[0] < lightField.ns() && point[1] >= 0 && point[1] < lightField.nt()))
      return makeError(ErrorCode::Usage, "point " + pointText(point) + " lies outside the " +
                                             std::to_string(lightField.ns()) + "x" + std::to_string(lightField.nt()) +
                                             " image");
  // The triangle's height over its longest side: under a pixel, the points do not span a plane.
  const double ax = points[1][0] - points[0][0], ay = points[1][1] - points[0][1];
  const double bx = points[2][0] - points[0][0], by = points[2][1] - points[0][1];
  const double cross = ax * by - ay * bx;
  const double longest = std::max({std::hypot(ax, ay), std::hypot(bx, by), std::hypot(bx - ax, by - ay)});
  if (!(std::abs(cross) >= longest))
    return makeError(ErrorCode::Usage, "the three points lie on one line: they span no plane");

  std::array<double, 3> slopes{};
  for (int i = 0; i < 3; ++i) {
    LFCAM_ASSIGN_OR_RETURN(slopes[i], slopeAtPixel(lightField, points[i][0], points[i][1], search));
  }
  // Solve [a; b] [gradientX, gradientY]' = differences of the slopes (Cramer's rule).
  const double ds1 = slopes[1] - slopes[0], ds2 = slopes[2] - slopes[0];
  FocusPlane plane = centredPlane(lightField);
  plane.gradientX = (ds1 * by - ay * ds2) / cross;
  plane.gradientY = (ax * ds2 - ds1 * bx) / cross;
  plane.slope =
      slopes[0] + plane.gradientX * (plane.centreX - points[0][0]) + plane.gradientY * (plane.centreY - points[0][1]);
  return plane;
}

FocusPlane focusPlaneFromTilt(const LightField& lightField, double slope, double tilt, double directionDeg) {
  FocusPlane plane = centredPlane(lightField);
  const double perPixel = tilt / std::max(1, lightField.ns()), direction = directionDeg * std::numbers::pi / 180;
  plane.slope = slope;
  plane.gradientX = perPixel * std::cos(direction);
  plane.gradientY = perPixel * std::sin(direction);
  return plane;
}

Image refocusTilted(const LightField& lightField, const FocusPlane& plane) {
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns, shape.nt, shape.channels);
  if (lightField.empty()) return out;
  forEachRowBlock(shape.nt, shape.ns, shape.channels + 1,
                  [&](int y0, int y1) { refocusTiltedRows(lightField, plane, y0, y1, out); });
  return out;
}

Image refocusTiltedReference(const LightField& lightField, const FocusPlane& plane) {
  return refocusSlopeFieldReference(lightField, [&plane](int x, int y) { return plane.slopeAt(x + 0.5, y + 0.5); });
}

}  // namespace lfcam
