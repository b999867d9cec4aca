// The general path of Equation 5 and the geometry it shares with the fast kernels (ray_paths.hpp).
#include "render/ray_paths.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/parallel.hpp"
#include "render/shift_and_add.hpp"

namespace lfcam {

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

double FilmSlopes::at(int x, int y, double px, double py) const {
  if (depth) return std::clamp(double(depth->at(x, y, 0)), farSlope, nearSlope);
  return plane.slopeAt(px, py);
}

namespace {

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

// Output rows [y0, y1) of renderRays.
template <class Real>
void rayRows(const LightField& lightField, const FilmSlopes& film, const std::vector<ApertureSample>& samples,
             const RayOptions& options, int y0, int y1, Image& out) {
  const LightFieldShape& shape = lightField.shape();
  const int k = options.factor;
  const double lensCentreU = 0.5 * (shape.nu - 1), lensCentreV = 0.5 * (shape.nv - 1);
  std::vector<Real> sum(shape.channels);
  for (int y = y0; y < y1; ++y) {
    const int viewY = y / k;
    const double pointY = (y + 0.5) / k, sigmaY = pointY - 0.5 * shape.nt;
    for (int x = 0; x < out.width(); ++x) {
      const int viewX = x / k;
      const double pointX = (x + 0.5) / k, sigmaX = pointX - 0.5 * shape.ns;
      const double slope = film.at(viewX, viewY, pointX, pointY);
      const Result<RayMap> found = rayMap(slope, options.beta, options.parallax);
      for (int channel = 0; channel < shape.channels; ++channel) out.at(x, y, channel) = 0.0f;
      if (!found) continue;
      const RayMap& map = found.value();
      const float own = film.depth ? film.depth->at(viewX, viewY, 0) : 0.0f;
      // Every ray, or with occluders those no nearer surface hides; if they hide them all (an
      // estimated map read this pixel farther than every surface its rays meet), every ray.
      for (const bool test : {options.occluders != nullptr, false}) {
        std::fill(sum.begin(), sum.end(), Real(0));
        Real weightSum = 0;
        for (const ApertureSample& sample : samples) {
          // The ray through the sample and the pixel, in index coordinates of the light field
          // (pixel index = position - 0.5).
          const Taps tu = linearTaps(map.uu * sample.u + map.us * sigmaX + lensCentreU, shape.nu, options.clampToLens);
          const Taps tv = linearTaps(map.uu * sample.v + map.us * sigmaY + lensCentreV, shape.nv, options.clampToLens);
          if (!tu.count || !tv.count) continue;
          const Taps ts = linearTaps(0.5 * shape.ns + map.su * sample.u + map.ss * sigmaX - 0.5, shape.ns, false);
          const Taps tt = linearTaps(0.5 * shape.nt + map.su * sample.v + map.ss * sigmaY - 0.5, shape.nt, false);
          if (!ts.count || !tt.count) continue;
          for (int a = 0; a < tv.count; ++a)
            for (int b = 0; b < tu.count; ++b)
              for (int c = 0; c < tt.count; ++c)
                for (int d = 0; d < ts.count; ++d) {
                  const int u = tu.index[b], v = tv.index[a], s = ts.index[d], t = tt.index[c];
                  if (test && options.occluders->hides(u, v, t, s, own)) continue;
                  Real w = Real(sample.weight * tv.coefficient[a] * tu.coefficient[b] * tt.coefficient[c] *
                                ts.coefficient[d]);
                  if (lightField.hasWeight()) w *= lightField.weightPlane(u, v)[std::size_t(t) * shape.ns + s];
                  if (w == 0) continue;
                  weightSum += w;
                  for (int channel = 0; channel < shape.channels; ++channel)
                    sum[channel] += w * Real(lightField.at(u, v, s, t, channel));
                }
        }
        if (weightSum == 0) continue;
        for (int channel = 0; channel < shape.channels; ++channel)
          out.at(x, y, channel) = float(sum[channel] / weightSum);
        break;
      }
    }
  }
}

}  // namespace

template <class Real>
Image renderRays(const LightField& lightField, const FilmSlopes& film, const std::vector<ApertureSample>& samples,
                 const RayOptions& options) {
  const LightFieldShape& shape = lightField.shape();
  Image out(shape.ns * options.factor, shape.nt * options.factor, shape.channels);
  if (std::is_same_v<Real, double>) {
    rayRows<Real>(lightField, film, samples, options, 0, out.height(), out);
    return out;
  }
  parallelFor(0, std::size_t(out.height()), 4, [&](std::size_t begin, std::size_t end) {
    rayRows<Real>(lightField, film, samples, options, int(begin), int(end), out);
  });
  return out;
}

template Image renderRays<float>(const LightField&, const FilmSlopes&, const std::vector<ApertureSample>&,
                                 const RayOptions&);
template Image renderRays<double>(const LightField&, const FilmSlopes&, const std::vector<ApertureSample>&,
                                  const RayOptions&);

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

}  // namespace lfcam
