// Tilted focus (tilted_focus.hpp): the plane from three points or a tilt, rendered by the slope-field
// kernel (slope_field_rows.hpp), and its float64 oracle.
#include "lfcam/render/tilted_focus.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "render/references.hpp"
#include "render/slope_field_rows.hpp"

namespace lfcam {

namespace {

FocusPlane centredPlane(const LightField& lightField) {
  FocusPlane plane;
  plane.centreX = 0.5 * lightField.ns();
  plane.centreY = 0.5 * lightField.nt();
  return plane;
}

std::string pointText(const ImagePoint& point) { return std::to_string(point[0]) + "," + std::to_string(point[1]); }

// Twice the signed area of the triangle, and its longest side: their ratio is its height over that side.
double crossOf(const std::array<ImagePoint, 3>& p) {
  return (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
}
double longestSide(const std::array<ImagePoint, 3>& p) {
  auto side = [&](int i, int j) { return std::hypot(p[j][0] - p[i][0], p[j][1] - p[i][1]); };
  return std::max({side(0, 1), side(0, 2), side(1, 2)});
}

}  // namespace

Result<std::array<ImagePoint, 3>> parseFocusPlanePoints(const std::string& text) {
  std::array<ImagePoint, 3> points{};
  char end = 0;
  const int read = std::sscanf(text.c_str(), "%lf,%lf:%lf,%lf:%lf,%lf%c", &points[0][0], &points[0][1], &points[1][0],
                               &points[1][1], &points[2][0], &points[2][1], &end);
  const bool finite = std::all_of(points.begin(), points.end(),
                                  [](const ImagePoint& p) { return std::isfinite(p[0]) && std::isfinite(p[1]); });
  if (read != 6 || !finite)
    return makeError(ErrorCode::Usage, "expected three points as X1,Y1:X2,Y2:X3,Y3, got '" + text + "'");
  return points;
}

Status checkFocusPlanePoints(const LightField& lightField, const std::array<ImagePoint, 3>& points) {
  for (const ImagePoint& point : points)
    if (!(point[0] >= 0 && point[0] < lightField.ns() && point[1] >= 0 && point[1] < lightField.nt()))
      return makeError(ErrorCode::Usage, "point " + pointText(point) + " lies outside the " +
                                             std::to_string(lightField.ns()) + "x" + std::to_string(lightField.nt()) +
                                             " image");
  // The triangle's height over its longest side: under a pixel, the points do not span a plane.
  if (!(std::abs(crossOf(points)) >= longestSide(points)))
    return makeError(ErrorCode::Usage, "the three points lie on one line: they span no plane");
  return {};
}

Result<FocusPlane> focusPlaneThroughPoints(const LightField& lightField, const std::array<ImagePoint, 3>& points,
                                           const FocusSearch& search) {
  LFCAM_TRY(checkFocusPlanePoints(lightField, points));
  const double ax = points[1][0] - points[0][0], ay = points[1][1] - points[0][1];
  const double bx = points[2][0] - points[0][0], by = points[2][1] - points[0][1];
  const double cross = crossOf(points);

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
  return refocusFilm(lightField, {.plane = plane}, nullptr, nullptr);
}

Image refocusTiltedReference(const LightField& lightField, const FocusPlane& plane) {
  return refocusSlopeFieldReference(lightField, [&plane](int x, int y) { return plane.slopeAt(x + 0.5, y + 0.5); });
}

}  // namespace lfcam
