// calibrateGrid: preparation of the image, a first lattice, centres grown outwards from the
// middle with a refit at each step, and the final grid (calibrate.hpp, docs/design.md).
#include "lfcam/calibrate/calibrate.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "calibrate/calibrate_internal.hpp"
#include "core/bilinear.hpp"
#include "core/box_filter.hpp"
#include "core/parallel.hpp"

namespace lfcam {

using calibrate_detail::CentreEstimate;
using calibrate_detail::Lattice;
using calibrate_detail::LatticeFit;
using calibrate_detail::Sample;

namespace {

// A scene raw: divided by its local mean (over about two microlenses each way), so that every
// microlens image looks like a white one whatever the scene's brightness there.
void flattenScene(Image& work, double pitch) {
  const int radius = std::max(2, int(std::lround(pitch)));
  Image mean(work.width(), work.height(), 1);
  boxFilter(work.plane(0), mean.plane(0), work.width(), work.height(), radius);
  float floor = 0;
  for (float v : mean.pixels()) floor = std::max(floor, v);
  floor *= 1e-3f;
  parallelFor(0, work.planeSize(), 1 << 16, [&](std::size_t begin, std::size_t end) {
    float* w = work.plane(0);
    const float* m = mean.plane(0);
    for (std::size_t k = begin; k < end; ++k) w[k] = w[k] / std::max(m[k], floor);
  });
}

// Share of the brightest microlens images' contrast a scene's microlens image needs to be fitted.
constexpr double kSceneSignalShare = 0.3;

// max - min of a one-channel image over the square of half-side `radius` around (x, y), clipped.
double windowContrast(const Image& image, double x, double y, double radius) {
  const int x0 = std::max(0, int(std::floor(x - radius))), x1 = std::min(image.width(), int(std::ceil(x + radius)));
  const int y0 = std::max(0, int(std::floor(y - radius))), y1 = std::min(image.height(), int(std::ceil(y + radius)));
  float lo = INFINITY, hi = -INFINITY;
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) {
      lo = std::min(lo, image.at(px, py, 0));
      hi = std::max(hi, image.at(px, py, 0));
    }
  return hi > lo ? hi - lo : 0.0;
}

// Microlenses averaged each way (2 reach + 1) by combAverage.
constexpr int kCombReach = 3;
// A flattened scene clipped here (a share of the local mean): the whole lit disc of a microlens
// image weighs alike, so the dark parts of the specimen inside it do not pull its centre (0.2 to
// 0.5 agree within 0.05 px on lfm-guv; docs/design.md).
constexpr float kSceneClip = 0.35f;

// Each pixel replaced by the mean of the pixels a whole number of lattice vectors away (up to
// `reach` along each), those inside the image: every microlens image becomes the average of its
// neighbourhood's. A scene's content differs from microlens to microlens and averages out; their
// shared aperture stays, so the centres measure the microlenses, not the specimen under them.
Image combAverage(const Image& work, const Lattice& l, int reach) {
  const int width = work.width(), height = work.height();
  const auto o = l.centre(0, 0), a = l.centre(1, 0), b = l.centre(0, 1);
  Image out = work.copy(), along(width, height, 1);
  for (const std::array<double, 2> v : {std::array{a[0] - o[0], a[1] - o[1]}, std::array{b[0] - o[0], b[1] - o[1]}}) {
    std::swap(out, along);
    parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
      const float* in = along.plane(0);
      for (std::size_t y = begin; y < end; ++y)
        for (int x = 0; x < width; ++x) {
          float sum = 0;
          int count = 0;
          for (int q = -reach; q <= reach; ++q) {
            const double sx = x + q * v[0], sy = double(y) + q * v[1];
            if (sx < 0 || sy < 0 || sx > width - 1 || sy > height - 1) continue;
            sum += bilinearSample(in, width, height, sx, sy);
            ++count;
          }
          out.plane(0)[y * width + x] = sum / count;
        }
    });
  }
  return out;
}

// Index ranges of the lattice points whose centres may lie in the image.
struct IndexBox {
  int k0 = 0, k1 = -1, n0 = 0, n1 = -1;
};

IndexBox indexBoxOfImage(const Lattice& l, int width, int height) {
  const double c = std::cos(l.theta), s = std::sin(l.theta);
  double aLo = INFINITY, aHi = -INFINITY, bLo = INFINITY, bHi = -INFINITY;
  for (const auto& [x, y] :
       {std::array<double, 2>{0, 0}, {double(width), 0}, {0, double(height)}, {double(width), double(height)}}) {
    const double dx = x - l.ox, dy = y - l.oy;
    const double a = (c * dx + s * dy) / l.pitchX, b = (-s * dx + c * dy) / l.pitchY;
    aLo = std::min(aLo, a);
    aHi = std::max(aHi, a);
    bLo = std::min(bLo, b);
    bHi = std::max(bHi, b);
  }
  return {int(std::floor(aLo)) - 1, int(std::ceil(aHi)) + 1, int(std::floor(bLo)) - 1, int(std::ceil(bHi)) + 1};
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The start of the growth: the microlens nearest the image's centre (highest contrast of a few
// hill climbs).
CentreEstimate findSeed(const Image& smooth, const Lattice& lattice, double radius, double relax) {
  CentreEstimate best;
  const double step = lattice.pitchX / 3;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const CentreEstimate e = calibrate_detail::refineCentre(smooth, 0.5 * smooth.width() + dx * step,
                                                              0.5 * smooth.height() + dy * step, radius, 60, relax);
      if (e.ok && (!best.ok || e.contrast > best.contrast)) best = e;
    }
  return best;
}

}  // namespace

// Measures the centres and fits the lattice, starting from `lattice`.
Result<Calibration> calibrateFrom(const Image& image, const calibrate_detail::PhaseGains& gains, Lattice lattice,
                                  const CalibrationOptions& options, const std::string& where) {
  if (lattice.pitchX < 3 || lattice.pitchY < 2)
    return makeError(ErrorCode::Format, where + ": the microlens pitch found (" + std::to_string(lattice.pitchX) +
                                            " px) is too small to calibrate");

  // Centres in two steps: an iterated centroid in a disc of half the neighbour distance (robust
  // from a guess a quarter pitch off), then, except for pinhole spots whose centroid is already
  // exact, the centre of symmetry over a slightly larger disc (unbiased whatever the shape of the
  // microlens images, which fill square or hexagonal cells and whose flat tops carry no
  // information for a centroid).
  const bool pinhole = options.target == CalibrationTarget::Pinhole;
  // A scene is flattened, clipped and comb-averaged between the preparation and the smoothing
  // (with this lattice's vectors); otherwise both are one pass.
  const bool scene = options.target == CalibrationTarget::Scene;
  // A scene's unflattened preparation stays for the signal gate below.
  const Image signal =
      scene ? calibrate_detail::prepareRegion(image, options, gains, 0, 0, image.width(), image.height(), false)
            : Image();
  const Image smooth = [&] {
    if (!scene)
      return calibrate_detail::prepareRegion(image, options, gains, 0, 0, image.width(), image.height(), true);
    Image work = signal.copy();
    flattenScene(work, lattice.pitchX);
    for (float& v : work.pixels()) v = std::min(v, kSceneClip);
    work = combAverage(work, lattice, kCombReach);
    return calibrate_detail::smoothBinomial(work);
  }();
  const double spacing = lattice.neighbourDistance();
  const double centroidRadius = 0.5 * spacing, symmetricRadius = 0.75 * spacing;
  const double relax = pinhole ? 1.0 : 1.5;  // a flat disc's centroid moves half-way per step
  const double minContrast = options.target == CalibrationTarget::Scene ? 0.15 : 0.3;
  const CentreEstimate seed = findSeed(smooth, lattice, centroidRadius, relax);
  if (!seed.ok) return makeError(ErrorCode::Format, where + ": no microlens image found near the centre");
  lattice.ox = seed.x;
  lattice.oy = seed.y;

  // Grow: measure the microlenses within `reach` lattice steps of the seed, refit, widen.
  std::vector<Sample> samples, present;
  LatticeFit fit;
  for (int reach = 3;; reach *= 4) {
    IndexBox box = indexBoxOfImage(lattice, smooth.width(), smooth.height());
    const bool last = box.k0 >= -reach && box.n0 >= -reach && box.k1 <= reach && box.n1 <= reach;
    box = {std::max(box.k0, -reach), std::min(box.k1, reach), std::max(box.n0, -reach), std::min(box.n1, reach)};
    std::vector<Sample> predicted;
    for (int n = box.n0; n <= box.n1; ++n)
      for (int k = box.k0; k <= box.k1; ++k) {
        const auto c = lattice.centre(k, n);
        if (c[0] - centroidRadius - 1 < 0 || c[1] - centroidRadius - 1 < 0 ||
            c[0] + centroidRadius + 1 > smooth.width() || c[1] + centroidRadius + 1 > smooth.height())
          continue;
        predicted.push_back({k, n, c[0], c[1]});
      }
    // When there are many more microlenses than the fit needs, every stride-th one each way only:
    // before the last step, those alone (they only predict further out); at the last step all are
    // found (the extent), but only those get the costly sub-pixel centre.
    const int stride = options.fitCentres > 0
                           ? std::max(1, int(std::floor(std::sqrt(double(predicted.size()) / options.fitCentres))))
                           : 1;
    std::vector<CentreEstimate> rough(predicted.size()), fine(predicted.size());
    // Hexagonal images fill most of the symmetric window with their six neighbours, whose ramps
    // about their own centres bias a single ramp (about 1e-4 in pitch); square ones less, and the
    // real square lfm-guv images agree better with napari-LF under the single ramp (docs/design.md).
    const std::vector<std::array<double, 2>> neighbours =
        lattice.packing == Packing::Hexagonal ? lattice.neighbourOffsets() : std::vector<std::array<double, 2>>{};
    parallelFor(0, predicted.size(), 64, [&](std::size_t begin, std::size_t end) {
      for (std::size_t m = begin; m < end; ++m) {
        const bool sampled = stride == 1 || (predicted[m].k % stride == 0 && predicted[m].n % stride == 0);
        if (!last && !sampled) continue;
        // Until the last step the centroid alone is enough to predict further out.
        rough[m] = calibrate_detail::refineCentre(smooth, predicted[m].x, predicted[m].y, centroidRadius, 20, relax,
                                                  pinhole ? 1e-3 : 0.01);
        if (!rough[m].ok) continue;
        if (!sampled) continue;  // fine[m] stays not ok
        if (pinhole || !last) {
          fine[m] = rough[m];
          continue;
        }
        fine[m] = calibrate_detail::refineSymmetric(smooth, rough[m].x, rough[m].y, symmetricRadius, 6, neighbours);
        if (std::hypot(fine[m].x - rough[m].x, fine[m].y - rough[m].y) > 1) fine[m].ok = false;
      }
    });
    std::vector<double> contrasts;
    for (const CentreEstimate& e : rough)
      if (e.ok) contrasts.push_back(e.contrast);
    const double contrastFloor = minContrast * median(contrasts);
    // Flattening makes a dark microlens image (vignetted, or no fluorescence there) look as
    // contrasted as a bright one, its centre then fitting noise and JPEG blocks: a scene's centres
    // enter the fit only where the unflattened image has signal, at least a share of what the
    // brightest tenth of the microlens images show (the extent still counts them all).
    std::vector<double> strength(predicted.size(), 0.0);
    double signalFloor = 0;
    if (scene) {
      std::vector<double> strengths;
      for (std::size_t m = 0; m < predicted.size(); ++m)
        if (fine[m].ok) strengths.push_back(strength[m] = windowContrast(signal, fine[m].x, fine[m].y, centroidRadius));
      if (!strengths.empty()) {
        const auto top = strengths.begin() + strengths.size() * 9 / 10;
        std::nth_element(strengths.begin(), top, strengths.end());
        signalFloor = kSceneSignalShare * *top;
      }
    }
    const double tolerance = 0.3 * spacing;
    samples.clear();
    present.clear();
    for (std::size_t m = 0; m < predicted.size(); ++m) {
      const CentreEstimate& e = rough[m];
      if (!e.ok || e.contrast < contrastFloor) continue;
      if (std::hypot(e.x - predicted[m].x, e.y - predicted[m].y) > tolerance) continue;
      present.push_back({predicted[m].k, predicted[m].n, e.x, e.y});
      if (fine[m].ok && strength[m] >= signalFloor)
        samples.push_back({predicted[m].k, predicted[m].n, fine[m].x, fine[m].y});
    }
    if (samples.size() < 6)
      return makeError(ErrorCode::Format, where + ": too few microlens images found (" +
                                              std::to_string(samples.size()) + ") to fit a lattice");
    fit = calibrate_detail::fitLattice(samples, lattice);
    if (fit.used < 6 || !(fit.lattice.pitchX > 2) || !(fit.lattice.pitchY > 2))
      return makeError(ErrorCode::Format, where + ": the microlens centres do not fit a lattice");
    lattice = fit.lattice;
    if (last) break;
  }
  const int found = int(samples.size());

  // The grid: the index rectangle around the microlenses whose image was found inside the image
  // (the first, centroid step needs only the image's own disc) where the lattice puts one.
  int k0 = INT32_MAX, k1 = INT32_MIN, n0 = INT32_MAX, n1 = INT32_MIN;
  const double onLattice = std::max(1.0, 0.1 * spacing);
  for (const Sample& p : present) {
    const auto c = lattice.centre(p.k, p.n);
    if (std::hypot(p.x - c[0], p.y - c[1]) > onLattice) continue;
    k0 = std::min(k0, p.k);
    k1 = std::max(k1, p.k);
    n0 = std::min(n0, p.n);
    n1 = std::max(n1, p.n);
  }
  if (k0 > k1) return makeError(ErrorCode::Format, where + ": no microlens image lies wholly inside the image");
  Calibration result;
  LensletGrid& grid = result.grid;
  grid.packing = lattice.packing;
  grid.pitchX = lattice.pitchX;
  grid.pitchY = lattice.pitchY;
  grid.rotationRad = lattice.theta;
  grid.hexParity = lattice.packing == Packing::Hexagonal ? (n0 & 1) : 0;
  {
    // centre(i, j) = lattice.centre(k0 + i, n0 + j): the origin is the unshifted position of row n0.
    const double a = k0 * lattice.pitchX, b = n0 * lattice.pitchY;
    const double c = std::cos(lattice.theta), s = std::sin(lattice.theta);
    grid.origin = {lattice.ox + c * a - s * b, lattice.oy + s * a + c * b};
  }
  grid.columns = k1 - k0 + 1;
  grid.rows = n1 - n0 + 1;
  grid.fit = {found, fit.used, fit.rms, fit.max, scene};
  result.centres.reserve(samples.size());
  for (std::size_t m = 0; m < samples.size(); ++m)
    result.centres.push_back(
        {samples[m].k - k0, samples[m].n - n0, samples[m].x, samples[m].y, fit.residual[m], bool(fit.inlier[m])});
  // A white image's centres fit a lattice to a few hundredths of a pixel. A scene whose centres
  // miss it by several times their own noise (0.055 px RMS: a centre against its neighbours'
  // median on the fluorescence frame) lies on a warped lattice; one that fits is left alone, as a
  // warp would only fit its noise (lfm-guv's capture fits to 0.07 px; a warp tried on it moved its
  // worst centre further from its radiometry grid's). 0.15 px was set with both frames in view.
  constexpr double kWarpAbovePx = 0.15;
  if (scene && grid.fit.rmsResidualPx > kWarpAbovePx) calibrate_detail::fitGridWarp(grid, result.centres);
  return result;
}

Result<Calibration> calibrateGridDetailed(const Image& image, const CalibrationOptions& options,
                                          const std::string& where) {
  if (image.empty() || image.channels() < 1) return makeError(ErrorCode::Usage, where + ": empty image");
  const calibrate_detail::PhaseGains gains = calibrate_detail::phaseGains(image, options);
  // The autocorrelation needs only the prepared central part (latticeFromAutocorrelation's crop).
  const int size = std::min({image.width(), image.height(), 1024}) & ~1;
  const int x0 = (image.width() - size) / 2, y0 = (image.height() - size) / 2;
  const Image centre = calibrate_detail::prepareRegion(image, options, gains, x0, y0, x0 + size, y0 + size, false);
  // The hint is only a guess (a metadata file may belong to another camera), and the image's own
  // autocorrelation can be fooled on a small image: when the two disagree (packing, or pitch by
  // more than 5%), both are fitted and the lattice that fits its centres better (relative to its
  // pitch) wins; the hint serves where the autocorrelation finds nothing.
  // Lattice vectors' peaks, against the strongest, measured on 160-pixel hexagonal images: white,
  // 0.95, but flat-topped images also correlate a third of a cell's diagonal away (gaps onto gaps,
  // 0.68 to 0.70: not a lattice vector); pinhole spots, sharp, lose much more between the integer
  // lags (the half-pitch row offset: under 0.78), and have no gaps to match.
  const double minPeak = options.target == CalibrationTarget::White ? 0.78 : 0.7;
  auto measured = calibrate_detail::latticeFromAutocorrelation(centre, where, minPeak);
  if (!options.hint) {
    LFCAM_TRY(measured);
    return calibrateFrom(image, gains, *measured, options, where);
  }
  const LensletHint& hint = *options.hint;
  if (!std::isfinite(hint.pitchPx) || hint.pitchPx < 3 || hint.pitchPx > 0.5 * std::min(image.width(), image.height()))
    return makeError(ErrorCode::Usage, where + ": the lenslet hint's pitch (" + std::to_string(hint.pitchPx) +
                                           " px) must lie in [3, half the image's size]");
  if (!std::isfinite(hint.rotationRad) || std::abs(hint.rotationRad) > 0.5)
    return makeError(ErrorCode::Usage, where + ": the lenslet hint's rotation must be within 0.5 rad");
  Lattice hinted;
  hinted.packing = hint.packing;
  hinted.pitchX = hint.pitchPx;
  hinted.pitchY = hint.packing == Packing::Hexagonal ? hint.pitchPx * std::sqrt(3.0) / 2 : hint.pitchPx;
  hinted.theta = hint.rotationRad;
  if (!measured || (measured->packing == hinted.packing && std::abs(measured->pitchX / hinted.pitchX - 1) <= 0.05))
    return calibrateFrom(image, gains, hinted, options, where);
  auto fromHint = calibrateFrom(image, gains, hinted, options, where);
  auto fromImage = calibrateFrom(image, gains, *measured, options, where);
  if (!fromHint) return fromImage;
  if (!fromImage) return fromHint;
  const auto relativeResidual = [](const Calibration& c) { return c.grid.fit.rmsResidualPx / c.grid.pitchX; };
  return relativeResidual(*fromImage) < relativeResidual(*fromHint) ? std::move(fromImage) : std::move(fromHint);
}

Result<LensletGrid> calibrateGrid(const Image& image, const CalibrationOptions& options, const std::string& where) {
  LFCAM_ASSIGN_OR_RETURN(auto result, calibrateGridDetailed(image, options, where));
  return std::move(result.grid);
}

Result<LensletGrid> calibrateGrid(const RawImage& raw, CalibrationOptions options, const std::string& where) {
  if (!options.hint && raw.lenslet) options.hint = raw.lenslet;
  if (options.colorFilter == ColorFilter::Mono) options.colorFilter = raw.colorFilter;
  if (options.blackLevel == 0) options.blackLevel = raw.blackLevel;
  return calibrateGrid(raw.mosaic, options, where);
}

}  // namespace lfcam
