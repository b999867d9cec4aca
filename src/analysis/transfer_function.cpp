// Transfer function of a point-source photograph (the paper's section 6.1) and its 75% cutoff.
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <memory>
#include <mutex>
#include <numbers>
#include <utility>

#include "analysis/references.hpp"
#include "core/fftw_planner.hpp"
#include "lfcam/analysis/analysis.hpp"

namespace lfcam {

namespace {

using fftw::plannerMutex;  // FFTW's planner is not thread-safe.

Status checkPhoto(const Image& photo, int zeroPadding) {
  if (photo.empty() || photo.width() < 1 || photo.height() < 1)
    return makeError(ErrorCode::Usage, "transfer function: empty photograph");
  if (zeroPadding < 1 || zeroPadding > 64)
    return makeError(ErrorCode::Usage, "transfer function: zero padding must be 1 to 64");
  return {};
}

// Writes |H| shifted (zero frequency at (w/2, h/2)) and normalised by |H(0)|.
Result<Image> normalisedShifted(int w, int h, const std::function<double(int, int)>& magnitude) {
  const double dc = magnitude(0, 0);
  if (!(dc > 0)) return makeError(ErrorCode::Usage, "transfer function: the photograph sums to zero");
  Image out(w, h, 1);
  for (int ky = 0; ky < h; ++ky)
    for (int kx = 0; kx < w; ++kx) out.at((kx + w / 2) % w, (ky + h / 2) % h, 0) = float(magnitude(kx, ky) / dc);
  return out;
}

}  // namespace

Result<Image> transferFunction(const Image& photo, int zeroPadding) {
  LFCAM_TRY(checkPhoto(photo, zeroPadding));
  const int w = photo.width() * zeroPadding, h = photo.height() * zeroPadding, half = w / 2 + 1;
  using Buffer = std::unique_ptr<float, decltype(&fftwf_free)>;
  using Spectrum = std::unique_ptr<fftwf_complex, decltype(&fftwf_free)>;
  Buffer in(static_cast<float*>(fftwf_malloc(sizeof(float) * std::size_t(w) * h)), fftwf_free);
  Spectrum out(static_cast<fftwf_complex*>(fftwf_malloc(sizeof(fftwf_complex) * std::size_t(half) * h)), fftwf_free);
  if (!in || !out) return makeError(ErrorCode::Resource, "transfer function: out of memory");
  fftwf_plan plan = nullptr;
  {
    std::lock_guard lock(plannerMutex());
    plan = fftwf_plan_dft_r2c_2d(h, w, in.get(), out.get(), FFTW_ESTIMATE);
  }
  if (!plan) return makeError(ErrorCode::Resource, "transfer function: FFTW could not plan");
  // The photograph in the frame's top-left corner: where it sits changes only the phase.
  std::fill(in.get(), in.get() + std::size_t(w) * h, 0.0f);
  for (int y = 0; y < photo.height(); ++y)
    std::copy(photo.plane(0) + std::size_t(y) * photo.width(), photo.plane(0) + std::size_t(y + 1) * photo.width(),
              in.get() + std::size_t(y) * w);
  fftwf_execute(plan);
  {
    std::lock_guard lock(plannerMutex());
    fftwf_destroy_plan(plan);
  }
  // The real transform keeps kx <= w/2; the rest is the conjugate mirror H(-k).
  auto magnitude = [&](int kx, int ky) -> double {
    if (kx >= half) {
      kx = (w - kx) % w;
      ky = (h - ky) % h;
    }
    const fftwf_complex& c = out.get()[std::size_t(ky) * half + kx];
    return std::hypot(double(c[0]), double(c[1]));
  };
  return normalisedShifted(w, h, magnitude);
}

Result<Image> transferFunctionReference(const Image& photo, int zeroPadding) {
  LFCAM_TRY(checkPhoto(photo, zeroPadding));
  const int w = photo.width() * zeroPadding, h = photo.height() * zeroPadding;
  auto magnitude = [&](int kx, int ky) {
    std::complex<double> sum = 0;
    for (int y = 0; y < photo.height(); ++y)
      for (int x = 0; x < photo.width(); ++x) {
        const double phase = -2 * std::numbers::pi * (double(kx) * x / w + double(ky) * y / h);
        sum += double(photo.at(x, y, 0)) * std::polar(1.0, phase);
      }
    return std::abs(sum);
  };
  return normalisedShifted(w, h, magnitude);
}

double cutoffFrequency(const Image& transfer, double energyShare) {
  const int w = transfer.width(), h = transfer.height();
  std::vector<std::pair<double, double>> samples;  // (radius, energy)
  samples.reserve(transfer.planeSize());
  double total = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double fx = double(x - w / 2) / w, fy = double(y - h / 2) / h;
      const double e = double(transfer.at(x, y, 0)) * transfer.at(x, y, 0);
      samples.emplace_back(std::hypot(fx, fy), e);
      total += e;
    }
  if (!(total > 0)) return 0;
  std::sort(samples.begin(), samples.end());
  // The energy within radius r, as a continuous curve: linear between the radii of the samples,
  // frequencies at one radius entering together (so the answer does not depend on their order).
  const double target = energyShare * total;
  double sum = 0, previousRadius = 0, previousSum = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    sum += samples[i].second;
    if (i + 1 < samples.size() && samples[i + 1].first == samples[i].first) continue;
    if (sum >= target) {
      const double step = sum - previousSum;
      const double t = step > 0 ? (target - previousSum) / step : 1.0;
      return previousRadius + std::clamp(t, 0.0, 1.0) * (samples[i].first - previousRadius);
    }
    previousRadius = samples[i].first;
    previousSum = sum;
  }
  return samples.back().first;
}

}  // namespace lfcam
