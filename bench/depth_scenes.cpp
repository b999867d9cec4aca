// The depth estimator's development scenes (depth_scenes.hpp).
#include "depth_scenes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include "lfcam/edof/depth.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "lfcam/synth/layered_planes.hpp"

namespace lfcam::bench {
namespace {

// The people test's small camera, with size x size microlenses 9 pixels apart, focused at 5 m: its
// f/2.8 main lens before f/4 microlenses makes microlens images 12.5 pixels across, 12 x 12 views.
CameraModel camera(int size) {
  CameraModel model = CameraModel::paperPrototype(9 * size, 9 * size);
  model.microlenses->pitchMm = 9 * model.sensor.pixelPitchMm;
  model.microlenses->focalLengthMm = 4 * model.microlenses->pitchMm;
  model.mainLens.focusDistanceMm = 5000;
  return model;
}

// Half the field of view (mm) at distance z.
double halfField(const CameraModel& model, double z) {
  return 0.5 * model.sensor.widthMm() * z / model.mainLens.imageDistanceMm();
}

Texture noise(double periodMm, Rgb dark, Rgb light, std::uint64_t seed) {
  Texture texture;
  texture.kind = TextureKind::Noise;
  texture.periodMm = periodMm;
  texture.dark = dark;
  texture.light = light;
  texture.seed = seed;
  return texture;
}

Plane plane(std::string name, std::array<double, 3> centre, double width, double height, Texture texture) {
  Plane p;
  p.name = std::move(name);
  p.centreMm = centre;
  p.widthMm = width;
  p.heightMm = height;
  p.texture = std::move(texture);
  return p;
}

// A textured backdrop filling the view at `z`: no ray escapes to a textureless background.
Plane backdrop(const CameraModel& model, double z, std::uint64_t seed) {
  const double h = halfField(model, z);
  return plane("backdrop", {0, 0, z}, 2.6 * h, 2.6 * h, noise(h / 8, {0.1f, 0.2f, 0.25f}, {0.7f, 0.75f, 0.6f}, seed));
}

// Sensor-like noise per sample, sigma^2 = 0.02^2 + 0.002 x value (2-4 % of the signal, the people
// test's model; a Lytro's decoded views are as noisy).
void addNoise(LightField& lightField, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (float& sample : lightField.samples())
    sample += std::sqrt(0.0004f + 0.002f * std::max(sample, 0.0f)) * normal(generator);
}

DepthScene withRange(std::string name, LightField lightField, Image disparity) {
  double low = INFINITY, high = -INFINITY;
  for (float d : disparity.pixels())
    if (std::isfinite(d)) low = std::min(low, double(d)), high = std::max(high, double(d));
  return {std::move(name), std::move(lightField), std::move(disparity), low - 0.25, high + 0.25};
}

DepthScene simulated(std::string name, const Scene& scene, const CameraModel& model, bool noisy = false) {
  auto lightField = idealLightFieldBoxFiltered(scene, model, 2);
  if (!lightField) throw std::runtime_error(name + ": the simulator failed");
  // The truth of the view lfcam depth maps: with this camera's 12 x 12 views, half a view step off
  // the axis (simulate.hpp).
  auto depth = idealDepthOfView(scene, model, (lightField->nu() - 1) / 2, (lightField->nv() - 1) / 2);
  if (!depth) throw std::runtime_error(name + ": the simulator failed");
  const Optics& optics = *lightField->metadata.optics;
  Image disparity(depth->width(), depth->height(), 1);
  for (int y = 0; y < depth->height(); ++y)
    for (int x = 0; x < depth->width(); ++x)
      disparity.at(x, y, 0) = float(disparityFromDistance(optics, depth->at(x, y, 0)).value_or(NAN));
  if (noisy) addNoise(*lightField, 11);
  return withRange(std::move(name), std::move(*lightField), std::move(disparity));
}

// `name` with a gloss on every plane but the first (the backdrop): their radiance brightens
// linearly across the aperture, by -gain to +gain from one corner of the views to the other (a
// sheen's highlight seen from one side; an imperfect devignetting does the same to whole views).
// The light field is linear in radiance: the scene with those planes black, plus their light
// alone (the backdrop black, still occluding) times each view's gain.
DepthScene glossy(std::string name, const Scene& scene, const CameraModel& model, double gain) {
  Texture black;
  black.light = {0, 0, 0};
  Scene rest = scene, alone = scene;
  alone.planes.front().texture = black;
  for (std::size_t i = 1; i < rest.planes.size(); ++i) rest.planes[i].texture = black;
  DepthScene result = simulated(std::move(name), rest, model);
  const LightField lit = simulated("", alone, model).lightField;
  LightField& lightField = result.lightField;
  const double cu = 0.5 * (lightField.nu() - 1), cv = 0.5 * (lightField.nv() - 1);
  for (int v = 0; v < lightField.nv(); ++v)
    for (int u = 0; u < lightField.nu(); ++u) {
      const float g = float(1 + gain * 0.5 * ((u - cu) / cu + (v - cv) / cv));
      for (int c = 0; c < lightField.channels(); ++c) {
        float* out = lightField.plane(u, v, c);
        const float* in = lit.plane(u, v, c);
        for (std::size_t i = 0; i < lightField.shape().viewPixels(); ++i) out[i] += g * in[i];
      }
    }
  return result;
}

// `texture` on a plane of width x height (mm) lit unevenly: its brightness falls linearly from 1 at
// the top-left corner to `far` at the bottom-right one. An image texture fine enough for the
// noise's smallest features (a fifth of their size).
Texture unevenlyLit(const Texture& texture, double width, double height, double far) {
  const double cell = texture.periodMm / 2.7 / 5;
  const int w = std::min(int(std::ceil(width / cell)), 4096), h = std::min(int(std::ceil(height / cell)), 4096);
  auto image = std::make_shared<Image>(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double px = (x + 0.5) / w * width, py = (y + 0.5) / h * height;
      const double light = 1 - (1 - far) * 0.5 * (px / width + py / height);
      const Rgb base = texture.evaluate(px, py, width, height);
      for (int c = 0; c < 3; ++c) image->at(x, y, c) = float(light * base[c]);
    }
  Texture out;
  out.kind = TextureKind::Image;
  out.image = std::move(image);
  return out;
}

// Half an elliptic cylinder with a vertical axis, bulging towards the camera: `facets` planes
// spanning +-endDeg around the axis at axisZ, `across` wide on either side and `deep` towards the
// camera, `height` tall.
void addFacetedColumn(Scene& scene, double across, double deep, double axisZ, double endDeg, int facets, double height,
                      const Texture& texture) {
  const double end = endDeg * M_PI / 180;
  const auto point = [&](double angle) {
    return std::array<double, 2>{across * std::sin(angle), axisZ - deep * std::cos(angle)};
  };
  for (int i = 0; i < facets; ++i) {
    const auto a = point(-end + 2 * end * i / facets), b = point(-end + 2 * end * (i + 1) / facets);
    Plane facet = plane("facet", {(a[0] + b[0]) / 2, 0, (a[1] + b[1]) / 2}, 1.02 * std::hypot(b[0] - a[0], b[1] - a[1]),
                        height, texture);
    facet.tiltYDeg = std::atan2(b[1] - a[1], b[0] - a[0]) * 180 / M_PI;  // its right side away right of the axis
    scene.planes.push_back(facet);
  }
}

Scene emptyScene(const CameraModel& model) {
  Scene scene;
  scene.camera = model;
  return scene;
}

// Texture of 4 % contrast: a card before a wall.
Scene weakTexture(const CameraModel& model) {
  const double d = model.mainLens.focusDistanceMm;
  Scene scene = emptyScene(model);
  const double far = 1.6 * d, hf = halfField(model, far);
  scene.planes.push_back(
      plane("far", {0, 0, far}, 2.6 * hf, 2.6 * hf, noise(hf / 10, {0.48f, 0.48f, 0.48f}, {0.52f, 0.52f, 0.52f}, 16)));
  const double z = 0.9 * d, h = halfField(model, z);
  scene.planes.push_back(
      plane("near", {0.2 * h, 0, z}, 0.8 * h, 1.2 * h, noise(h / 8, {0.58f, 0.5f, 0.45f}, {0.62f, 0.54f, 0.49f}, 17)));
  return scene;
}

}  // namespace

DepthScene coarseLayeredPlanes(int size) {
  LayeredPlanesScene coarse = defaultLayeredPlanesScene(9, size);
  for (TexturedPlane& plane : coarse.planes) plane.period *= 4;
  auto planes = renderLayeredPlanes(coarse);
  return withRange("synth layered planes, coarse texture", std::move(planes.lightField), std::move(planes.disparity));
}

DepthScene weakTextureGlossy(int size) {
  const CameraModel model = camera(size);
  return glossy("weak texture, glossy", weakTexture(model), model, 0.1);
}

DepthScene narrowNearParts(int size) {
  const CameraModel model = camera(size);
  const double d = model.mainLens.focusDistanceMm;
  Scene scene = emptyScene(model);
  scene.planes.push_back(backdrop(model, 2.2 * d, 31));
  const double z = 0.55 * d, h = halfField(model, z), pixel = 2 * h / size;
  const Texture marble = noise(h / 24, {0.45f, 0.4f, 0.35f}, {0.95f, 0.9f, 0.85f}, 32);
  const double widths[] = {3, 4, 6, 8};
  for (int i = 0; i < 4; ++i)
    scene.planes.push_back(plane("finger", {(-0.5 + 0.25 * i) * h, -0.2 * h, z}, widths[i] * pixel, 1.1 * h, marble));
  scene.planes.push_back(plane("arm", {-0.1 * h, 0.55 * h, 1.05 * z}, 1.5 * h, 5 * pixel, marble));
  return simulated("narrow near parts", scene, model);
}

std::vector<DepthScene> developmentScenes(int size) {
  std::vector<DepthScene> scenes;
  {
    auto planes = renderLayeredPlanes(defaultLayeredPlanesScene(9, size));
    scenes.push_back(withRange("synth layered planes", std::move(planes.lightField), std::move(planes.disparity)));
  }
  scenes.push_back(coarseLayeredPlanes(size));
  const CameraModel model = camera(size);
  const double d = model.mainLens.focusDistanceMm;
  const Scene people = *builtinScene("people", model);
  scenes.push_back(simulated("people", people, model));
  scenes.push_back(simulated("people, Lytro-like noise", people, model, true));
  {  // A floor at a grazing angle (80 degrees) before a wall.
    Scene scene = emptyScene(model);
    scene.planes.push_back(backdrop(model, 2.2 * d, 3));
    const double h = halfField(model, 1.3 * d);
    Plane floor =
        plane("floor", {0, 0.5 * h, 1.3 * d}, 3 * h, 0.6 * d, noise(h / 10, {0.3f, 0.2f, 0.1f}, {0.8f, 0.7f, 0.5f}, 5));
    floor.tiltXDeg = 80;
    scene.planes.push_back(floor);
    scenes.push_back(simulated("slanted floor", scene, model));
    scenes.push_back(glossy("slanted floor, glossy", scene, model, 0.1));
  }
  {  // A floor and a wall beside the camera, running from near it to a backdrop: disparity that
     // changes by 0.04 px per pixel at 128 px per view (the slanted floor above: 0.004; HCI
     // antinous's floor and the sides of its statue: 0.02 to 0.08 at 512 px). Also with dim texture
     // of 3 % contrast, as the weak texture's 4 %, before the backdrop's strong texture.
    Scene scene = emptyScene(model);
    scene.planes.push_back(backdrop(model, 2.2 * d, 21));
    const double offset = 0.56 * halfField(model, d);  // from the camera's axis
    Plane floor = plane("floor", {0, offset, 1.4 * d}, 2 * d, 1.7 * d,
                        noise(offset / 8, {0.35f, 0.25f, 0.15f}, {0.85f, 0.75f, 0.6f}, 22));
    floor.tiltXDeg = 90;
    Plane wall = plane("wall", {offset, 0, 1.4 * d}, 1.7 * d, 2 * d,
                       noise(offset / 8, {0.15f, 0.3f, 0.35f}, {0.6f, 0.8f, 0.85f}, 23));
    wall.tiltYDeg = 90;
    scene.planes.push_back(floor);
    scene.planes.push_back(wall);
    scenes.push_back(simulated("steep slants", scene, model));
    scene.planes[1].texture = noise(offset / 8, {0.28f, 0.25f, 0.2f}, {0.3f, 0.27f, 0.22f}, 22);
    scene.planes[2].texture = noise(offset / 8, {0.28f, 0.28f, 0.3f}, {0.3f, 0.3f, 0.32f}, 23);
    scenes.push_back(simulated("steep slants, weak texture", scene, model));
    // The same, unevenly lit and glossy: the light falling off across each plane while their sheen
    // brightens across the aperture (HCI antinous's floor: 3 % across the views, under a spot).
    for (std::size_t i : {1, 2}) {
      Plane& p = scene.planes[i];
      p.texture = unevenlyLit(p.texture, p.widthMm, p.heightMm, 0.4);
    }
    scenes.push_back(glossy("steep slants, weak, unevenly lit, glossy", scene, model, 0.03));
  }
  {  // Cards standing on a floor as steep as the one above: occlusion edges whose background is
     // slanted, behind and beside a nearer surface (as the floor around HCI antinous's statue).
    Scene scene = emptyScene(model);
    scene.planes.push_back(backdrop(model, 2.2 * d, 24));
    const double offset = 0.56 * halfField(model, d);
    Plane floor = plane("floor", {0, offset, 1.4 * d}, 2 * d, 1.7 * d,
                        noise(offset / 8, {0.35f, 0.25f, 0.15f}, {0.85f, 0.75f, 0.6f}, 25));
    floor.tiltXDeg = 90;
    scene.planes.push_back(floor);
    const struct {
      double x, z, height;
      Rgb dark, light;
    } cards[] = {{-0.45, 0.9, 0.9, {0.5f, 0.1f, 0.1f}, {0.95f, 0.6f, 0.4f}},
                 {0.35, 1.3, 1.1, {0.1f, 0.3f, 0.1f}, {0.6f, 0.9f, 0.5f}}};
    for (const auto& card : cards) {
      const double h = halfField(model, card.z * d), tall = card.height * h;
      scene.planes.push_back(plane("card", {card.x * h, offset - tall / 2, card.z * d}, 0.35 * h, tall,
                                   noise(h / 8, card.dark, card.light, 26 + std::uint64_t(card.z * 10))));
    }
    scenes.push_back(simulated("cards on a steep floor", scene, model));
  }
  {  // Half an elliptic cylinder bulging towards the camera (from 0.8 to 1.1 times the focus
     // distance), 32 facets: deep enough along z for its disparity to curve by 0.6 px.
    Scene scene = emptyScene(model);
    scene.planes.push_back(backdrop(model, 2.0 * d, 4));
    const double across = 0.6 * halfField(model, d);
    addFacetedColumn(scene, across, 0.4 * d, 1.2 * d, 75, 32, 2.5 * across,
                     noise(across / 12, {0.15f, 0.1f, 0.3f}, {0.85f, 0.8f, 0.9f}, 6));
    scenes.push_back(simulated("curved surface", scene, model));
    scenes.push_back(simulated("curved surface, noisy", scene, model, true));
    scenes.push_back(glossy("curved surface, glossy", scene, model, 0.1));
    // Varnished: towards its sides, seen at grazing angles, it mirrors the backdrop (Fresnel), whose
    // virtual image lies behind the surface.
    for (std::size_t i = 1; i < scene.planes.size(); ++i) scene.planes[i].reflectance = 0.04;
    scenes.push_back(simulated("curved surface, varnished", scene, model));
  }
  {  // A grey column bulging far towards the camera (from 0.55 to 1.0 times the focus distance) before
     // a grey wall: disparity that changes fast at grazing angles, and no hue to tell surfaces apart.
    Scene scene = emptyScene(model);
    const double wallZ = 1.6 * d, hw = halfField(model, wallZ);
    scene.planes.push_back(
        plane("wall", {0, 0, wallZ}, 2.6 * hw, 2.6 * hw, noise(hw / 9, {0.25f, 0.25f, 0.25f}, {0.7f, 0.7f, 0.7f}, 18)));
    const double across = 0.45 * halfField(model, d);
    addFacetedColumn(scene, across, 0.45 * d, 1.0 * d, 80, 48, 3 * across,
                     noise(across / 10, {0.3f, 0.3f, 0.3f}, {0.8f, 0.8f, 0.8f}, 19));
    scenes.push_back(simulated("grey column", scene, model));
  }
  {  // Bars 1 to 4 pixels wide, nearer than a wall.
    Scene scene = emptyScene(model);
    scene.planes.push_back(backdrop(model, 1.6 * d, 8));
    const double z = 0.8 * d, h = halfField(model, z), pixel = 2 * h / size;
    for (int i = 0; i < 4; ++i)
      scene.planes.push_back(plane("bar", {(-0.6 + 0.4 * i) * h, 0, z}, (i + 1) * pixel, 1.6 * h,
                                   noise(h / 6, {0.6f, 0.1f, 0.1f}, {0.95f, 0.85f, 0.3f}, 9 + i)));
    scene.planes.push_back(plane("rail", {0, 0.5 * h, 0.9 * d}, 1.6 * h, 2 * pixel,
                                 noise(h / 6, {0.1f, 0.1f, 0.6f}, {0.4f, 0.9f, 0.95f}, 13)));
    scenes.push_back(simulated("thin structures", scene, model));
    scenes.push_back(simulated("thin structures, noisy", scene, model, true));
  }
  scenes.push_back(narrowNearParts(size));
  {  // Texture at the scale of a pixel, and of half a pixel, on two cards.
    Scene scene = emptyScene(model);
    const double far = 1.8 * d, hf = halfField(model, far);
    scene.planes.push_back(plane("far", {0, 0, far}, 2.6 * hf, 2.6 * hf,
                                 noise(1.0 * hf / size, {0.2f, 0.2f, 0.2f}, {0.8f, 0.8f, 0.8f}, 14)));
    const double z = 0.85 * d, h = halfField(model, z);
    scene.planes.push_back(plane("near", {-0.2 * h, 0.1 * h, z}, 0.9 * h, 0.9 * h,
                                 noise(2.0 * h / size, {0.1f, 0.3f, 0.1f}, {0.9f, 0.9f, 0.6f}, 15)));
    scenes.push_back(simulated("fine texture", scene, model));
  }
  scenes.push_back(simulated("weak texture", weakTexture(model), model));
  scenes.push_back(weakTextureGlossy(size));
  return scenes;
}

}  // namespace lfcam::bench
