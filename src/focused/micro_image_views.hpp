// The micro-images that see a point Q of a focused plenoptic image at virtual depth v, and where:
// S = C + orientation (Q - C) / v (focused_calibration.hpp), kept when S lies in the sampled disc
// of the micro-image (its usable radius times `aperture`, centred `viewpoint` shares of that radius
// from C). Shared by rendering and depth.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"

#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam::focused_detail {

// Usage error unless `image` is the size `calibration` describes.
inline Status checkImageSize(const Image& image, const FocusedCalibration& calibration) {
  if (image.width() == calibration.imageWidth && image.height() == calibration.imageHeight) return {};
  return makeError(ErrorCode::Usage, "the image is " + std::to_string(image.width()) + "x" +
                                         std::to_string(image.height()) + ", its calibration describes " +
                                         std::to_string(calibration.imageWidth) + "x" +
                                         std::to_string(calibration.imageHeight));
}

struct MicroImageSample {
  int i = 0, j = 0;     // the micro-image
  double x = 0, y = 0;  // S, image pixels
  double rho = 0;       // S's distance from the disc's centre over its radius
};

class MicroImageViews {
 public:
  MicroImageViews(const FocusedCalibration& calibration, double aperture = 1, std::array<double, 2> viewpoint = {0, 0})
      : grid_(calibration.grid),
        sign_(calibration.orientationSign()),
        usable_(0.5 * calibration.diameterPx() - calibration.borderPx),
        radius_(aperture * usable_),
        shiftX_(viewpoint[0] * usable_),
        shiftY_(viewpoint[1] * usable_),
        cos_(std::cos(grid_.rotationRad)),
        sin_(std::sin(grid_.rotationRad)) {
    // The centres once: LensletGrid::centre turns and warps the lattice at every call.
    centres_.reserve(std::size_t(grid_.columns) * std::size_t(grid_.rows));
    for (int j = 0; j < grid_.rows; ++j) {
      rowSpans_.push_back({std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()});
      for (int i = 0; i < grid_.columns; ++i) {
        centres_.push_back(grid_.centre(i, j));
        rowSpans_.back() = {std::min(rowSpans_.back()[0], centres_.back()[1]),
                            std::max(rowSpans_.back()[1], centres_.back()[1])};
      }
    }
  }

  double usableRadius() const { return usable_; }
  int columns() const { return grid_.columns; }
  // Lens (i, j)'s centre at j * columns + i.
  const std::vector<std::array<double, 2>>& centres() const { return centres_; }
  // The least and greatest y of lattice row j's centres: which rows of lenses reach a band of rows.
  const std::vector<std::array<double, 2>>& rowSpans() const { return rowSpans_; }

  // The micro-image whose centre is nearest the image point (x, y), {-1, -1} far off the grid.
  std::array<int, 2> nearestLens(double x, double y) const {
    const auto s = visitDiscs(x, y, 1, 0, 0, [](const MicroImageSample&) {});
    return {s.i, s.j};
  }

  // visit(sample) for each micro-image whose disc holds S (rho < 1); returns the sample of the one
  // whose disc centre is nearest S (rho may be >= 1; i = -1 when the grid has none near).
  template <class Visit>
  MicroImageSample forEach(double qx, double qy, double v, Visit&& visit) const {
    return visitDiscs(qx, qy, v, shiftX_, shiftY_, visit);
  }

 private:
  // forEach with the discs moved by (shiftX, shiftY) from the centres.
  template <class Visit>
  MicroImageSample visitDiscs(double qx, double qy, double v, double shiftX, double shiftY, Visit&& visit) const {
    // S is in the disc when |Q - sign v shift - C| < v radius.
    const double cx = qx - sign_ * v * shiftX, cy = qy - sign_ * v * shiftY;
    const double reach = std::max(v * radius_, grid_.pitchX);
    MicroImageSample nearest;
    nearest.i = -1;
    nearest.rho = std::numeric_limits<double>::infinity();
    const double dx = cx - grid_.origin[0], dy = cy - grid_.origin[1];
    const double across = (cos_ * dx + sin_ * dy) / grid_.pitchX, down = (-sin_ * dx + cos_ * dy) / grid_.pitchY;
    const int j0 = std::max(0, int(std::floor(down - reach / grid_.pitchY)) - 1);
    const int j1 = std::min(grid_.rows - 1, int(std::ceil(down + reach / grid_.pitchY)) + 1);
    const int i0 = std::max(0, int(std::floor(across - reach / grid_.pitchX)) - 1);
    const int i1 = std::min(grid_.columns - 1, int(std::ceil(across + reach / grid_.pitchX)) + 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const auto& c = centres_[std::size_t(j) * std::size_t(grid_.columns) + std::size_t(i)];
        const double ex = cx - c[0], ey = cy - c[1], distance2 = ex * ex + ey * ey;
        if (distance2 > reach * reach) continue;
        MicroImageSample s{i, j, c[0] + sign_ * (qx - c[0]) / v, c[1] + sign_ * (qy - c[1]) / v,
                           std::sqrt(distance2) / (v * radius_)};  // hypot took a third of the render
        if (s.rho < nearest.rho) nearest = s;
        if (s.rho < 1) visit(s);
      }
    return nearest;
  }

  const LensletGrid& grid_;
  double sign_, usable_, radius_, shiftX_, shiftY_, cos_, sin_;
  std::vector<std::array<double, 2>> centres_;  // lens (i, j)'s at j * columns + i
  std::vector<std::array<double, 2>> rowSpans_;
};

}  // namespace lfcam::focused_detail
