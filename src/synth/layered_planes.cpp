// The layered-planes light field: fronto-parallel textured planes rendered straight into
// (u, v, s, t), so that every pixel's true disparity is known exactly (layered_planes.hpp).
#include "lfcam/synth/layered_planes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>

#include "core/parallel.hpp"

namespace lfcam {

namespace {

// ------------------------------------------------------------------------------------------------
// Textures: scalar functions of the plane's own coordinates (centre-view pixels), in [0, 1].

// A 64-bit mix (splitmix64's finaliser): lattice values that depend only on their inputs, so
// the light field is the same on every machine and thread count.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t hash(std::uint64_t seed, std::uint64_t a) { return mix(seed ^ mix(a)); }

double unitFromHash(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }  // [0, 1)

// One mix per lattice point (the noise needs 12 per sample, the costliest part of rendering);
// odd multipliers spread the coordinates and the octave before the mix.
double lattice(std::uint64_t key, int octave, double x, double y) {
  return unitFromHash(mix(key ^ (std::uint64_t(std::int64_t(x)) * 0xd1b54a32d192ed03ull) ^
                          (std::uint64_t(std::int64_t(y)) * 0x8cb92ba72f3d8dd7ull) ^
                          (std::uint64_t(octave + 1) * 0xaef17502108ef2d9ull)));
}

// C2 fade of value noise: no visible lattice creases.
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

// Value noise: random values on a lattice of spacing `period`, interpolated smoothly. Three
// octaves (period, period/2, period/4, none finer than 3 px), amplitudes halving: band-limited,
// so a box-filtered pixel does not alias.
double valueNoise(double x, double y, double period, std::uint64_t key) {
  double sum = 0, amplitude = 1, total = 0;
  double spacing = std::max(period, 3.0);
  for (int octave = 0; octave < 3 && spacing >= 3.0; ++octave, spacing *= 0.5, amplitude *= 0.5) {
    const double fx = x / spacing, fy = y / spacing;
    const double ix = std::floor(fx), iy = std::floor(fy);
    const double tx = fade(fx - ix), ty = fade(fy - iy);
    const double v00 = lattice(key, octave, ix, iy), v10 = lattice(key, octave, ix + 1, iy);
    const double v01 = lattice(key, octave, ix, iy + 1), v11 = lattice(key, octave, ix + 1, iy + 1);
    const double top = v00 + tx * (v10 - v00), bottom = v01 + tx * (v11 - v01);
    sum += amplitude * (top + ty * (bottom - top));
    total += amplitude;
  }
  // A sum of interpolated uniforms clusters around 1/2; stretch it to use most of [0, 1].
  return std::clamp(0.5 + 1.6 * (sum / total - 0.5), 0.0, 1.0);
}

struct PreparedPlane {
  TexturedPlane plane;
  std::uint64_t key = 0;            // texture seed of this plane
  double centreX = 0, centreY = 0;  // of the extent (rings, ellipse)
  double halfWidth = 0, halfHeight = 0;
  double stripeCos = 1, stripeSin = 0;  // stripe direction, from the seed
  bool background = false;              // empty extent: covers everything

  bool covers(double x, double y) const {
    if (background) return true;
    if (plane.elliptical) {
      const double dx = (x - centreX) / halfWidth, dy = (y - centreY) / halfHeight;
      return dx * dx + dy * dy <= 1;
    }
    return x >= plane.x0 && x < plane.x1 && y >= plane.y0 && y < plane.y1;
  }

  double texture(double x, double y) const {
    const double period = std::max(plane.period, 1e-3);
    switch (plane.texture) {
      case PlaneTexture::Checkerboard: {
        const double half = 0.5 * period;  // period = two squares
        const auto cell = std::int64_t(std::floor(x / half)) + std::int64_t(std::floor(y / half));
        return (cell & 1) ? 0.9 : 0.1;
      }
      case PlaneTexture::Noise: return valueNoise(x, y, period, key);
      case PlaneTexture::Stripes:
        return 0.5 + 0.5 * std::sin(2 * std::numbers::pi * (x * stripeCos + y * stripeSin) / period);
      case PlaneTexture::Rings:
        return 0.5 + 0.5 * std::cos(2 * std::numbers::pi * std::hypot(x - centreX, y - centreY) / period);
    }
    return 0.5;
  }
};

// Linear value of a texture value t under a tint: within about [0.02, 0.9] for tints in [0.25, 1].
float shade(float tint, double t) { return float(tint * (0.1 + 0.8 * t)); }

}  // namespace

LayeredPlanesScene defaultLayeredPlanesScene(int views, int width, std::uint64_t seed, int height) {
  if (height <= 0) height = width;
  LayeredPlanesScene scene;  // laid out for 9x9 views of 256x256, 3x3 samples per pixel
  // Disparities -1.0 .. +1.6 px per view step: the nearest card moves 12.8 px between the
  // outermost views, enough to see occlusion change, small enough for shift-and-add to focus.
  // A cloudy blue background, far.
  scene.planes.push_back(
      {.disparity = -1.0, .texture = PlaneTexture::Noise, .period = 24, .colour = {0.55f, 0.7f, 1.0f}});
  // A warm checkerboard card in the plane of focus (slope 0).
  scene.planes.push_back({.disparity = 0.0,
                          .texture = PlaneTexture::Checkerboard,
                          .period = 16,
                          .colour = {1.0f, 0.85f, 0.6f},
                          .x0 = 32,
                          .y0 = 36,
                          .x1 = 150,
                          .y1 = 140});
  // A green striped ellipse in front of it, overlapping its lower right corner.
  scene.planes.push_back({.disparity = 0.8,
                          .texture = PlaneTexture::Stripes,
                          .period = 10,
                          .colour = {0.5f, 1.0f, 0.55f},
                          .x0 = 112,
                          .y0 = 96,
                          .x1 = 224,
                          .y1 = 200,
                          .elliptical = true});
  // A red card with rings, nearest, overlapping the ellipse's lower left.
  scene.planes.push_back({.disparity = 1.6,
                          .texture = PlaneTexture::Rings,
                          .period = 12,
                          .colour = {1.0f, 0.45f, 0.4f},
                          .x0 = 60,
                          .y0 = 160,
                          .x1 = 152,
                          .y1 = 232});

  // Scale the layout to the size asked for.
  const double scaleX = width / double(scene.ns), scaleY = height / double(scene.nt);
  for (TexturedPlane& plane : scene.planes) {
    plane.x0 *= scaleX, plane.y0 *= scaleY, plane.x1 *= scaleX, plane.y1 *= scaleY;
    plane.period *= std::min(scaleX, scaleY);
  }
  scene.nu = scene.nv = views;
  scene.ns = width;
  scene.nt = height;
  scene.seed = seed;

  // Optics of a plausible plenoptic camera (paper, section 3.2): a lens 100 mm from the
  // microlenses with a 25 mm aperture (image-side f/4, matching f/4 microlenses of 125 um),
  // its aperture divided into nu views; focal length 90 mm puts slope 0 at 0.9 m.
  const double apertureMm = 25;
  scene.optics = Optics{
      .lensStepMm = apertureMm / scene.nu, .spatialStepMm = 0.125, .lensToMicrolensMm = 100, .focalLengthMm = 90.0};
  return scene;
}

LayeredPlanesLightField renderLayeredPlanes(const LayeredPlanesScene& scene, const ProgressCallback& progress) {
  const int nu = std::max(scene.nu, 0), nv = std::max(scene.nv, 0);
  const int ns = std::max(scene.ns, 0), nt = std::max(scene.nt, 0);
  const int samples = std::max(scene.supersampling, 1);
  LayeredPlanesLightField result{LightField({.nu = nu, .nv = nv, .ns = ns, .nt = nt, .channels = 3}), Image(ns, nt, 1)};

  // Nearest first (largest disparity), so the first plane that covers a point is the one seen.
  std::vector<PreparedPlane> planes;
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    const TexturedPlane& plane = scene.planes[i];
    PreparedPlane prepared{.plane = plane, .key = hash(scene.seed, i + 1)};
    prepared.background = !(plane.x1 > plane.x0 && plane.y1 > plane.y0);
    prepared.centreX = prepared.background ? 0.5 * ns : 0.5 * (plane.x0 + plane.x1);
    prepared.centreY = prepared.background ? 0.5 * nt : 0.5 * (plane.y0 + plane.y1);
    prepared.halfWidth = 0.5 * (plane.x1 - plane.x0);
    prepared.halfHeight = 0.5 * (plane.y1 - plane.y0);
    const double angle = std::numbers::pi * unitFromHash(hash(prepared.key, 0xa9));
    prepared.stripeCos = std::cos(angle), prepared.stripeSin = std::sin(angle);
    planes.push_back(prepared);
  }
  std::stable_sort(planes.begin(), planes.end(), [](const PreparedPlane& a, const PreparedPlane& b) {
    return a.plane.disparity > b.plane.disparity;
  });

  // The plane seen at centre-view point (x, y) from view position (u, v) (view steps from the
  // centre): plane of disparity d shows its point (x + u d, y + v d) (layered_planes.hpp).
  auto seen = [&](double x, double y, double u, double v) -> const PreparedPlane* {
    for (const PreparedPlane& plane : planes) {
      const double d = plane.plane.disparity;
      if (plane.covers(x + u * d, y + v * d)) return &plane;
    }
    return nullptr;
  };

  // One row t of view (u, v): each pixel the mean of samples x samples stratum centres (a box
  // filter over its area, as a sensor pixel integrates). Rows of all views are independent.
  LightField& lightField = result.lightField;
  auto renderRow = [&](int u, int v, int t) {
    const double uc = lightField.uFromCentre(u), vc = lightField.vFromCentre(v);
    float* rows[3];
    for (int c = 0; c < 3; ++c) rows[c] = lightField.plane(u, v, c) + std::size_t(t) * ns;
    const double inverseCount = 1.0 / (samples * samples);
    for (int s = 0; s < ns; ++s) {
      double sum[3] = {0, 0, 0};
      for (int j = 0; j < samples; ++j) {
        const double y = t + (j + 0.5) / samples;
        for (int i = 0; i < samples; ++i) {
          const double x = s + (i + 0.5) / samples;
          const PreparedPlane* plane = seen(x, y, uc, vc);
          if (!plane) continue;  // nothing there: black
          const double d = plane->plane.disparity;
          const double value = plane->texture(x + uc * d, y + vc * d);
          for (int c = 0; c < 3; ++c) sum[c] += shade(plane->plane.colour[c], value);
        }
      }
      for (int c = 0; c < 3; ++c) rows[c][s] = float(sum[c] * inverseCount);
    }
  };

  // Schedule: every (view, row) is a task; 32 rows make a task worth its overhead.
  const std::size_t rowsTotal = std::size_t(nu) * nv * nt;
  parallelFor(
      0, rowsTotal, 32,
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t index = begin; index < end; ++index) {
          const int t = int(index % nt), view = int(index / nt);
          renderRow(view % nu, view / nu, t);
        }
      },
      progress);

  // Ground truth: the plane seen through the aperture's centre at each pixel's centre; NaN
  // where no plane covers it.
  for (int t = 0; t < nt; ++t)
    for (int s = 0; s < ns; ++s) {
      const PreparedPlane* plane = seen(s + 0.5, t + 0.5, 0, 0);
      result.disparity.at(s, t, 0) = plane ? float(plane->plane.disparity) : std::numeric_limits<float>::quiet_NaN();
    }

  LightFieldMetadata& metadata = lightField.metadata;
  // Optics left at zero mean "unknown": slopeFromAlpha would divide by zero.
  if (scene.optics.lensStepMm > 0 && scene.optics.spatialStepMm > 0) metadata.optics = scene.optics;
  if (!scene.planes.empty()) {
    auto [lowest, highest] =
        std::minmax_element(scene.planes.begin(), scene.planes.end(),
                            [](const TexturedPlane& a, const TexturedPlane& b) { return a.disparity < b.disparity; });
    metadata.disparityMin = lowest->disparity;
    metadata.disparityMax = highest->disparity;
  }
  metadata.source = "lfcam layered planes, seed " + std::to_string(scene.seed);
  return result;
}

}  // namespace lfcam
