#include "lfcam/lfm/psf.hpp"

#include <fftw3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numbers>
#include <tuple>

#include "core/fftw_planner.hpp"
#include "core/parallel.hpp"
#include "lfm/psf_stages.hpp"

#include "lfm/message_text.hpp"

namespace lfcam {

using lfm::number;
using lfm::usage;

namespace lfm {

constexpr double kPi = std::numbers::pi;

void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(n, 0.0);
  weights.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Newton from the Chebyshev-like guess; P_n and its derivative by the three-term recurrence.
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    nodes[i] = -x;
    nodes[n - 1 - i] = x;
    weights[i] = weights[n - 1 - i] = 2 / ((1 - x * x) * derivative * derivative);
  }
}

int windowPixels(const LfmOptics& optics, int lensletsAcross) {
  const double perLenslet = optics.microlensPitchUm / optics.pixelSizeUm;
  // A rectified frame's whole pixels a lenslet: the window is those lenslets exactly, its centre
  // (the axis) on a pixel's centre when N is odd, between two when even.
  if (std::abs(perLenslet - std::round(perLenslet)) < 1e-9) return lensletsAcross * int(std::round(perLenslet));
  const int pixels = int(std::ceil(lensletsAcross * perLenslet - 1e-9));
  return pixels % 2 == 0 ? pixels + 1 : pixels;
}

DebyeIntegral::DebyeIntegral(const LfmOptics& optics, double depthUm, double maxRadiusUm, PupilModel pupil) {
  const double kappa = optics.imageCutoffPerUm();  // pupil radius in image-side spatial frequency
  beta_ = 2 * kPi * kappa;
  const double sinAlpha = optics.sinAlpha();
  const double k = 2 * kPi * optics.immersionIndex / optics.wavelengthUm();  // wavenumber in the medium
  const double cosAlpha = std::sqrt(1 - sinAlpha * sinAlpha);
  // Nodes: J0(v rho) turns through about v radians over rho in [0, 1], the defocus phase through
  // k |z| (1 - cos alpha); Gauss-Legendre needs about half a node a radian, given twice that.
  const double phaseRange =
      std::abs(k * depthUm) * (pupil == PupilModel::AbbeSine ? 1 - cosAlpha : 0.5 * sinAlpha * sinAlpha);
  const int n = std::clamp(int(64 + std::ceil(beta_ * maxRadiusUm + phaseRange)), 64, 40000);
  std::vector<double> x, w;
  gaussLegendre(n, x, w);
  rho_.resize(n);
  weight_.resize(n);
  double energy = 0;  // integral of A(rho)^2 rho d rho
  for (int j = 0; j < n; ++j) {
    const double rho = 0.5 * (x[j] + 1), weight = 0.5 * w[j];
    double amplitude = 1, phase = 0;
    if (pupil == PupilModel::AbbeSine) {
      // Equation 3 in rho = sin(theta) / sin(alpha): sqrt(cos theta) sin(theta) d theta =
      // sin^2(alpha) rho d rho / sqrt(cos theta); the constant sin^2(alpha) goes into C.
      const double cosTheta = std::sqrt(1 - sinAlpha * sinAlpha * rho * rho);
      amplitude = 1 / std::sqrt(cosTheta);
      phase = k * depthUm * (1 - cosTheta);
    } else {
      phase = k * depthUm * 0.5 * sinAlpha * sinAlpha * rho * rho;
    }
    rho_[j] = rho;
    weight_[j] = weight * amplitude * rho * std::polar(1.0, phase);
    energy += weight * amplitude * amplitude * rho;
  }
  // U(r) = 2 pi kappa^2 P0 integral A e^{i phi} J0(v rho) rho d rho, the pupil's amplitude P0 such that
  // the plane's energy (Parseval: 2 pi kappa^2 P0^2 integral A^2 rho d rho) is 1.
  const double scale = 2 * kPi * kappa * kappa / std::sqrt(2 * kPi * kappa * kappa * energy);
  for (auto& value : weight_) value *= scale;
}

std::complex<double> DebyeIntegral::field(double radiusUm) const {
  const double v = beta_ * radiusUm;
  std::complex<double> sum = 0;
  for (std::size_t j = 0; j < rho_.size(); ++j) sum += weight_[j] * std::cyl_bessel_j(0.0, v * rho_[j]);
  return sum;
}

double maxRadiusOnGrid(const LfmOptics& optics, const LfmPoint& point, int n) {
  const double halfX = sampleCoordinate(n - 1, n, optics.sampleSpacingUm());
  const double halfY = sampleCoordinate(n - 1, n, optics.sampleHeightUm());
  const double cx = optics.magnification * point.xUm, cy = optics.magnification * point.yUm;
  return std::hypot(halfX + std::abs(cx), halfY + std::abs(cy));
}

std::vector<std::complex<double>> nativeFieldDirect(const LfmOptics& optics, PupilModel pupil, const LfmPoint& point,
                                                    int n) {
  const double dx = optics.sampleSpacingUm(), dy = optics.sampleHeightUm();
  const DebyeIntegral debye(optics, point.zUm, maxRadiusOnGrid(optics, point, n), pupil);
  const double cx = optics.magnification * point.xUm, cy = optics.magnification * point.yUm;
  std::vector<std::complex<double>> field(std::size_t(n) * n);
  parallelFor(0, n, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < n; ++x)
        field[y * n + x] =
            debye.field(std::hypot(sampleCoordinate(x, n, dx) - cx, sampleCoordinate(int(y), n, dy) - cy));
  });
  return field;
}

std::complex<double> RadialProfile::at(double radiusUm) const {
  const double r = radiusUm / step;
  const int i = std::min(int(r), int(values.size()) - 2);
  const double t = r - i;
  return (1 - t) * values[i] + t * values[i + 1];
}

RadialProfile radialProfile(const LfmOptics& optics, PupilModel pupil, double depthUm, double maxRadiusUm) {
  const DebyeIntegral debye(optics, depthUm, maxRadiusUm, pupil);
  RadialProfile profile{.depthUm = depthUm, .step = optics.sampleSpacingUm() / 16};
  profile.values.resize(std::size_t(std::ceil(maxRadiusUm / profile.step)) + 2);
  parallelFor(0, profile.values.size(), 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) profile.values[i] = debye.field(double(i) * profile.step);
  });
  return profile;
}

std::vector<std::complex<double>> nativeFieldFromProfile(const LfmOptics& optics, const RadialProfile& profile,
                                                         const LfmPoint& point, int n) {
  const double dx = optics.sampleSpacingUm(), dy = optics.sampleHeightUm();
  const double cx = optics.magnification * point.xUm, cy = optics.magnification * point.yUm;
  std::vector<std::complex<double>> field(std::size_t(n) * n);
  parallelFor(0, n, 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < n; ++x)
        field[y * n + x] =
            profile.at(std::hypot(sampleCoordinate(x, n, dx) - cx, sampleCoordinate(int(y), n, dy) - cy));
  });
  return field;
}

LensletCentre nearestLenslet(const LfmOptics& optics, double xUm, double yUm) {
  const double pitch = optics.microlensPitchUm;
  if (optics.array == MicrolensLayout::Square)
    return {std::round(xUm / pitch) * pitch, std::round(yUm / pitch) * pitch};
  // The nearest centre of the rows through and around the nearest row's: a hexagonal cell
  // reaches into the next rows' bands.
  const double row = optics.rowPitchUm();
  const double t0 = std::round(yUm / row);
  LensletCentre best{0, 0};
  double bestDistance = std::numeric_limits<double>::infinity();
  for (double t = t0 - 1; t <= t0 + 1; ++t) {
    const double shift = std::fmod(std::abs(t), 2.0) == 1 ? 0.5 : 0.0;
    const LensletCentre centre{(std::round(xUm / pitch - shift) + shift) * pitch, t * row};
    const double distance = std::hypot(xUm - centre.xUm, yUm - centre.yUm);
    if (distance < bestDistance) best = centre, bestDistance = distance;
  }
  return best;
}

template <class T>
void applyMicrolenses(const LfmOptics& optics, int n, std::complex<T>* field) {
  const double dx = optics.sampleSpacingUm(), dy = optics.sampleHeightUm();
  // The aperture: the cell shrunk by sqrt(fill factor); halfAperture its half-width along x (a
  // hexagon's inradius).
  const double halfAperture = 0.5 * std::sqrt(optics.microlensFillFactor) * optics.microlensPitchUm;
  const bool hexagonal = optics.array == MicrolensLayout::Hexagonal;
  const double chirp = kPi / (optics.wavelengthUm() * optics.microlensFocalLengthUm);  // image side: air
  // Equation 6: each lenslet a thin lens centred on its cell.
  parallelFor(0, n, 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < n; ++x) {
        const double px = sampleCoordinate(x, n, dx), py = sampleCoordinate(int(y), n, dy);
        const LensletCentre centre = nearestLenslet(optics, px, py);
        const double lx = std::abs(px - centre.xUm), ly = std::abs(py - centre.yUm);
        // A hexagon's sides: two at |x| = a, four at |x| / 2 + sqrt(3) / 2 |y| = a.
        const bool inside = hexagonal ? lx <= halfAperture && 0.5 * lx + 0.5 * std::sqrt(3.0) * ly <= halfAperture
                                      : lx <= halfAperture && ly <= halfAperture;
        std::complex<T>& value = field[y * n + x];
        value = inside ? value * std::complex<T>(std::polar(1.0, -chirp * (lx * lx + ly * ly))) : std::complex<T>(0);
      }
  });
}
template void applyMicrolenses(const LfmOptics&, int, std::complex<float>*);
template void applyMicrolenses(const LfmOptics&, int, std::complex<double>*);

FresnelTransfer::FresnelTransfer(int n, double spacingXUm, double spacingYUm, double wavelengthUm, double distanceUm)
    : n_(n) {
  const std::size_t size = std::size_t(n) * n;
  transfer_.resize(size);
  const double scale = 1.0 / double(size);  // FFTW's inverse is unnormalised
  for (int y = 0; y < n; ++y) {
    const double fy = (y <= (n - 1) / 2 ? y : y - n) / (n * spacingYUm);
    for (int x = 0; x < n; ++x) {
      const double fx = (x <= (n - 1) / 2 ? x : x - n) / (n * spacingXUm);
      const double phase = -kPi * wavelengthUm * distanceUm * (fx * fx + fy * fy);
      transfer_[std::size_t(y) * n + x] = std::complex<float>(std::polar(scale, phase));
    }
  }
  // Plans for an in-place transform of an fftwf_malloc'ed buffer: propagate() executes them on a
  // buffer of its own, of the same alignment.
  std::unique_ptr<fftwf_complex, fftw::Free> buffer(fftwf_alloc_complex(size));
  std::lock_guard lock(fftw::plannerMutex());
  forward_ = fftwf_plan_dft_2d(n, n, buffer.get(), buffer.get(), FFTW_FORWARD, FFTW_ESTIMATE);
  inverse_ = fftwf_plan_dft_2d(n, n, buffer.get(), buffer.get(), FFTW_BACKWARD, FFTW_ESTIMATE);
}

FresnelTransfer::~FresnelTransfer() {
  std::lock_guard lock(fftw::plannerMutex());
  if (forward_) fftwf_destroy_plan(static_cast<fftwf_plan>(forward_));
  if (inverse_) fftwf_destroy_plan(static_cast<fftwf_plan>(inverse_));
}

void FresnelTransfer::propagate(std::complex<float>* field) const {
  const std::size_t size = std::size_t(n_) * n_;
  std::unique_ptr<fftwf_complex, fftw::Free> buffer(fftwf_alloc_complex(size));
  auto* data = reinterpret_cast<std::complex<float>*>(buffer.get());
  std::copy(field, field + size, data);
  fftwf_execute_dft(static_cast<fftwf_plan>(forward_), buffer.get(), buffer.get());
  for (std::size_t i = 0; i < size; ++i) data[i] *= transfer_[i];
  fftwf_execute_dft(static_cast<fftwf_plan>(inverse_), buffer.get(), buffer.get());
  std::copy(data, data + size, field);
}

std::vector<std::complex<double>> fresnelDirect(const std::vector<std::complex<double>>& field, int n,
                                                double spacingXUm, double spacingYUm, double wavelengthUm,
                                                double distanceUm) {
  const double chirp = kPi / (wavelengthUm * distanceUm);
  const std::complex<double> scale = spacingXUm * spacingYUm / std::complex<double>(0, wavelengthUm * distanceUm);
  // exp(i chirp d^2) for every separation d = k * spacing along each axis: the kernel separates.
  std::vector<std::complex<double>> kernelX(2 * n - 1), kernelY(2 * n - 1);
  for (int k = -(n - 1); k <= n - 1; ++k) {
    kernelX[k + n - 1] = std::polar(1.0, chirp * (k * spacingXUm) * (k * spacingXUm));
    kernelY[k + n - 1] = std::polar(1.0, chirp * (k * spacingYUm) * (k * spacingYUm));
  }
  std::vector<std::complex<double>> out(std::size_t(n) * n);
  parallelFor(0, n, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < n; ++x) {
        std::complex<double> sum = 0;
        for (int y1 = 0; y1 < n; ++y1) {
          const std::complex<double> ky = kernelY[int(y) - y1 + n - 1];
          for (int x1 = 0; x1 < n; ++x1) sum += field[std::size_t(y1) * n + x1] * ky * kernelX[x - x1 + n - 1];
        }
        out[y * n + x] = scale * sum;
      }
  });
  return out;
}

int hexagonalBrickPixels(const LfmOptics& optics) {
  if (optics.array != MicrolensLayout::Hexagonal) return 0;
  const double perLenslet = optics.microlensPitchUm / optics.pixelSizeUm;
  const int n = int(std::round(perLenslet));
  const bool whole = std::abs(perLenslet - n) < 1e-9 * n;
  return whole && std::abs(n * optics.pixelHeightUm() - optics.rowPitchUm()) < 1e-9 * optics.rowPitchUm() ? n : 0;
}

Image integratePixels(const std::complex<float>* field, int n, const LfmOptics& optics) {
  const int supersample = optics.supersample, pixels = n / supersample;
  const int brick = hexagonalBrickPixels(optics), middleRow = pixels / std::max(brick, 1) / 2;
  Image image(pixels, pixels, 1);
  const double area = optics.sampleSpacingUm() * optics.sampleHeightUm();
  for (int py = 0; py < pixels; ++py) {
    const bool shifted = brick > 0 && (py / brick - middleRow) % 2 != 0;
    const int shift = shifted ? brick * supersample / 2 : 0;
    for (int px = 0; px < pixels; ++px) {
      double sum = 0;
      for (int sy = 0; sy < supersample; ++sy)
        for (int sx = 0; sx < supersample; ++sx) {
          const int x = (px * supersample + sx + shift) % n;
          sum += std::norm(std::complex<double>(field[std::size_t(py * supersample + sy) * n + x]));
        }
      image.at(px, py, 0) = float(sum * area);
    }
  }
  return image;
}

}  // namespace lfm

Result<std::vector<std::complex<double>>> debyeField(const LfmOptics& optics, double depthUm,
                                                     std::span<const double> radiiUm, PupilModel pupil) {
  LFCAM_TRY(validateLfmOptics(optics));
  double maxRadius = 0;
  for (double r : radiiUm) {
    if (!(r >= 0) || !std::isfinite(r))
      return makeError(ErrorCode::Usage, "radius " + number(r, "%.3g") + " must be >= 0");
    maxRadius = std::max(maxRadius, r);
  }
  if (!std::isfinite(depthUm)) return makeError(ErrorCode::Usage, "depth must be finite");
  const lfm::DebyeIntegral debye(optics, depthUm, maxRadius, pupil);
  std::vector<std::complex<double>> field(radiiUm.size());
  parallelFor(0, field.size(), 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) field[i] = debye.field(radiiUm[i]);
  });
  return field;
}

struct LfmPsf::State {
  LfmOptics optics;
  PupilModel pupil;
  int pixels = 0, samples = 0;
  lfm::FresnelTransfer transfer;
  std::vector<std::complex<float>> mask;  // the microlens array's transmission on the window
  // The radial profiles of the depths seen so far, each reaching any point of the centre lenslet.
  mutable std::mutex profilesMutex;
  mutable std::vector<std::shared_ptr<const lfm::RadialProfile>> profiles;

  State(const LfmOptics& o, PupilModel p, int pixelsAcross)
      : optics(o),
        pupil(p),
        pixels(pixelsAcross),
        samples(pixelsAcross * o.supersample),
        transfer(samples, o.sampleSpacingUm(), o.sampleHeightUm(), o.wavelengthUm(), o.microlensFocalLengthUm),
        mask(std::size_t(samples) * samples, 1.0f) {
    lfm::applyMicrolenses(optics, samples, mask.data());
  }

  std::shared_ptr<const lfm::RadialProfile> profileFor(const LfmPoint& point) const {
    // The farthest a voxel of the array's period sits from the axis (computePsfSet's points).
    const LfmPoint corner{0.5 * optics.microlensPitchUm / optics.magnification,
                          (optics.rowsPerPeriod() - 0.5) * optics.rowPitchUm() / optics.magnification, point.zUm};
    const double reach = lfm::maxRadiusOnGrid(optics, corner, samples);
    if (lfm::maxRadiusOnGrid(optics, point, samples) > reach)
      return std::make_shared<const lfm::RadialProfile>(
          lfm::radialProfile(optics, pupil, point.zUm, lfm::maxRadiusOnGrid(optics, point, samples)));
    {
      std::lock_guard lock(profilesMutex);
      for (const auto& profile : profiles)
        if (profile->depthUm == point.zUm) return profile;
    }
    // Two threads may both compute a new depth's profile; the second copy is dropped.
    auto profile = std::make_shared<const lfm::RadialProfile>(lfm::radialProfile(optics, pupil, point.zUm, reach));
    std::lock_guard lock(profilesMutex);
    profiles.push_back(profile);
    return profile;
  }
};

Result<LfmPsf> LfmPsf::create(const LfmOptics& optics, int lensletsAcross, PupilModel pupil) {
  LFCAM_TRY(validateLfmOptics(optics));
  if (lensletsAcross < 1 || lensletsAcross % 2 == 0 || lensletsAcross > 201)
    return makeError(ErrorCode::Usage,
                     "lenslets across " + std::to_string(lensletsAcross) + " must be odd, in [1, 201]");
  // The field after the mask holds frequencies up to the native image's cutoff plus the lenslets'
  // phase slope at their edge, along each axis; the samples must hold them without aliasing. A
  // hexagonal aperture reaches 2 / sqrt(3) of its inradius along y.
  const double halfAperture = 0.5 * std::sqrt(optics.microlensFillFactor) * optics.microlensPitchUm;
  const double reachY = optics.array == MicrolensLayout::Hexagonal ? halfAperture * 2 / std::sqrt(3.0) : halfAperture;
  for (const auto& [reach, spacing, pixel] : {std::tuple{halfAperture, optics.sampleSpacingUm(), optics.pixelSizeUm},
                                              std::tuple{reachY, optics.sampleHeightUm(), optics.pixelHeightUm()}}) {
    const double bandwidth =
        optics.imageCutoffPerUm() + reach / (optics.wavelengthUm() * optics.microlensFocalLengthUm);
    if (!(2 * bandwidth * spacing < 1))
      return makeError(ErrorCode::Usage, "sample spacing " + number(spacing, "%.3g") +
                                             " um aliases the field after the microlenses (up to " +
                                             number(bandwidth, "%.3g") + " cycles/um): raise supersample to at least " +
                                             std::to_string(int(std::floor(2 * bandwidth * pixel)) + 1));
  }
  if (const int brick = lfm::hexagonalBrickPixels(optics); brick * optics.supersample % 2 != 0)
    return makeError(ErrorCode::Usage, "a hexagonal frame of " + std::to_string(brick) +
                                           " pixels a lenslet needs an even supersample: its shifted rows sit half a "
                                           "pitch over");
  const int pixels = lfm::windowPixels(optics, lensletsAcross);
  if (std::size_t(pixels) * optics.supersample > 8192)
    return makeError(ErrorCode::Resource, "a window of " + std::to_string(pixels * optics.supersample) +
                                              " samples across is above 8192: fewer lenslets or less supersampling");
  return LfmPsf(std::make_unique<State>(optics, pupil, pixels));
}

int LfmPsf::lensletsFor(const LfmOptics& optics, double maxDepthUm) {
  const double sinAlpha = std::min(optics.sinAlpha(), 0.999999);
  const double radius = optics.magnification * std::abs(maxDepthUm) * sinAlpha / std::sqrt(1 - sinAlpha * sinAlpha);
  // Rows (the closer-spaced axis) to the blur's edge, and a period's rows of margin: a period of a
  // hexagonal array holds points a row off the axis.
  return 2 * (int(std::ceil(radius / optics.rowPitchUm())) + optics.rowsPerPeriod()) + 1;
}

LfmPsf::LfmPsf(std::unique_ptr<State> state) : state_(std::move(state)) {}
LfmPsf::LfmPsf(LfmPsf&&) noexcept = default;
LfmPsf& LfmPsf::operator=(LfmPsf&&) noexcept = default;
LfmPsf::~LfmPsf() = default;

const LfmOptics& LfmPsf::optics() const { return state_->optics; }
int LfmPsf::pixelsAcross() const { return state_->pixels; }
int LfmPsf::samplesAcross() const { return state_->samples; }

std::vector<std::complex<double>> LfmPsf::nativeField(const LfmPoint& point) const {
  return lfm::nativeFieldFromProfile(state_->optics, *state_->profileFor(point), point, state_->samples);
}

std::vector<std::complex<float>> LfmPsf::sensorField(const LfmPoint& point) const {
  const std::vector<std::complex<double>> native = nativeField(point);
  std::vector<std::complex<float>> field(native.size());
  for (std::size_t i = 0; i < field.size(); ++i) field[i] = std::complex<float>(native[i]) * state_->mask[i];
  state_->transfer.propagate(field.data());
  return field;
}

Image LfmPsf::psf(const LfmPoint& point) const {
  const std::vector<std::complex<float>> field = sensorField(point);
  return lfm::integratePixels(field.data(), state_->samples, state_->optics);
}

Status validateLfmGrid(const LfmGrid& grid) {
  if (grid.pixelsPerLenslet < 2 || grid.pixelsPerLenslet > 255)
    return makeError(ErrorCode::Usage,
                     "pixels per lenslet " + std::to_string(grid.pixelsPerLenslet) + " outside [2, 255]");
  if (grid.voxelsPerLenslet < 1 || grid.voxelsPerLenslet > grid.pixelsPerLenslet)
    return makeError(ErrorCode::Usage, "voxels per lenslet (supersample) " + std::to_string(grid.voxelsPerLenslet) +
                                           " must be in [1, " + std::to_string(grid.pixelsPerLenslet) +
                                           "] (the pixels per lenslet)");
  if (grid.depthsUm.empty()) return makeError(ErrorCode::Usage, "no slices: the volume needs at least one");
  for (double z : grid.depthsUm)
    if (!std::isfinite(z)) return makeError(ErrorCode::Usage, "slice depth " + number(z, "%.3g") + " must be finite");
  return {};
}

LfmOptics frameOptics(const LfmOptics& optics, int pixelsPerLenslet) {
  LfmOptics frame = optics;
  frame.pixelSizeUm = optics.microlensPitchUm / pixelsPerLenslet;
  if (optics.array == MicrolensLayout::Hexagonal) {
    frame.pixelAspect = optics.rowPitchUm() / optics.microlensPitchUm;
    if (pixelsPerLenslet * frame.supersample % 2 != 0) ++frame.supersample;
  }
  return frame;
}

LfmPoint LfmPsfSet::point(int depth, int i, int j) const {
  return {grid.voxelOffsetUm(optics, i), grid.voxelRowOffsetUm(optics, j), grid.depthsUm[depth]};
}

const float* LfmPsfSet::psf(int depth, int i, int j) const {
  const std::size_t index = (std::size_t(depth) * voxelRows() + j) * grid.voxelsPerLenslet + i;
  return values.data() + index * pixelsAcross * pixelsAcross;
}

Result<LfmPsfSet> computePsfSet(const LfmOptics& microscope, const LfmGrid& grid, int lensletsAcross,
                                PupilModel pupil) {
  LFCAM_TRY(validateLfmOptics(microscope));
  LFCAM_TRY(validateLfmGrid(grid));
  const LfmOptics optics = frameOptics(microscope, grid.pixelsPerLenslet);
  double deepest = 0;
  for (double z : grid.depthsUm) deepest = std::max(deepest, std::abs(z));
  if (lensletsAcross == 0) lensletsAcross = LfmPsf::lensletsFor(optics, deepest);
  LFCAM_ASSIGN_OR_RETURN(LfmPsf model, LfmPsf::create(optics, lensletsAcross, pupil));
  const int k = grid.voxelsPerLenslet, n = model.pixelsAcross();
  LfmPsfSet set{.optics = optics, .pupil = pupil, .grid = grid, .lensletsAcross = lensletsAcross, .pixelsAcross = n};
  const std::size_t size = std::size_t(n) * n;
  set.values.resize(grid.depthsUm.size() * k * set.voxelRows() * size);
  // A square array and its pixels are symmetric about the centre lenslet's axes and diagonal:
  // phase K - 1 - i is phase i mirrored, phase (j, i) phase (i, j) transposed. Only the phases
  // with fold(i) <= fold(j) are computed; the others are copied from them.
  const bool square = optics.array == MicrolensLayout::Square;
  auto fold = [k](int i) { return std::min(i, k - 1 - i); };
  std::vector<std::array<int, 3>> computed;  // depth, i, j
  for (int depth = 0; depth < int(grid.depthsUm.size()); ++depth)
    for (int j = 0; j < set.voxelRows(); ++j)
      for (int i = 0; i < k; ++i)
        if (!square || (i == fold(i) && j == fold(j) && i <= j)) computed.push_back({depth, i, j});
  // One PSF a task: each one's own stages thread within it too.
  parallelFor(0, computed.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const auto [depth, i, j] = computed[c];
      const Image image = model.psf(set.point(depth, i, j));
      std::copy(image.pixels().begin(), image.pixels().end(), const_cast<float*>(set.psf(depth, i, j)));
    }
  });
  for (int depth = 0; square && depth < int(grid.depthsUm.size()); ++depth)
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const int fi = fold(i), fj = fold(j);
        const bool transposed = fi > fj;
        if (i == fi && j == fj && !transposed) continue;
        const float* base = set.psf(depth, transposed ? fj : fi, transposed ? fi : fj);
        float* out = const_cast<float*>(set.psf(depth, i, j));
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            const int my = j != fj ? n - 1 - y : y, mx = i != fi ? n - 1 - x : x;
            out[std::size_t(y) * n + x] = transposed ? base[std::size_t(mx) * n + my] : base[std::size_t(my) * n + mx];
          }
      }
  return set;
}

}  // namespace lfcam
