// The depth-range passband filter of denoise.hpp: one in-place 4D real FFT per channel over the
// padded light field, the passband, the inverse, and the division by the filtered view indicator.
#include "lfcam/render/denoise.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <numbers>
#include <vector>

#include "core/fftw_planner.hpp"
#include "core/parallel.hpp"
#include "render/denoise_padding.hpp"
#include "render/references.hpp"

namespace lfcam {

namespace {

// Beyond this many standard deviations from the passband's segment the passband is taken as 0
// (exp(-18) < 2e-8): it bounds the copies of the segment worth measuring.
constexpr double kReach = 6;

// The squared distance from (fu, fv) to the segment from a = slopeMin (fs, ft) to slopeMax (fs, ft)
// or to its copies one cycle per view step apart, when under (kReach bandwidths)^2; else infinity.
double squaredDistanceToSlopes(const DenoiseOptions& options, double fs, double ft, double fu, double fv) {
  const double ax = options.slopeMin * fs, ay = options.slopeMin * ft;
  const double dx = options.slopeMax * fs - ax, dy = options.slopeMax * ft - ay;
  const double length2 = dx * dx + dy * dy, reach = kReach * options.bandwidth;
  // The copies k whose bounding box, widened by `reach`, holds the point.
  const int kx0 = int(std::ceil(std::min(ax, ax + dx) - reach - fu)),
            kx1 = int(std::floor(std::max(ax, ax + dx) + reach - fu));
  const int ky0 = int(std::ceil(std::min(ay, ay + dy) - reach - fv)),
            ky1 = int(std::floor(std::max(ay, ay + dy) + reach - fv));
  double nearest = std::numeric_limits<double>::infinity();
  for (int ky = ky0; ky <= ky1; ++ky)
    for (int kx = kx0; kx <= kx1; ++kx) {
      const double px = fu + kx - ax, py = fv + ky - ay;
      const double along = length2 > 0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
      const double ex = px - along * dx, ey = py - along * dy;
      nearest = std::min(nearest, ex * ex + ey * ey);
    }
  return nearest <= reach * reach ? nearest : std::numeric_limits<double>::infinity();
}

double gaussian(double squaredDistance, double bandwidth) {
  return std::isfinite(squaredDistance) ? std::exp(-squaredDistance / (2 * bandwidth * bandwidth)) : 0.0;
}

}  // namespace

double denoisePassband(const DenoiseOptions& options, double fs, double ft, double fu, double fv) {
  return gaussian(squaredDistanceToSlopes(options, fs, ft, fu, fv), options.bandwidth);
}

DenoiseOptions defaultDenoiseOptions(const LightField& lightField) {
  DenoiseOptions options;
  const LightFieldMetadata& metadata = lightField.metadata;
  if (metadata.disparityMin && metadata.disparityMax && *metadata.disparityMin <= *metadata.disparityMax) {
    options.slopeMin = *metadata.disparityMin;
    options.slopeMax = *metadata.disparityMax;
  }
  return options;
}

namespace {

template <class T>
using FftwBuffer = std::unique_ptr<T[], fftw::Free>;

Status checkOptions(const LightField& lightField, const DenoiseOptions& options) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "denoise: empty light field");
  if (!std::isfinite(options.slopeMin) || !std::isfinite(options.slopeMax) || options.slopeMin > options.slopeMax)
    return makeError(ErrorCode::Usage, "denoise: the depth range must be two finite slopes A:B with A <= B");
  if (!(options.bandwidth > 0 && options.bandwidth <= 0.5))
    return makeError(ErrorCode::Usage, "denoise: the bandwidth must lie in (0, 0.5] cycles per view step");
  return {};
}

}  // namespace

namespace denoise_detail {

DenoisePadding paddingFor(const LightFieldShape& shape, const DenoiseOptions& options) {
  DenoisePadding padding;
  padding.shear = 0.5 * (options.slopeMin + options.slopeMax);
  // The farthest any passband slope, or the shear, moves content between two views.
  const double farthest =
      std::max(std::abs(options.slopeMin), std::abs(options.slopeMax)) * double(std::max(shape.nu, shape.nv) - 1);
  padding.margin = int(std::ceil(farthest)) + 4;
  padding.ns = (shape.ns + 2 * padding.margin) | 1;
  padding.nt = (shape.nt + 2 * padding.margin) | 1;
  padding.nu = 2 * shape.nu;
  padding.nv = 2 * shape.nv;
  return padding;
}

int mirror(int index, int size) {
  if (size == 1) return 0;
  const int period = 2 * size;
  index %= period;
  if (index < 0) index += period;
  return index < size ? index : period - 1 - index;
}

double frequency(int k, int size) { return double(k <= size / 2 ? k : k - size) / size; }

DenoiseOptions shearedPassband(const DenoiseOptions& options, const DenoisePadding& padding) {
  DenoiseOptions sheared = options;
  sheared.slopeMin -= padding.shear;
  sheared.slopeMax -= padding.shear;
  return sheared;
}

double mirroredPassband(const DenoiseOptions& sheared, double fs, double ft, double fu, double fv) {
  return gaussian(
      std::min(squaredDistanceToSlopes(sheared, fs, ft, fu, fv), squaredDistanceToSlopes(sheared, fs, -ft, fu, fv)),
      sheared.bandwidth);
}

}  // namespace denoise_detail

namespace {

// Per channel: each view's 2D spectrum, sheared so that the passband's middle slope stands still,
// mirrored angularly (the views' sequence then wraps round without a jump, so a surface's energy
// stays on its plane instead of leaking across the angular spectrum); the angular DFT of every
// spatial frequency; the passband; and back.
LightField filterSamples(const LightField& lightField, const DenoiseOptions& options) {
  using namespace denoise_detail;
  const LightFieldShape& shape = lightField.shape();
  const DenoisePadding padding = paddingFor(shape, options);
  const DenoiseOptions sheared = shearedPassband(options, padding);
  const int Ns = padding.ns, Nt = padding.nt, Mu = padding.nu, Mv = padding.nv, margin = padding.margin;
  const int half = Ns / 2 + 1;
  const std::size_t frequencies = std::size_t(Nt) * half, slots = std::size_t(Mu) * Mv;

  // The passband, [v'][u'][kt][ks], times the inverse transforms' 1 / size.
  const double scale = 1.0 / (double(Ns) * Nt * Mu * Mv);
  std::vector<float> passband(slots * frequencies);
  parallelFor(0, slots * Nt, 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row < end; ++row) {
      const std::size_t slot = row / Nt;
      const int kt = int(row % Nt), ku = int(slot % Mu), kv = int(slot / Mu);
      const double fu = frequency(ku, Mu), fv = frequency(kv, Mv), ft = frequency(kt, Nt);
      float* out = passband.data() + row * half;
      for (int ks = 0; ks < half; ++ks) out[ks] = float(scale * mirroredPassband(sheared, double(ks) / Ns, ft, fu, fv));
    }
  });

  FftwBuffer<fftwf_complex> spectrum(
      static_cast<fftwf_complex*>(fftwf_malloc(sizeof(fftwf_complex) * slots * frequencies)));
  FftwBuffer<float> real(static_cast<float*>(fftwf_malloc(sizeof(float) * std::size_t(Ns) * Nt)));
  FftwBuffer<fftwf_complex> plane(static_cast<fftwf_complex*>(fftwf_malloc(sizeof(fftwf_complex) * frequencies)));
  if (!spectrum || !real || !plane) throw std::bad_alloc();
  fftwf_plan spatialForward, spatialInverse, angularForward, angularInverse;
  {
    std::lock_guard lock(fftw::plannerMutex());
    spatialForward = fftwf_plan_dft_r2c_2d(Nt, Ns, real.get(), plane.get(), FFTW_ESTIMATE);
    spatialInverse = fftwf_plan_dft_c2r_2d(Nt, Ns, plane.get(), real.get(), FFTW_ESTIMATE);
    const int n[2] = {Mv, Mu};
    const int count = int(frequencies), stride = int(frequencies);
    angularForward = fftwf_plan_many_dft(2, n, count, spectrum.get(), nullptr, stride, 1, spectrum.get(), nullptr,
                                         stride, 1, FFTW_FORWARD, FFTW_ESTIMATE);
    angularInverse = fftwf_plan_many_dft(2, n, count, spectrum.get(), nullptr, stride, 1, spectrum.get(), nullptr,
                                         stride, 1, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  // The shear's phase at view offset (du, dv) from the centre: exp(sign 2 pi i (fs du + ft dv) shear).
  auto shearPlane = [&](fftwf_complex* data, double du, double dv, double sign) {
    for (int kt = 0; kt < Nt; ++kt) {
      const double ft = frequency(kt, Nt);
      for (int ks = 0; ks < half; ++ks) {
        const std::complex<double> phase =
            std::polar(1.0, sign * 2 * std::numbers::pi * (double(ks) / Ns * du + ft * dv) * padding.shear);
        fftwf_complex& value = data[std::size_t(kt) * half + ks];
        const std::complex<double> product = std::complex<double>(value[0], value[1]) * phase;
        value[0] = float(product.real());
        value[1] = float(product.imag());
      }
    }
  };

  LightField out(shape);
  auto slotOf = [&](int u, int v) { return spectrum.get() + (std::size_t(v) * Mu + u) * frequencies; };
  for (int c = 0; c < shape.channels; ++c) {
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u) {
        const float* in = lightField.plane(u, v, c);
        for (int t = 0; t < Nt; ++t) {
          const float* source = in + std::size_t(mirror(t - margin, shape.nt)) * shape.ns;
          float* row = real.get() + std::size_t(t) * Ns;
          for (int s = 0; s < Ns; ++s) row[s] = source[mirror(s - margin, shape.ns)];
        }
        fftwf_execute_dft_r2c(spatialForward, real.get(), plane.get());
        shearPlane(plane.get(), lightField.uFromCentre(u), lightField.vFromCentre(v), -1);
        const std::size_t bytes = sizeof(fftwf_complex) * frequencies;
        std::memcpy(slotOf(u, v), plane.get(), bytes);
        std::memcpy(slotOf(Mu - 1 - u, v), plane.get(), bytes);
        std::memcpy(slotOf(u, Mv - 1 - v), plane.get(), bytes);
        std::memcpy(slotOf(Mu - 1 - u, Mv - 1 - v), plane.get(), bytes);
      }
    fftwf_execute_dft(angularForward, spectrum.get(), spectrum.get());
    parallelFor(0, slots * frequencies, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        spectrum[i][0] *= passband[i];
        spectrum[i][1] *= passband[i];
      }
    });
    fftwf_execute_dft(angularInverse, spectrum.get(), spectrum.get());
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u) {
        std::memcpy(plane.get(), slotOf(u, v), sizeof(fftwf_complex) * frequencies);
        shearPlane(plane.get(), lightField.uFromCentre(u), lightField.vFromCentre(v), +1);
        fftwf_execute_dft_c2r(spatialInverse, plane.get(), real.get());
        float* target = out.plane(u, v, c);
        for (int t = 0; t < shape.nt; ++t)
          std::copy_n(real.get() + std::size_t(t + margin) * Ns + margin, shape.ns, target + std::size_t(t) * shape.ns);
      }
  }
  {
    std::lock_guard lock(fftw::plannerMutex());
    for (fftwf_plan plan : {spatialForward, spatialInverse, angularForward, angularInverse}) fftwf_destroy_plan(plan);
  }
  return out;
}

// In place, the DFT along one axis of a [Mv][Mu][Nt][Ns] array (sign -1 forward, +1 inverse), term
// by term in float64, on the lines whose other indices pass `keep`.
template <class Keep>
void dftAlongAxis(std::vector<std::complex<double>>& data, const int (&size)[4], int axis, int sign, Keep keep) {
  std::size_t stride = 1;
  for (int a = 3; a > axis; --a) stride *= std::size_t(size[a]);
  const int n = size[axis];
  std::vector<std::complex<double>> line(n);
  for (std::size_t start = 0; start < data.size(); ++start) {
    if ((start / stride) % std::size_t(n) != 0 || !keep(start)) continue;  // not the first sample of a kept line
    for (int k = 0; k < n; ++k) {
      std::complex<double> sum = 0;
      for (int j = 0; j < n; ++j)
        sum += data[start + std::size_t(j) * stride] * std::polar(1.0, sign * 2 * std::numbers::pi * double(k) * j / n);
      line[k] = sum;
    }
    for (int k = 0; k < n; ++k) data[start + std::size_t(k) * stride] = line[k];
  }
}

LightField filterSamplesReference(const LightField& lightField, const DenoiseOptions& options) {
  using namespace denoise_detail;
  const LightFieldShape& shape = lightField.shape();
  const DenoisePadding padding = paddingFor(shape, options);
  const DenoiseOptions sheared = shearedPassband(options, padding);
  const int size[4] = {padding.nv, padding.nu, padding.nt, padding.ns};
  const std::size_t count = std::size_t(size[0]) * size[1] * size[2] * size[3];
  const std::size_t viewSize = std::size_t(size[2]) * size[3];
  auto index = [&](int v, int u, int t, int s) { return ((std::size_t(v) * size[1] + u) * size[2] + t) * size[3] + s; };
  auto isRealView = [&](std::size_t i) {
    const std::size_t view = i / viewSize;
    return int(view % size[1]) < shape.nu && int(view / size[1]) < shape.nv;
  };
  auto everyLine = [](std::size_t) { return true; };
  auto shear = [&](std::vector<std::complex<double>>& frame, double sign) {
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u)
        for (int kt = 0; kt < size[2]; ++kt)
          for (int ks = 0; ks < size[3]; ++ks)
            frame[index(v, u, kt, ks)] *= std::polar(1.0, sign * 2 * std::numbers::pi *
                                                              (frequency(ks, size[3]) * lightField.uFromCentre(u) +
                                                               frequency(kt, size[2]) * lightField.vFromCentre(v)) *
                                                              padding.shear);
  };
  LightField out(shape);
  for (int c = 0; c < shape.channels; ++c) {
    std::vector<std::complex<double>> frame(count, 0.0);
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u)
        for (int t = 0; t < size[2]; ++t)
          for (int s = 0; s < size[3]; ++s)
            frame[index(v, u, t, s)] =
                lightField.at(u, v, mirror(s - padding.margin, shape.ns), mirror(t - padding.margin, shape.nt), c);
    dftAlongAxis(frame, size, 2, -1, isRealView);
    dftAlongAxis(frame, size, 3, -1, isRealView);
    shear(frame, -1);
    for (int v = 0; v < size[0]; ++v)  // the angular mirror images
      for (int u = 0; u < size[1]; ++u) {
        const int sourceU = u < shape.nu ? u : size[1] - 1 - u, sourceV = v < shape.nv ? v : size[0] - 1 - v;
        if (sourceU == u && sourceV == v) continue;
        std::copy_n(frame.begin() + std::ptrdiff_t(index(sourceV, sourceU, 0, 0)), viewSize,
                    frame.begin() + std::ptrdiff_t(index(v, u, 0, 0)));
      }
    dftAlongAxis(frame, size, 0, -1, everyLine);
    dftAlongAxis(frame, size, 1, -1, everyLine);
    for (int kv = 0; kv < size[0]; ++kv)
      for (int ku = 0; ku < size[1]; ++ku)
        for (int kt = 0; kt < size[2]; ++kt)
          for (int ks = 0; ks < size[3]; ++ks)
            frame[index(kv, ku, kt, ks)] *= mirroredPassband(sheared, frequency(ks, size[3]), frequency(kt, size[2]),
                                                             frequency(ku, size[1]), frequency(kv, size[0]));
    dftAlongAxis(frame, size, 0, +1, everyLine);
    dftAlongAxis(frame, size, 1, +1, everyLine);
    shear(frame, +1);
    dftAlongAxis(frame, size, 2, +1, isRealView);
    dftAlongAxis(frame, size, 3, +1, isRealView);
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u)
        for (int t = 0; t < shape.nt; ++t)
          for (int s = 0; s < shape.ns; ++s)
            out.at(u, v, s, t, c) =
                float(frame[index(v, u, t + padding.margin, s + padding.margin)].real() / double(count));
  }
  return out;
}

// With a weight, the normalised convolution filter(weight x samples) / filter(weight), so that
// samples the aperture cut off (weight 0) neither darken nor blur their neighbours; where the
// filtered weight is under 5 % the sample is kept as it was.
Result<LightField> filterWeighted(const LightField& lightField, const DenoiseOptions& options,
                                  LightField (*filter)(const LightField&, const DenoiseOptions&)) {
  LFCAM_TRY(checkOptions(lightField, options));
  LightField out;
  if (!lightField.hasWeight()) {
    out = filter(lightField, options);
  } else {
    const LightFieldShape& shape = lightField.shape();
    LightField weighted(shape, Pages::Ordinary), weight({shape.nu, shape.nv, shape.ns, shape.nt, 1}, Pages::Ordinary);
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u) {
        const float* w = lightField.weightPlane(u, v);
        std::copy_n(w, shape.viewPixels(), weight.plane(u, v, 0));
        for (int c = 0; c < shape.channels; ++c)
          for (std::size_t i = 0; i < shape.viewPixels(); ++i)
            weighted.plane(u, v, c)[i] = lightField.plane(u, v, c)[i] * w[i];
      }
    out = filter(weighted, options);
    const LightField filteredWeight = filter(weight, options);
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u) {
        const float* w = filteredWeight.plane(u, v, 0);
        for (int c = 0; c < shape.channels; ++c) {
          float* target = out.plane(u, v, c);
          const float* source = lightField.plane(u, v, c);
          for (std::size_t i = 0; i < shape.viewPixels(); ++i) target[i] = w[i] > 0.05f ? target[i] / w[i] : source[i];
        }
      }
    out.enableWeight();
    std::copy(lightField.weights().begin(), lightField.weights().end(), out.weights().begin());
  }
  out.metadata = lightField.metadata;
  return out;
}

}  // namespace

Result<LightField> denoise(const LightField& lightField, const DenoiseOptions& options) {
  return filterWeighted(lightField, options, filterSamples);
}

Result<LightField> denoiseReference(const LightField& lightField, const DenoiseOptions& options) {
  return filterWeighted(lightField, options, filterSamplesReference);
}

}  // namespace lfcam
