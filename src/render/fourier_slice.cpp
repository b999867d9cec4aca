// Fourier slice refocusing: fourier_slice.hpp.
#include "lfcam/render/fourier_slice.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <numbers>

#include "core/fftw_planner.hpp"

namespace lfcam {

namespace {

using fftw::plannerMutex;  // FFTW's planner is not thread-safe; its executors are.

template <class T>
using FftwBuffer = std::unique_ptr<T[], fftw::Free>;
template <class T>
FftwBuffer<T> fftwAlloc(std::size_t count) {
  return FftwBuffer<T>(static_cast<T*>(fftwf_malloc(sizeof(T) * std::max<std::size_t>(count, 1))));
}

// Kaiser-Bessel kernel of `width` grid steps, at offset x (grid steps) from its centre.
double kaiserBessel(double x, int width, double beta) {
  const double r = 2 * x / width;
  if (std::abs(r) > 1) return 0;
  return std::cyl_bessel_i(0.0, beta * std::sqrt(1 - r * r)) / std::cyl_bessel_i(0.0, beta);
}

// Its continuous Fourier transform at nu cycles per grid step (numerically: it is smooth).
double kaiserBesselTransform(double nu, int width, double beta) {
  const int steps = 2000;
  const double dx = double(width) / steps;
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double x = -0.5 * width + (i + 0.5) * dx;
    sum += kaiserBessel(x, width, beta) * std::cos(2 * std::numbers::pi * x * nu) * dx;
  }
  return sum;
}

int wrap(long index, int size) { return int(((index % size) + size) % size); }

}  // namespace

Result<FourierRefocuser> FourierRefocuser::create(const LightField& lightField, const FourierSliceOptions& options) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "Fourier slice: empty light field");
  if (!(options.oversampling >= 1 && options.oversampling <= 8) || options.kernelWidth < 2 || options.kernelWidth > 16)
    return makeError(ErrorCode::Usage,
                     "Fourier slice: oversampling must lie in [1, 8] and the kernel width in [2, 16]");
  FourierRefocuser result;
  const LightFieldShape& shape = lightField.shape();
  result.shape_ = shape;
  result.width_ = options.kernelWidth;
  result.paddedU_ = std::max(shape.nu, int(std::ceil(options.oversampling * shape.nu)));
  result.paddedV_ = std::max(shape.nv, int(std::ceil(options.oversampling * shape.nv)));
  // Beatty et al. 2005: the Kaiser-Bessel shape for this width and oversampling.
  const double sigma = std::max(1.01, options.oversampling), w = options.kernelWidth;
  result.kaiserBeta_ =
      std::numbers::pi * std::sqrt(std::max(0.0, w * w / (sigma * sigma) * (sigma - 0.5) * (sigma - 0.5) - 0.8));
  // View u is placed at index u - wholeU (mod padded), so that the views sit around index 0,
  // where the roll-off correction is accurate; halfU is what is left of the true centre.
  const int wholeU = (shape.nu - 1) / 2, wholeV = (shape.nv - 1) / 2;
  result.halfU_ = 0.5 * (shape.nu - 1) - wholeU;
  result.halfV_ = 0.5 * (shape.nv - 1) - wholeV;

  const int ns = shape.ns, nt = shape.nt, half = ns / 2 + 1;
  const std::size_t planeFrequencies = std::size_t(nt) * half;
  const int Mu = result.paddedU_, Mv = result.paddedV_;
  std::vector<double> rollOffU(shape.nu), rollOffV(shape.nv);
  for (int u = 0; u < shape.nu; ++u)
    rollOffU[u] = kaiserBesselTransform(double(u - wholeU) / Mu, result.width_, result.kaiserBeta_);
  for (int v = 0; v < shape.nv; ++v)
    rollOffV[v] = kaiserBesselTransform(double(v - wholeV) / Mv, result.width_, result.kaiserBeta_);

  auto real = fftwAlloc<float>(std::size_t(ns) * nt);
  auto complex = fftwAlloc<fftwf_complex>(planeFrequencies);
  fftwf_plan planar, angular;
  result.spectrum_.resize(shape.channels);
  for (auto& channel : result.spectrum_) channel.assign(std::size_t(Mu) * Mv * planeFrequencies, 0.0f);
  {
    std::lock_guard lock(plannerMutex());
    planar = fftwf_plan_dft_r2c_2d(nt, ns, real.get(), complex.get(), FFTW_ESTIMATE);
    const int n[2] = {Mv, Mu};
    auto* data = reinterpret_cast<fftwf_complex*>(result.spectrum_[0].data());
    angular = fftwf_plan_many_dft(2, n, int(planeFrequencies), data, nullptr, int(planeFrequencies), 1, data, nullptr,
                                  int(planeFrequencies), 1, FFTW_FORWARD, FFTW_ESTIMATE);
  }
  for (int c = 0; c < shape.channels; ++c) {
    std::vector<std::complex<float>>& spectrum = result.spectrum_[c];
    // Spatial FFT of each view, divided by the roll-off of the angular kernel.
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u) {
        const float scale = float(1.0 / (rollOffU[u] * rollOffV[v]));
        const float* plane = lightField.plane(u, v, c);
        for (std::size_t i = 0; i < std::size_t(ns) * nt; ++i) real[i] = plane[i] * scale;
        fftwf_execute_dft_r2c(planar, real.get(), complex.get());
        const std::size_t slot = std::size_t(wrap(v - wholeV, Mv)) * Mu + wrap(u - wholeU, Mu);
        std::memcpy(static_cast<void*>(spectrum.data() + slot * planeFrequencies), complex.get(),
                    planeFrequencies * sizeof(fftwf_complex));
      }
    // Angular FFT, zero-padded, for every spatial frequency at once.
    auto* data = reinterpret_cast<fftwf_complex*>(spectrum.data());
    fftwf_execute_dft(angular, data, data);
  }
  {
    std::lock_guard lock(plannerMutex());
    fftwf_destroy_plan(planar);
    fftwf_destroy_plan(angular);
  }
  return result;
}

std::size_t FourierRefocuser::spectrumBytes() const {
  std::size_t bytes = 0;
  for (const auto& channel : spectrum_) bytes += channel.size() * sizeof(std::complex<float>);
  return bytes;
}

Image FourierRefocuser::refocus(double slope) const {
  const int ns = shape_.ns, nt = shape_.nt, half = ns / 2 + 1;
  const std::size_t planeFrequencies = std::size_t(nt) * half;
  const int Mu = paddedU_, Mv = paddedV_;
  Image out(ns, nt, shape_.channels);
  if (!std::isfinite(slope) || spectrum_.empty()) return out;

  auto slice = fftwAlloc<fftwf_complex>(planeFrequencies);
  auto real = fftwAlloc<float>(std::size_t(ns) * nt);
  fftwf_plan inverse;
  {
    std::lock_guard lock(plannerMutex());
    inverse = fftwf_plan_dft_c2r_2d(nt, ns, slice.get(), real.get(), FFTW_ESTIMATE);
  }
  // Kernel taps along one angular axis at frequency f (cycles per view step): grid indices and
  // weights, times the phase that moves the views' origin back to the true centre.
  struct AxisTaps {
    int index[16];
    double weight[16];
    int count = 0;
    std::complex<double> phase;
  };
  auto taps = [&](double f, int padded, double halfStep) {
    AxisTaps t;
    const double x = f * padded;
    const long first = long(std::ceil(x - 0.5 * width_)), last = long(std::floor(x + 0.5 * width_));
    for (long k = first; k <= last && t.count < 16; ++k) {
      t.index[t.count] = wrap(k, padded);
      t.weight[t.count++] = kaiserBessel(x - double(k), width_, kaiserBeta_);
    }
    t.phase = std::polar(1.0, 2 * std::numbers::pi * f * halfStep);
    return t;
  };
  // Spatial FFT normalisation and the mean over the views.
  const double normalise = 1.0 / (double(ns) * nt * double(shape_.nu) * shape_.nv);
  std::vector<AxisTaps> columnTaps(half);
  for (int ks = 0; ks < half; ++ks) columnTaps[ks] = taps(slope * double(ks) / ns, Mu, halfU_);

  for (int c = 0; c < shape_.channels; ++c) {
    const std::complex<float>* spectrum = spectrum_[c].data();
    for (int kt = 0; kt < nt; ++kt) {
      const double ft = double(kt <= nt / 2 ? kt : kt - nt) / nt;
      const AxisTaps rowTaps = taps(slope * ft, Mv, halfV_);
      for (int ks = 0; ks < half; ++ks) {
        const AxisTaps& colTaps = columnTaps[ks];
        const std::size_t frequency = std::size_t(kt) * half + ks;
        std::complex<double> sum = 0;
        for (int a = 0; a < rowTaps.count; ++a) {
          std::complex<double> row = 0;
          const std::size_t rowBase = std::size_t(rowTaps.index[a]) * Mu;
          for (int b = 0; b < colTaps.count; ++b)
            row += colTaps.weight[b] *
                   std::complex<double>(spectrum[(rowBase + colTaps.index[b]) * planeFrequencies + frequency]);
          sum += rowTaps.weight[a] * row;
        }
        sum *= rowTaps.phase * colTaps.phase * normalise;
        slice[frequency][0] = float(sum.real());
        slice[frequency][1] = float(sum.imag());
      }
    }
    fftwf_execute_dft_c2r(inverse, slice.get(), real.get());
    std::memcpy(out.plane(c), real.get(), sizeof(float) * std::size_t(ns) * nt);
  }
  {
    std::lock_guard lock(plannerMutex());
    fftwf_destroy_plan(inverse);
  }
  return out;
}

}  // namespace lfcam
