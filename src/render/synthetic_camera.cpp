// The synthetic camera (Equation 5) and the moving observer (Equation 7): synthetic_camera.hpp.
//
// Three ways to evaluate the same integral:
//   - beta = 1: every ray of one aperture sample hits the lens plane at the same u, so each
//     sample is one view (or a bilinear blend of four, between views) shifted by a constant:
//     the shift-and-add kernel of refocus.cpp (shift_and_add.hpp), fast.
//   - beta != 1: u varies across the image, so each ray is interpolated quadrilinearly in
//     (u, v, s, t), per output pixel: generalRows below, in float32 and threaded.
//   - the reference: generalRows in float64, single-threaded, for every case.
#include "lfcam/synthetic_camera.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lfcam/parallel.hpp"
#include "lfcam/refocus.hpp"
#include "render/references.hpp"
#include "render/shift_and_add.hpp"

namespace lfcam {

double Aperture::weight(double u, double v, int nu, int nv) const {
  const double du = u - centreU, dv = v - centreV;
  const double tolerance = 1e-9;  // views exactly on the edge are inside
  switch (shape) {
    case Shape::Full: return 1;
    case Shape::Circle: return du * du + dv * dv <= radius * radius + tolerance ? 1 : 0;
    case Shape::Square: return std::abs(du) <= radius + tolerance && std::abs(dv) <= radius + tolerance ? 1 : 0;
    case Shape::Mask: {
      if (!mask || mask->empty() || nu <= 0 || nv <= 0) return 0;
      const double x = (du / nu + 0.5) * mask->width(), y = (dv / nv + 0.5) * mask->height();
      if (!(x >= 0 && y >= 0 && x < mask->width() && y < mask->height())) return 0;
      double sum = 0;
      for (int c = 0; c < mask->channels(); ++c) sum += mask->at(int(x), int(y), c);
      return std::clamp(sum / mask->channels(), 0.0, 1.0);
    }
  }
  return 0;
}

namespace {

// The linear map of synthetic_camera.hpp from (aperture sample, output pixel) to the ray's
// coordinates in the light field, per axis: lens = uu * u' + us * sigma,
// spatial = su * u' + ss * sigma (from the centres).
struct RayMap {
  double uu = 1, us = 0, su = 0, ss = 1;
};

Result<RayMap> rayMap(double slope, double beta, double parallax) {
  if (!std::isfinite(slope) || !std::isfinite(beta))
    return makeError(ErrorCode::Usage, "synthetic camera: slope and beta must be finite");
  if (beta == 1) return RayMap{1, 0, -slope, 1};  // Equation 6: no need to know the optics
  if (!(parallax > 0) || !std::isfinite(parallax))
    return makeError(ErrorCode::Usage,
                     "synthetic camera: moving the lens plane (beta != 1) needs the optics of the light field "
                     "(du/ds); this one has none");
  if (slope == parallax)
    return makeError(ErrorCode::Usage, "synthetic camera: the slope equals du/ds, a film plane at infinity");
  const double alpha = parallax / (parallax - slope);  // inverse of slope = r (1 - 1/alpha)
  const double separation = alpha + beta - 1;
  if (std::abs(separation) < 1e-9)
    return makeError(ErrorCode::Usage, "synthetic camera: film and lens planes coincide (alpha + beta = 1)");
  const double a = alpha / separation, b = beta / separation;
  return RayMap{a, -alpha * (1 - a) / parallax, -parallax * (1 - b), alpha * b};
}

// One sample of the aperture: a position on the synthetic lens plane and its weight A.
struct ApertureSample {
  double u = 0, v = 0;  // view steps from the centre
  double weight = 0;
};

// supersampling^2 samples per view, at the centres of a regular grid over each view's square
// (supersampling 1: the views themselves); samples of weight 0 are dropped.
std::vector<ApertureSample> apertureSamples(const LightField& lightField, const Aperture& aperture, int supersampling) {
  std::vector<ApertureSample> samples;
  const int k = std::max(1, supersampling);
  for (int v = 0; v < lightField.nv(); ++v)
    for (int j = 0; j < k; ++j)
      for (int u = 0; u < lightField.nu(); ++u)
        for (int i = 0; i < k; ++i) {
          const double su = lightField.uFromCentre(u) + (i + 0.5) / k - 0.5;
          const double sv = lightField.vFromCentre(v) + (j + 0.5) / k - 0.5;
          const double weight = aperture.weight(su, sv, lightField.nu(), lightField.nv());
          if (weight > 0) samples.push_back({su, sv, weight});
        }
  return samples;
}

// Linear interpolation taps along one axis at index position p: (index, coefficient) pairs
// inside [0, size), clamped to the ends first when `clamp`.
struct Taps {
  int index[2] = {0, 0};
  double coefficient[2] = {0, 0};
  int count = 0;
};

Taps linearTaps(double p, int size, bool clamp) {
  Taps taps;
  if (clamp) p = std::clamp(p, 0.0, double(size - 1));
  if (!(p > -1 && p < size)) return taps;
  const double whole = std::floor(p), fraction = p - whole;
  for (int k = 0; k < 2; ++k) {
    const int index = int(whole) + k;
    const double coefficient = k ? fraction : 1 - fraction;
    if (index < 0 || index >= size || coefficient == 0) continue;
    taps.index[taps.count] = index;
    taps.coefficient[taps.count++] = coefficient;
  }
  return taps;
}

// Output rows [y0, y1) by the ray map, per pixel: each aperture sample's ray interpolated
// quadrilinearly, taps weighted by A x coefficient x the light field's weight, normalised.
// Real = double is the reference; float the threaded kernel.
template <class Real>
void generalRows(const LightField& lightField, const RayMap& map, const std::vector<ApertureSample>& samples,
                 bool clampToLens, int y0, int y1, Image& out) {
  const LightFieldShape& shape = lightField.shape();
  const double lensCentreU = 0.5 * (shape.nu - 1), lensCentreV = 0.5 * (shape.nv - 1);
  std::vector<Real> sum(shape.channels);
  for (int y = y0; y < y1; ++y) {
    const double sigmaY = y + 0.5 - 0.5 * shape.nt;
    for (int x = 0; x < shape.ns; ++x) {
      const double sigmaX = x + 0.5 - 0.5 * shape.ns;
      std::fill(sum.begin(), sum.end(), Real(0));
      Real weightSum = 0;
      for (const ApertureSample& sample : samples) {
        // The ray through the sample and the pixel, in index coordinates of the light field
        // (pixel index = position - 0.5).
        const Taps tu = linearTaps(map.uu * sample.u + map.us * sigmaX + lensCentreU, shape.nu, clampToLens);
        const Taps tv = linearTaps(map.uu * sample.v + map.us * sigmaY + lensCentreV, shape.nv, clampToLens);
        if (!tu.count || !tv.count) continue;
        const Taps ts = linearTaps(0.5 * shape.ns + map.su * sample.u + map.ss * sigmaX - 0.5, shape.ns, false);
        const Taps tt = linearTaps(0.5 * shape.nt + map.su * sample.v + map.ss * sigmaY - 0.5, shape.nt, false);
        if (!ts.count || !tt.count) continue;
        for (int a = 0; a < tv.count; ++a)
          for (int b = 0; b < tu.count; ++b)
            for (int c = 0; c < tt.count; ++c)
              for (int d = 0; d < ts.count; ++d) {
                const int u = tu.index[b], v = tv.index[a], s = ts.index[d], t = tt.index[c];
                Real w =
                    Real(sample.weight * tv.coefficient[a] * tu.coefficient[b] * tt.coefficient[c] * ts.coefficient[d]);
                if (lightField.hasWeight()) w *= lightField.weightPlane(u, v)[std::size_t(t) * shape.ns + s];
                if (w == 0) continue;
                weightSum += w;
                for (int channel = 0; channel < shape.channels; ++channel)
                  sum[channel] += w * Real(lightField.at(u, v, s, t, channel));
              }
      }
      for (int channel = 0; channel < shape.channels; ++channel)
        out.at(x, y, channel) = weightSum > 0 ? float(sum[channel] / weightSum) : 0.0f;
    }
  }
}

template <class Real>
Image renderGeneral(const LightField& lightField, const RayMap& map, const std::vector<ApertureSample>& samples,
                    bool clampToLens, bool threaded) {
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns, shape.nt, shape.channels);
  if (!threaded) {
    generalRows<Real>(lightField, map, samples, clampToLens, 0, shape.nt, out);
    return out;
  }
  parallelFor(0, std::size_t(shape.nt), 4, [&](std::size_t begin, std::size_t end) {
    generalRows<Real>(lightField, map, samples, clampToLens, int(begin), int(end), out);
  });
  return out;
}

int supersamplingFor(const SyntheticCamera& camera, const RenderOptions& options) {
  if (options.method == RenderMethod::Fast) return 1;
  if (options.supersampling > 0) return options.supersampling;
  return std::clamp(int(std::ceil(std::abs(camera.slope))), 1, 8);
}

Status checkInput(const LightField& lightField, const std::vector<ApertureSample>& samples) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "synthetic camera: empty light field");
  if (samples.empty())
    return makeError(ErrorCode::Usage, "synthetic camera: the aperture lets no ray of the light field through");
  return {};
}

// beta = 1: each aperture sample at lens position (u', v') is the view there (a bilinear blend of
// the four around it between views), sampled at the constant shift -(u', v') slope.
Image renderShiftAndAdd(const LightField& lightField, double slope, const std::vector<ApertureSample>& samples) {
  std::vector<ShiftAndAddTerm> terms;
  for (const ApertureSample& sample : samples) {
    const Taps tu = linearTaps(sample.u + 0.5 * (lightField.nu() - 1), lightField.nu(), false);
    const Taps tv = linearTaps(sample.v + 0.5 * (lightField.nv() - 1), lightField.nv(), false);
    for (int a = 0; a < tv.count; ++a)
      for (int b = 0; b < tu.count; ++b)
        terms.push_back({tu.index[b], tv.index[a], -sample.u * slope, -sample.v * slope,
                         float(sample.weight * tu.coefficient[b] * tv.coefficient[a])});
  }
  return shiftAndAdd(lightField, std::move(terms));
}

}  // namespace

Result<Image> renderSyntheticPhoto(const LightField& lightField, const SyntheticCamera& camera,
                                   const RenderOptions& options) {
  LFCAM_ASSIGN_OR_RETURN(auto map, rayMap(camera.slope, camera.beta, camera.parallax));
  const int supersampling = supersamplingFor(camera, options);
  const std::vector<ApertureSample> samples = apertureSamples(lightField, camera.aperture, supersampling);
  LFCAM_TRY(checkInput(lightField, samples));
  if (camera.beta == 1) {
    // The full aperture at the views is the plain refocus, with its separable normalisation.
    if (camera.aperture.shape == Aperture::Shape::Full && supersampling == 1) return refocus(lightField, camera.slope);
    return renderShiftAndAdd(lightField, camera.slope, samples);
  }
  return renderGeneral<float>(lightField, map, samples, false, true);
}

Result<Image> renderSyntheticPhotoReference(const LightField& lightField, const SyntheticCamera& camera,
                                            int supersampling) {
  LFCAM_ASSIGN_OR_RETURN(auto map, rayMap(camera.slope, camera.beta, camera.parallax));
  const std::vector<ApertureSample> samples = apertureSamples(lightField, camera.aperture, supersampling);
  LFCAM_TRY(checkInput(lightField, samples));
  return renderGeneral<double>(lightField, map, samples, false, false);
}

namespace {

Result<Image> observeWith(const LightField& lightField, const Observer& observer, bool reference) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "observer: empty light field");
  if (!std::isfinite(observer.u) || !std::isfinite(observer.v))
    return makeError(ErrorCode::Usage, "observer: the position must be finite");
  // alpha = 1: the real film plane.
  LFCAM_ASSIGN_OR_RETURN(const auto map, rayMap(0.0, observer.beta, observer.parallax));
  const std::vector<ApertureSample> pinhole{{observer.u, observer.v, 1.0}};
  if (reference) return renderGeneral<double>(lightField, map, pinhole, observer.clampToLens, false);
  if (observer.beta == 1) {
    // On the real lens plane the pinhole's ray lands on the same (u, v) for every pixel: a blend
    // of the (at most) four views around it, at no shift, which the shift-and-add kernel streams
    // (clamping moves the pinhole itself onto the lens). Measured by lfcam bench's observer.
    ApertureSample sample = pinhole.front();
    if (observer.clampToLens) {
      sample.u = std::clamp(sample.u, lightField.uFromCentre(0), lightField.uFromCentre(lightField.nu() - 1));
      sample.v = std::clamp(sample.v, lightField.vFromCentre(0), lightField.vFromCentre(lightField.nv() - 1));
    }
    return renderShiftAndAdd(lightField, 0.0, {sample});
  }
  return renderGeneral<float>(lightField, map, pinhole, observer.clampToLens, true);
}

}  // namespace

Result<Image> observe(const LightField& lightField, const Observer& observer) {
  return observeWith(lightField, observer, false);
}

Result<Image> observeReference(const LightField& lightField, const Observer& observer) {
  return observeWith(lightField, observer, true);
}

}  // namespace lfcam
