// The photograph of a focused plenoptic image: scalar rendering, one pixel at a time.
#include "lfcam/focused/focused_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/bilinear.hpp"
#include "core/parallel.hpp"
#include "io/io_support.hpp"

namespace lfcam {

namespace {

// The micro-images whose centres lie within `radius` of an image point, as lattice indices.
class LensNeighbourhood {
 public:
  explicit LensNeighbourhood(const LensletGrid& grid)
      : grid_(grid), cos_(std::cos(grid.rotationRad)), sin_(std::sin(grid.rotationRad)) {}

  template <class Visit>
  void forEach(double x, double y, double radius, Visit&& visit) const {
    const double dx = x - grid_.origin[0], dy = y - grid_.origin[1];
    const double across = (cos_ * dx + sin_ * dy) / grid_.pitchX, down = (-sin_ * dx + cos_ * dy) / grid_.pitchY;
    const int j0 = std::max(0, int(std::floor(down - radius / grid_.pitchY)) - 1);
    const int j1 = std::min(grid_.rows - 1, int(std::ceil(down + radius / grid_.pitchY)) + 1);
    const int i0 = std::max(0, int(std::floor(across - radius / grid_.pitchX)) - 1);
    const int i1 = std::min(grid_.columns - 1, int(std::ceil(across + radius / grid_.pitchX)) + 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const auto c = grid_.centre(i, j);
        const double ex = x - c[0], ey = y - c[1];
        if (ex * ex + ey * ey <= radius * radius) visit(i, j, c);
      }
  }

 private:
  const LensletGrid& grid_;
  double cos_, sin_;
};

}  // namespace

Result<Image> renderFocused(const Image& image, const FocusedCalibration& calibration,
                            const FocusedRenderRequest& request) {
  if (image.width() != calibration.imageWidth || image.height() != calibration.imageHeight)
    return makeError(ErrorCode::Usage, "the image is " + std::to_string(image.width()) + "x" +
                                           std::to_string(image.height()) + ", its calibration describes " +
                                           std::to_string(calibration.imageWidth) + "x" +
                                           std::to_string(calibration.imageHeight));
  if (!(request.pixelsPerLens >= 1 && request.pixelsPerLens <= calibration.diameterPx()))
    return makeError(ErrorCode::Usage, "pixels per lens must be in [1, " +
                                           io::shortestNumber(calibration.diameterPx()) +
                                           "] (the micro-image diameter)");
  const double usable = 0.5 * calibration.diameterPx() - calibration.borderPx;
  const double shift = std::hypot(request.viewpoint[0], request.viewpoint[1]);
  if (!(request.aperture > 0 && request.aperture + shift <= 1 + 1e-9))
    return makeError(ErrorCode::Usage, "the aperture (" + io::shortestNumber(request.aperture) +
                                           ") and the viewpoint's distance from the centre (" +
                                           io::shortestNumber(shift) + ") must add up to at most 1");
  const FocusedPhotoFrame frame = focusedPhotoFrame(calibration, request.pixelsPerLens);
  if (request.virtualDepthMap &&
      (request.virtualDepthMap->width() != frame.width || request.virtualDepthMap->height() != frame.height))
    return makeError(ErrorCode::Usage, "the virtual depth map is " + std::to_string(request.virtualDepthMap->width()) +
                                           "x" + std::to_string(request.virtualDepthMap->height()) +
                                           ", the photograph " + std::to_string(frame.width) + "x" +
                                           std::to_string(frame.height));
  if (!request.virtualDepthMap && !(request.virtualDepth > 0 && std::isfinite(request.virtualDepth)))
    return makeError(ErrorCode::Usage, "the virtual depth must be positive");
  if (request.nearestLensOnly && !request.virtualDepthMap) {
    // The farthest point of a lattice cell from its centre, over v, must stay on the micro-image.
    const double cellRadius = calibration.grid.packing == Packing::Hexagonal
                                  ? calibration.diameterPx() / std::sqrt(3.0)
                                  : calibration.diameterPx() / std::sqrt(2.0);
    if (cellRadius / request.virtualDepth > usable)
      return makeError(ErrorCode::Usage, "virtual depth " + io::shortestNumber(request.virtualDepth) +
                                             ": its patches would reach past the micro-images; at least " +
                                             io::shortestNumber(std::ceil(cellRadius / usable * 100) / 100) +
                                             " is needed");
  }

  const double sign = calibration.orientationSign();
  const double radius = request.aperture * usable;
  const double shiftX = request.viewpoint[0] * usable, shiftY = request.viewpoint[1] * usable;
  const LensNeighbourhood lenses(calibration.grid);
  const int channels = image.channels();
  Image photo(frame.width, frame.height, channels);

  parallelFor(0, std::size_t(frame.height), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> sum(static_cast<std::size_t>(channels));
    for (std::size_t py = begin; py < end; ++py)
      for (int px = 0; px < frame.width; ++px) {
        const auto q = frame.imagePoint(px + 0.5, py + 0.5);
        const double v = request.virtualDepthMap ? request.virtualDepthMap->at(px, int(py), 0) : request.virtualDepth;
        std::fill(sum.begin(), sum.end(), 0.0);
        double total = 0;
        auto add = [&](double sx, double sy, double weight) {
          for (int c = 0; c < channels; ++c)
            sum[std::size_t(c)] +=
                weight * bilinearSample(image.plane(c), image.width(), image.height(), sx - 0.5, sy - 0.5);
          total += weight;
        };
        if (!(v > 0) || !std::isfinite(v)) {
          for (int c = 0; c < channels; ++c) photo.at(px, int(py), c) = 0;
          continue;
        }
        // The micro-image whose disc centre is nearest to S, the fallback where no disc holds S.
        double nearest = std::numeric_limits<double>::infinity();
        std::array<double, 2> nearestS{0, 0};
        bool anySharp = false;
        if (!request.nearestLensOnly && request.sharpLensTypes && calibration.lensTypes.size() > 1)
          for (const LensType& type : calibration.lensTypes)
            anySharp |= v >= type.minVirtualDepth && v <= type.maxVirtualDepth;
        // S lies in the disc when |Q - C - sign v shift| <= v radius.
        const double cx = q[0] - sign * v * shiftX, cy = q[1] - sign * v * shiftY;
        lenses.forEach(cx, cy, std::max(v * radius, calibration.diameterPx()),
                       [&](int i, int j, const std::array<double, 2>& c) {
                         const double sx = c[0] + sign * (q[0] - c[0]) / v, sy = c[1] + sign * (q[1] - c[1]) / v;
                         const double rho = std::hypot(sx - c[0] - shiftX, sy - c[1] - shiftY) / radius;
                         if (rho < nearest) {
                           nearest = rho;
                           nearestS = {sx, sy};
                         }
                         if (request.nearestLensOnly || rho >= 1) return;
                         if (anySharp) {
                           const LensType& type = calibration.lensTypes[std::size_t(calibration.lensType(i, j))];
                           if (v < type.minVirtualDepth || v > type.maxVirtualDepth) return;
                         }
                         const double w = 1 - rho * rho;
                         add(sx, sy, w * w);
                       });
        if (total == 0 && std::isfinite(nearest)) add(nearestS[0], nearestS[1], 1);
        for (int c = 0; c < channels; ++c)
          photo.at(px, int(py), c) = total > 0 ? float(sum[std::size_t(c)] / total) : 0.0f;
      }
  });
  return photo;
}

}  // namespace lfcam
