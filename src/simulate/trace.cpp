// The ray tracer: sensor pixel -> microlens -> main lens -> scene (simulate.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/parallel.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "simulate/tracing.hpp"

namespace lfcam {

namespace simulate_detail {

PreparedScene::PreparedScene(const Scene& scene, const CameraModel& camera)
    : background(scene.background),
      focusDistance(camera.mainLens.focusDistanceMm),
      imageDistance(camera.mainLens.imageDistanceMm()) {
  for (const Plane& plane : scene.planes) {
    PreparedPlane p;
    p.plane = &plane;
    p.centre = {plane.centreMm[0], plane.centreMm[1], plane.centreMm[2]};
    const double tx = plane.tiltXDeg * M_PI / 180, ty = plane.tiltYDeg * M_PI / 180;
    // Right axis turned about the vertical (its right side away from the camera: +z), down axis
    // turned about the horizontal (its top away), then made orthogonal to the right axis.
    Vec3 a{std::cos(ty), 0, std::sin(ty)};
    Vec3 b{0, std::cos(tx), -std::sin(tx)};
    b = normalize(b - a * dot(a, b));
    p.right = a;
    p.down = b;
    p.normal = cross(a, b);
    p.halfWidth = 0.5 * plane.widthMm;
    p.halfHeight = 0.5 * plane.heightMm;
    planes.push_back(p);
  }
  for (const PointLight& light : scene.lights) lights.push_back(light);
}

Hit PreparedScene::trace(const Vec3& origin, const Vec3& direction, int bounces) const {
  Hit best;
  best.t = std::numeric_limits<double>::infinity();
  const PreparedPlane* bestPlane = nullptr;
  double bestX = 0, bestY = 0;
  for (const PreparedPlane& p : planes) {
    const double denominator = dot(p.normal, direction);
    if (std::abs(denominator) < 1e-12) continue;
    const double t = dot(p.normal, p.centre - origin) / denominator;
    if (!(t > 0) || t >= best.t) continue;
    const Vec3 d = origin + direction * t - p.centre;
    const double x = dot(p.right, d), y = dot(p.down, d);
    if (std::abs(x) > p.halfWidth || std::abs(y) > p.halfHeight) continue;
    best.t = t;
    bestPlane = &p;
    bestX = x;
    bestY = y;
  }
  const PointLight* bestLight = nullptr;
  for (const PointLight& light : lights) {
    if (std::abs(direction.z) < 1e-12) continue;
    const double t = (light.positionMm[2] - origin.z) / direction.z;
    if (!(t > 0) || t >= best.t) continue;
    const double dx = origin.x + direction.x * t - light.positionMm[0];
    const double dy = origin.y + direction.y * t - light.positionMm[1];
    if (dx * dx + dy * dy > light.radiusMm * light.radiusMm) continue;
    best.t = t;
    bestLight = &light;
  }
  if (bestLight) {
    best.radiance = bestLight->radiance;
    best.depth = bestLight->positionMm[2];
  } else if (bestPlane) {
    const Plane& plane = *bestPlane->plane;
    best.radiance = plane.texture.evaluate(bestX + bestPlane->halfWidth, bestY + bestPlane->halfHeight, plane.widthMm,
                                           plane.heightMm);
    best.depth = origin.z + direction.z * best.t;
    if (plane.reflectance > 0 && bounces > 0) {
      // Schlick: F = F0 + (1 - F0) (1 - cos i)^5; the mirrored ray leaves just off the plane.
      const Vec3 unit = normalize(direction);
      const double cosine = std::min(std::abs(dot(unit, bestPlane->normal)), 1.0);
      const double fresnel = plane.reflectance + (1 - plane.reflectance) * std::pow(1 - cosine, 5);
      const Vec3 mirrored = unit - bestPlane->normal * (2 * dot(unit, bestPlane->normal));
      const Vec3 hit = origin + direction * best.t;
      const Rgb seen = trace(hit + mirrored * 1e-6, mirrored, bounces - 1).radiance;
      for (int c = 0; c < 3; ++c) best.radiance[c] = float((1 - fresnel) * best.radiance[c] + fresnel * seen[c]);
    }
  } else {
    best.radiance = background;
    best.depth = std::numeric_limits<double>::infinity();
  }
  return best;
}

Hit PreparedScene::traceThroughLens(double lensX, double lensY, double imageX, double imageY) const {
  // The object-side ray leaves the lens point towards the conjugate of the image-side point
  // (imageX, imageY) at distance F: (-x d / F, -y d / F, d).
  const double k = -focusDistance / imageDistance;
  const Vec3 origin{lensX, lensY, 0};
  const Vec3 target{imageX * k, imageY * k, focusDistance};
  return trace(origin, target - origin);
}

}  // namespace simulate_detail

namespace {

using simulate_detail::Hit;
using simulate_detail::PreparedScene;

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// PCG32 (O'Neill): small, fast, and cheap to seed per pixel.
class Pcg32 {
 public:
  explicit Pcg32(std::uint64_t seed) : state_(0) {
    next();
    state_ += seed;
    next();
  }
  std::uint32_t next() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + 1442695040888963407ull;
    const std::uint32_t shifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
    const std::uint32_t rot = std::uint32_t(old >> 59u);
    return (shifted >> rot) | (shifted << ((32 - rot) & 31));
  }
  double uniform() { return next() * 0x1.0p-32; }

 private:
  std::uint64_t state_;
};

float channelValue(const Rgb& radiance, int channel) {
  if (channel >= 0) return radiance[channel];
  return 0.2126f * radiance[0] + 0.7152f * radiance[1] + 0.0722f * radiance[2];
}

// Shirley-Chiu concentric map of the unit square onto the unit disc: keeps strata compact.
void concentricDisc(double a, double b, double& x, double& y) {
  const double sx = 2 * a - 1, sy = 2 * b - 1;
  if (sx == 0 && sy == 0) {
    x = y = 0;
    return;
  }
  double r, phi;
  if (std::abs(sx) > std::abs(sy)) {
    r = sx;
    phi = M_PI / 4 * (sy / sx);
  } else {
    r = sy;
    phi = M_PI / 2 - M_PI / 4 * (sx / sy);
  }
  x = r * std::cos(phi);
  y = r * std::sin(phi);
}

// Everything about the optics the per-pixel kernel needs, in mm.
struct TraceOptics {
  double F = 0, apertureRadius = 0, pixel = 0, halfW = 0, halfH = 0;
  bool lightField = false;
  // Microlens array.
  double beta = 0, pitch = 0, rowPitch = 0, cosR = 1, sinR = 0, offX = 0, offY = 0;
  bool hex = false;
  const MicrolensArray* array = nullptr;  // each microlens's focal length (lens types)
  int columns = 0, rows = 0;
  double imageScale = 1;   // microlens centre -> image centre on the sensor
  double activeHalfA = 0;  // half extents of the sampled rectangle of one microlens (local frame)
  double activeHalfB = 0;
  double activeHalfSide = 0;  // hexagon: half of the flat-to-flat width (scaled by fill factor)
  double cellArea = 0;        // of the sampled cell (rectangle or hexagon), mm^2
  double reach = 0;           // how far from its image centre a microlens can deliver light
  int searchI = 1, searchJ = 1;

  // A point of the hexagonal cell (flats at a = +-activeHalfSide) from a point (ca, cb) of the unit
  // square, uniformly: the hexagon is three rhombi, each spanned by two vertices 120 degrees apart.
  // Every sample lands inside, where sampling the bounding box and rejecting the corners made the
  // flat top of each hexagonal microlens image as noisy as the count of accepted samples.
  void hexagonPoint(double ca, double cb, double& a, double& b) const {
    const double h = activeHalfSide, k = activeHalfB;  // k: centre to the vertex on the b axis
    static constexpr double kVertexA[3] = {0, 1, -1}, kVertexB[3] = {1, -0.5, -0.5};
    const int r = std::min(2, int(ca * 3));
    const double s = ca * 3 - r;
    const int q = (r + 1) % 3;
    a = (s * kVertexA[r] + cb * kVertexA[q]) * h;
    b = (s * kVertexB[r] + cb * kVertexB[q]) * k;
  }

  void lensCentre(int i, int j, double& x, double& y) const {
    double a = (i - 0.5 * (columns - 1)) * pitch;
    if (hex && (j & 1)) a += 0.5 * pitch;
    const double b = (j - 0.5 * (rows - 1)) * rowPitch;
    x = offX + cosR * a - sinR * b;
    y = offY + sinR * a + cosR * b;
  }
};

TraceOptics prepareOptics(const CameraModel& camera) {
  TraceOptics o;
  o.F = camera.mainLens.imageDistanceMm();
  o.apertureRadius = 0.5 * camera.mainLens.apertureDiameterMm();
  o.pixel = camera.sensor.pixelPitchMm;
  o.halfW = 0.5 * camera.sensor.width * o.pixel;
  o.halfH = 0.5 * camera.sensor.height * o.pixel;
  if (!camera.microlenses) return o;
  const MicrolensArray& m = *camera.microlenses;
  o.lightField = true;
  o.beta = m.separationMm();
  o.array = &m;
  o.pitch = m.pitchMm;
  o.rowPitch = m.rowPitchMm();
  o.cosR = std::cos(m.rotationDeg * M_PI / 180);
  o.sinR = std::sin(m.rotationDeg * M_PI / 180);
  o.offX = m.offsetMm[0];
  o.offY = m.offsetMm[1];
  o.hex = m.packing == Packing::Hexagonal;
  const auto counts = camera.microlensCounts();
  o.columns = counts[0];
  o.rows = counts[1];
  o.imageScale = 1 + o.beta / o.F;
  const double shrink = std::sqrt(m.fillFactor);
  if (o.hex) {
    o.activeHalfSide = 0.5 * o.pitch * shrink;
    o.activeHalfA = o.activeHalfSide;
    o.activeHalfB = o.pitch / std::sqrt(3.0) * shrink;
    o.cellArea = 2 * std::sqrt(3.0) * o.activeHalfSide * o.activeHalfSide;
  } else {
    o.activeHalfA = o.activeHalfB = 0.5 * o.pitch * shrink;
    o.cellArea = 4 * o.activeHalfA * o.activeHalfB;
  }
  // x - imageCentre = delta (1 - beta/fm + beta/F) - beta u / F, delta in the active cell,
  // u in the aperture; plus the pixel's half diagonal.
  double k = 0;
  for (int type = 0; type < m.lensTypes(); ++type) {
    const double fm = m.typeFocalLengthsMm.empty() ? m.focalLengthMm : m.typeFocalLengthsMm[std::size_t(type)];
    k = std::max(k, std::abs(1 - o.beta / fm + o.beta / o.F));
  }
  o.reach = std::hypot(o.activeHalfA, o.activeHalfB) * k + o.beta / o.F * o.apertureRadius + o.pixel * 0.7072;
  o.searchI = int(std::ceil(o.reach / (o.pitch * o.imageScale))) + 1;
  o.searchJ = int(std::ceil(o.reach / (o.rowPitch * o.imageScale))) + 1;
  return o;
}

constexpr int kMaxStrata = 32;  // up to 1024 samples per pixel

// The irradiance (per unit radiance) of one pixel of channel `channel`. `rays` counts traced rays.
double pixelIrradiance(const TraceOptics& o, const PreparedScene& scene, int px, int py, int n, int channel,
                       std::uint64_t seed, std::uint64_t& rays) {
  Pcg32 rng(mix64(seed ^ mix64((std::uint64_t(py) << 32) | std::uint32_t(px))));
  const int count = n * n;
  // Lens strata paired with pixel strata by a random permutation (a Latin-hypercube-like pairing
  // of two 2D stratifications, as pbrt's stratified sampler does).
  int permutation[kMaxStrata * kMaxStrata];
  std::iota(permutation, permutation + count, 0);
  for (int k = count - 1; k > 0; --k) std::swap(permutation[k], permutation[rng.next() % (k + 1)]);
  const double x0 = px * o.pixel - o.halfW, y0 = py * o.pixel - o.halfH;
  const double inv = 1.0 / n, r2 = o.apertureRadius * o.apertureRadius, F2 = o.F * o.F;

  if (!o.lightField) {
    // Conventional: E = (1 / F^2) * integral over the aperture of L cos^4.
    double sum = 0;
    for (int k = 0; k < count; ++k) {
      const double x = x0 + ((k % n) + rng.uniform()) * inv * o.pixel;
      const double y = y0 + ((k / n) + rng.uniform()) * inv * o.pixel;
      const int l = permutation[k];
      double dx, dy;
      concentricDisc(((l % n) + rng.uniform()) * inv, ((l / n) + rng.uniform()) * inv, dx, dy);
      const double ux = dx * o.apertureRadius, uy = dy * o.apertureRadius;
      const double d2 = (ux - x) * (ux - x) + (uy - y) * (uy - y);
      const double c2 = F2 / (F2 + d2);
      const Hit hit = scene.traceThroughLens(ux, uy, x, y);
      sum += channelValue(hit.radiance, channel) * c2 * c2;
    }
    rays += count;
    return sum / count * (M_PI * r2) / F2;
  }

  // Light field: find the microlenses whose image can reach this pixel.
  const double cx = x0 + 0.5 * o.pixel, cy = y0 + 0.5 * o.pixel;
  const double qx = cx / o.imageScale - o.offX, qy = cy / o.imageScale - o.offY;
  const double qa = o.cosR * qx + o.sinR * qy, qb = -o.sinR * qx + o.cosR * qy;
  const int j0 = int(std::lround(qb / o.rowPitch + 0.5 * (o.rows - 1)));
  double total = 0;
  for (int j = j0 - o.searchJ; j <= j0 + o.searchJ; ++j) {
    if (j < 0 || j >= o.rows) continue;
    const double shift = (o.hex && (j & 1)) ? 0.5 : 0.0;
    const int i0 = int(std::lround(qa / o.pitch + 0.5 * (o.columns - 1) - shift));
    for (int i = i0 - o.searchI; i <= i0 + o.searchI; ++i) {
      if (i < 0 || i >= o.columns) continue;
      double lx, ly;
      o.lensCentre(i, j, lx, ly);
      const double ex = lx * o.imageScale - cx, ey = ly * o.imageScale - cy;
      if (ex * ex + ey * ey > o.reach * o.reach) continue;
      // E = (1 / beta^2) * integral over the microlens of L cos^4 (paraxial inside the camera).
      const double fm = o.array->focalLengthOf(i, j);
      double sum = 0;
      for (int k = 0; k < count; ++k) {
        const double x = x0 + ((k % n) + rng.uniform()) * inv * o.pixel;
        const double y = y0 + ((k / n) + rng.uniform()) * inv * o.pixel;
        const int l = permutation[k];
        const double ca = ((l % n) + rng.uniform()) * inv, cb = ((l / n) + rng.uniform()) * inv;
        double a, b;
        if (o.hex)
          o.hexagonPoint(ca, cb, a, b);
        else {
          a = (ca * 2 - 1) * o.activeHalfA;
          b = (cb * 2 - 1) * o.activeHalfB;
        }
        const double mx = lx + o.cosR * a - o.sinR * b, my = ly + o.sinR * a + o.cosR * b;
        // Sensor -> microlens (slope in), thin microlens, -> main lens at distance F.
        const double sx = (mx - x) / o.beta - (mx - lx) / fm;
        const double sy = (my - y) / o.beta - (my - ly) / fm;
        const double ux = mx + o.F * sx, uy = my + o.F * sy;
        if (ux * ux + uy * uy > r2) continue;  // stopped by the main lens's aperture
        const double d2 = (ux - mx) * (ux - mx) + (uy - my) * (uy - my);
        const double c2 = F2 / (F2 + d2);
        const Hit hit = scene.traceThroughLens(ux, uy, mx, my);
        sum += channelValue(hit.radiance, channel) * c2 * c2;
        ++rays;
      }
      total += sum / count * o.cellArea / (o.beta * o.beta);
    }
  }
  return total;
}

}  // namespace

SensorCapture simulateCapture(const Scene& scene, const CameraModel& camera, const SimulationOptions& options,
                              const ProgressCallback& progress) {
  const PreparedScene prepared(scene, camera);
  const TraceOptics optics = prepareOptics(camera);
  const int n =
      std::clamp(int(std::ceil(std::sqrt(double(std::max(1, options.samplesPerPixel))) - 1e-9)), 1, kMaxStrata);
  const int width = camera.sensor.width, height = camera.sensor.height;
  SensorCapture capture;
  capture.irradiance = Image(width, height, 1);
  std::vector<std::uint64_t> rowRays(height, 0);
  const std::uint64_t seed = mix64(camera.sensor.seed ^ 0x7261797361ull);
  // Schedule: bands of rows, each band's rows spread over the threads; progress between bands.
  const int band = std::max(16, height / 50);
  for (int start = 0; start < height; start += band) {
    const int stop = std::min(height, start + band);
    parallelFor(std::size_t(start), std::size_t(stop), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t y = begin; y < end; ++y) {
        float* row = capture.irradiance.row(int(y), 0);
        std::uint64_t rays = 0;
        // Raw pixel (x, y) is sensor pixel (width - 1 - x, height - 1 - y): the camera's readout
        // turns the sensor image by 180 degrees (camera_model.hpp); the colour filter is the raw's.
        for (int x = 0; x < width; ++x)
          row[x] = float(pixelIrradiance(optics, prepared, width - 1 - x, height - 1 - int(y), n,
                                         colorFilterChannel(camera.sensor.colorFilter, x, int(y)), seed, rays));
        rowRays[y] = rays;
      }
    });
    if (progress) progress(double(stop) / height);
  }
  capture.rays = std::accumulate(rowRays.begin(), rowRays.end(), std::uint64_t(0));
  capture.raw = applySensor(capture.irradiance, camera.sensor);
  return capture;
}

namespace {

// Poisson variates: multiplication (Knuth) below a mean of 10, above it the transformed
// rejection with squeeze of Hoermann (1993, "PTRS"), exact, ~1.1 uniforms per variate.
double poisson(Pcg32& rng, double mean) {
  if (mean < 10) {
    const double limit = std::exp(-mean);
    double product = rng.uniform();
    int k = 0;
    while (product > limit) {
      product *= rng.uniform();
      ++k;
    }
    return k;
  }
  const double root = std::sqrt(mean);
  const double b = 0.931 + 2.53 * root, a = -0.059 + 0.02483 * b;
  const double inverseAlpha = 1.1239 + 1.1328 / (b - 3.4), vr = 0.9277 - 3.6224 / (b - 2);
  for (;;) {
    const double u = rng.uniform() - 0.5, v = rng.uniform(), us = 0.5 - std::abs(u);
    const double k = std::floor((2 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= vr) return k;
    if (k < 0 || (us < 0.013 && v > us)) continue;
    if (std::log(v) + std::log(inverseAlpha) - std::log(a / (us * us) + b) <=
        -mean + k * std::log(mean) - std::lgamma(k + 1))
      return k;
  }
}

// Standard normal variates (Marsaglia's polar method), one pair at a time.
class Gaussian {
 public:
  double operator()(Pcg32& rng) {
    if (hasSpare_) {
      hasSpare_ = false;
      return spare_;
    }
    double x, y, r;
    do {
      x = 2 * rng.uniform() - 1;
      y = 2 * rng.uniform() - 1;
      r = x * x + y * y;
    } while (r >= 1 || r == 0);
    const double f = std::sqrt(-2 * std::log(r) / r);
    spare_ = y * f;
    hasSpare_ = true;
    return x * f;
  }

 private:
  double spare_ = 0;
  bool hasSpare_ = false;
};

}  // namespace

Image applySensor(const Image& irradiance, const Sensor& sensor) {
  Image raw(irradiance.width(), irradiance.height(), 1);
  const double scale = sensor.exposure * sensor.electronsPerIrradiance, gain = sensor.gain();
  const double maxCode = sensor.whiteLevel;
  parallelFor(0, std::size_t(irradiance.height()), 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y) {
      // One generator per row, seeded by (seed, row): independent of the threads.
      Pcg32 rng(mix64(sensor.seed ^ mix64(0x6e6f697365ull + y)));
      Gaussian gaussian;
      const float* in = irradiance.row(int(y), 0);
      float* out = raw.row(int(y), 0);
      for (int x = 0; x < irradiance.width(); ++x) {
        const double mean = std::max(0.0, double(in[x]) * scale);
        double electrons = mean;
        if (sensor.noise && mean > 0) electrons = poisson(rng, mean);
        electrons = std::min(electrons, sensor.fullWellElectrons);
        if (sensor.noise && sensor.readNoiseElectrons > 0) electrons += sensor.readNoiseElectrons * gaussian(rng);
        double code = std::round(sensor.blackLevel + electrons * gain);
        if (sensor.hotPixelFraction > 0 &&
            double(mix64(sensor.seed ^ mix64(0x686f74ull + (std::uint64_t(y) << 32) + std::uint64_t(x))) >> 11) *
                    0x1.0p-53 <
                sensor.hotPixelFraction)
          code = maxCode;
        out[x] = float(std::clamp(code, 0.0, maxCode));
      }
    }
  });
  return raw;
}

}  // namespace lfcam
