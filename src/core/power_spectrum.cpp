#include "core/power_spectrum.hpp"

#include <cmath>
#include <complex>
#include <cstdint>
#include <memory>
#include <mutex>
#include <numeric>

#include <fftw3.h>

#include "core/fftw_planner.hpp"

namespace lfcam {

namespace {

double meanOf(std::span<const double> sequence) {
  return sequence.empty() ? 0.0 : std::accumulate(sequence.begin(), sequence.end(), 0.0) / double(sequence.size());
}

}  // namespace

std::vector<double> powerSpectrum(std::span<const double> sequence) {
  const int n = int(sequence.size());
  if (n < 2) return std::vector<double>(std::size_t(n / 2 + 1), 0.0);
  const int half = n / 2 + 1;
  std::unique_ptr<float, fftw::Free> real(static_cast<float*>(fftwf_malloc(sizeof(float) * std::size_t(n))));
  std::unique_ptr<fftwf_complex, fftw::Free> spectrum(
      static_cast<fftwf_complex*>(fftwf_malloc(sizeof(fftwf_complex) * std::size_t(half))));
  fftwf_plan plan;
  {
    std::lock_guard<std::mutex> lock(fftw::plannerMutex());
    plan = fftwf_plan_dft_r2c_1d(n, real.get(), spectrum.get(), FFTW_ESTIMATE);
  }
  const double mean = meanOf(sequence);
  for (int i = 0; i < n; ++i) real.get()[i] = float(sequence[std::size_t(i)] - mean);
  fftwf_execute(plan);
  std::vector<double> power(static_cast<std::size_t>(half));
  for (int f = 0; f < half; ++f) {
    const double re = spectrum.get()[f][0], im = spectrum.get()[f][1];
    power[std::size_t(f)] = re * re + im * im;
  }
  power[0] = 0;  // the mean was removed; what rounding leaves there is not signal
  {
    std::lock_guard<std::mutex> lock(fftw::plannerMutex());
    fftwf_destroy_plan(plan);
  }
  return power;
}

std::vector<double> powerSpectrumReference(std::span<const double> sequence) {
  const int n = int(sequence.size());
  const double mean = meanOf(sequence);
  std::vector<double> power(std::size_t(n / 2 + 1), 0.0);
  for (int f = 1; f <= n / 2; ++f) {
    std::complex<double> sum = 0;
    for (int i = 0; i < n; ++i)
      sum += (sequence[std::size_t(i)] - mean) * std::polar(1.0, -2 * M_PI * double((std::int64_t(f) * i) % n) / n);
    power[std::size_t(f)] = std::norm(sum);
  }
  return power;
}

}  // namespace lfcam
