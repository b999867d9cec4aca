// Scenes: procedural textures, the built-in scenes, and the scene file (docs/formats.md).
#include "lfcam/simulate/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/json_reader.hpp"
#include "lfcam/io/image_io.hpp"
#include "simulate/camera_json.hpp"

namespace lfcam {

using json_reader::JsonObject;

namespace {

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
double hashUnit(std::uint64_t seed, long long a, long long b) {
  return double(mix(mix(seed ^ std::uint64_t(a) * 0x632be59bd9b4e019ull) ^ std::uint64_t(b)) >> 11) * 0x1.0p-53;
}

Rgb blend(const Rgb& a, const Rgb& b, double w) {
  return {float(a[0] + (b[0] - a[0]) * w), float(a[1] + (b[1] - a[1]) * w), float(a[2] + (b[2] - a[2]) * w)};
}

// floor(v) as a cell index, saturated: a huge ratio (a period of 1e-300 mm) or a NaN must not
// overflow the conversion to an integer, which is undefined behaviour.
long long cellIndex(double v) {
  constexpr double kLimit = 0x1p62;
  if (!(std::abs(v) < kLimit)) return std::isnan(v) ? 0 : v > 0 ? (1ll << 62) : -(1ll << 62);
  return (long long)std::floor(v);
}

double smoothNoise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const long long ix = cellIndex(x), iy = cellIndex(y);
  double tx = x - fx, ty = y - fy;
  tx = tx * tx * (3 - 2 * tx);
  ty = ty * ty * (3 - 2 * ty);
  const double a = hashUnit(seed, ix, iy), b = hashUnit(seed, ix + 1, iy);
  const double c = hashUnit(seed, ix, iy + 1), d = hashUnit(seed, ix + 1, iy + 1);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

}  // namespace

Rgb Texture::evaluate(double x, double y, double width, double height) const {
  // (x, y): from the plane's top-left corner, mm; x right, y down.
  switch (kind) {
    case TextureKind::Constant: return light;
    case TextureKind::Image: {
      const Image& im = *image;
      const double fx = x / width * im.width() - 0.5, fy = y / height * im.height() - 0.5;
      const int x0 = int(std::clamp<long long>(cellIndex(fx), 0, im.width() - 1)),
                y0 = int(std::clamp<long long>(cellIndex(fy), 0, im.height() - 1));
      const int x1 = std::min(x0 + 1, im.width() - 1), y1 = std::min(y0 + 1, im.height() - 1);
      const double wx = std::clamp(fx - std::floor(fx), 0.0, 1.0), wy = std::clamp(fy - std::floor(fy), 0.0, 1.0);
      Rgb out{};
      for (int c = 0; c < 3; ++c) {
        const int cc = im.channels() >= 3 ? c : 0;  // grey (and grey + alpha) images: grey
        const double top = im.at(x0, y0, cc) + (im.at(x1, y0, cc) - im.at(x0, y0, cc)) * wx;
        const double bottom = im.at(x0, y1, cc) + (im.at(x1, y1, cc) - im.at(x0, y1, cc)) * wx;
        out[c] = float(top + (bottom - top) * wy);
      }
      return out;
    }
    case TextureKind::Checkerboard: {
      const long long i = cellIndex((x - 0.5 * width) / periodMm);
      const long long j = cellIndex((y - 0.5 * height) / periodMm);
      return ((i ^ j) & 1) ? dark : light;  // the parity of i + j, without a sum that can overflow
    }
    case TextureKind::Chart: {
      // Group k in the k-th column; vertical bars (frequency along x) on top, horizontal below;
      // a margin of 10% of the column around each group, light background.
      const double column = width / groups;
      const int k = int(std::clamp<long long>(cellIndex(x / column), 0, groups - 1));
      const double lx = x - k * column, half = 0.5 * height;
      const bool top = y < half;
      const double ly = top ? y : y - half;
      if (lx < 0.1 * column || lx > 0.9 * column || ly < 0.1 * half || ly > 0.9 * half) return light;
      const double frequency =
          groups > 1 ? minFrequency * std::pow(maxFrequency / minFrequency, double(k) / (groups - 1)) : minFrequency;
      const double along = top ? lx - 0.1 * column : ly - 0.1 * half;
      return std::fmod(along * frequency, 1.0) < 0.5 ? dark : light;
    }
    case TextureKind::SiemensStar: {
      const double angle = std::atan2(y - 0.5 * height, x - 0.5 * width);
      const double sector = (angle + M_PI) / (2 * M_PI) * spokes * 2;
      return cellIndex(sector) & 1 ? dark : light;
    }
    case TextureKind::Text: {
      // Lines of glyphs: each glyph a 3x5 grid of random strokes in a 4x7 cell, gaps between
      // words; one line of glyph height `periodMm` every 1.5 lines.
      const double cell = periodMm / 5.0;  // one stroke
      const long long line = cellIndex(y / (1.5 * periodMm));
      const double inLine = y - line * 1.5 * periodMm;
      if (inLine >= periodMm) return light;
      const long long glyph = cellIndex(x / (4 * cell));
      const double inGlyph = x - double(glyph) * 4 * cell;  // glyph may be saturated: no integer product
      if (inGlyph >= 3 * cell) return light;
      // Hash keys in unsigned arithmetic: it wraps where signed would overflow.
      if (hashUnit(seed, line, (long long)(std::uint64_t(glyph) * 7 + 3)) < 0.18)
        return light;  // a space between words
      const int gx = int(std::clamp<long long>(cellIndex(inGlyph / cell), 0, 2));
      const int gy = int(std::clamp<long long>(cellIndex(inLine / cell), 0, 4));
      return hashUnit(seed ^ 0x51ed, (long long)(std::uint64_t(line) * 1000003 + std::uint64_t(glyph)), gy * 3 + gx) <
                     0.55
                 ? dark
                 : light;
    }
    case TextureKind::Noise: {
      const double n = 0.6 * smoothNoise(seed, x / periodMm, y / periodMm) +
                       0.4 * smoothNoise(seed + 1, 2.7 * x / periodMm, 2.7 * y / periodMm);
      return blend(dark, light, std::clamp(n, 0.0, 1.0));
    }
    case TextureKind::Edge: {
      const double angle = angleDeg * M_PI / 180.0;
      // Signed distance from the line through the centre at angle from vertical (clockwise).
      const double d = (x - 0.5 * width) * std::cos(angle) - (y - 0.5 * height) * std::sin(angle);
      return d < 0 ? dark : light;
    }
  }
  return light;
}

namespace {

Plane card(std::string name, double x, double y, double z, double w, double h, Texture texture) {
  Plane plane;
  plane.name = std::move(name);
  plane.centreMm = {x, y, z};
  plane.widthMm = w;
  plane.heightMm = h;
  plane.texture = std::move(texture);
  return plane;
}

Texture procedural(TextureKind kind, double period, Rgb dark, Rgb light, std::uint64_t seed = 1) {
  Texture t;
  t.kind = kind;
  t.periodMm = period;
  t.dark = dark;
  t.light = light;
  t.seed = seed;
  return t;
}

// Half the field of view (mm) at distance z: the sensor's half width mapped through the lens.
double halfField(const CameraModel& camera, double z) {
  return 0.5 * std::min(camera.sensor.widthMm(), camera.sensor.heightMm()) * z / camera.mainLens.imageDistanceMm();
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"people", "chart", "pinhole", "white"}; }
bool isBuiltinSceneName(const std::string& name) {
  const auto names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Result<Scene> builtinScene(const std::string& name, const CameraModel& camera) {
  Scene scene;
  scene.name = name;
  scene.camera = camera;
  const double d = camera.mainLens.focusDistanceMm;
  if (name == "people") {
    // Cards at several depths around the focus distance, in the spirit of Figures 13-14: a
    // noise backdrop far behind, a "person" in the focal plane, one nearer, one farther.
    const double far = 2.0 * d, nearZ = 0.8 * d, farZ = 1.3 * d;
    const double hb = halfField(camera, far);
    scene.planes.push_back(
        card("backdrop", 0, 0, far, 2.4 * hb, 2.4 * hb,
             procedural(TextureKind::Noise, hb / 6, {0.10f, 0.25f, 0.12f}, {0.55f, 0.75f, 0.45f}, 7)));
    const double hf = halfField(camera, farZ);
    scene.planes.push_back(
        card("far person", 0.45 * hf, -0.1 * hf, farZ, 0.7 * hf, 1.6 * hf,
             procedural(TextureKind::Checkerboard, hf / 6, {0.1f, 0.1f, 0.35f}, {0.8f, 0.8f, 0.95f})));
    const double hd = halfField(camera, d);
    scene.planes.push_back(
        card("focused person", -0.05 * hd, 0.05 * hd, d, 0.6 * hd, 1.5 * hd,
             procedural(TextureKind::Text, hd / 10, {0.05f, 0.05f, 0.05f}, {0.95f, 0.85f, 0.7f}, 3)));
    const double hn = halfField(camera, nearZ);
    Texture star = procedural(TextureKind::SiemensStar, 1, {0.4f, 0.05f, 0.05f}, {0.95f, 0.9f, 0.8f});
    star.spokes = 16;
    scene.planes.push_back(card("near person", -0.55 * hn, 0.3 * hn, nearZ, 0.6 * hn, 0.9 * hn, star));
    scene.background = {0.6f, 0.7f, 0.9f};
  } else if (name == "chart") {
    // Section 6.1: a resolution chart slightly nearer than the focus distance (5%).
    const double z = 0.95 * d, h = halfField(camera, z);
    Texture chart = procedural(TextureKind::Chart, 1, {0.05f, 0.05f, 0.05f}, {0.9f, 0.9f, 0.9f});
    // Frequencies from 1/8 to 1 cycle per microlens-sized patch of the target... expressed per mm
    // on the target: a microlens sees pitch * z / F mm of it.
    const double patch = camera.microlenses ? camera.microlenses->pitchMm * z / camera.mainLens.imageDistanceMm()
                                            : 14 * camera.sensor.pixelPitchMm * z / camera.mainLens.imageDistanceMm();
    chart.minFrequency = 0.0625 / patch;
    chart.maxFrequency = 0.5 / patch;
    chart.groups = 6;
    scene.planes.push_back(card("chart", 0, 0, z, 1.6 * h, 1.6 * h, chart));
    scene.background = {0.2f, 0.2f, 0.2f};
  } else if (name == "pinhole") {
    // A point source at the focus distance on a black field (the pinhole target of section 6.1).
    PointLight light;
    light.name = "pinhole";
    light.positionMm = {0, 0, d};
    // Its image is half a microlens across (two pixels in a conventional camera): below the light
    // field's spatial resolution, yet large enough for rays traced from the sensor to find it.
    const double imageDiameter =
        camera.microlenses ? 0.5 * camera.microlenses->pitchMm : 2 * camera.sensor.pixelPitchMm;
    light.radiusMm = 0.5 * imageDiameter * d / camera.mainLens.imageDistanceMm();
    light.radiance = {1, 1, 1};
    scene.lights.push_back(light);
  } else if (name == "white") {
    scene.background = {1, 1, 1};
  } else {
    std::string names;
    for (const auto& n : builtinSceneNames()) names += (names.empty() ? "" : ", ") + n;
    return makeError(ErrorCode::Usage, name + ": not a scene file nor a built-in scene (" + names + ")");
  }
  return scene;
}

namespace {

Result<Texture> parseTexture(const nlohmann::json& json, const std::string& where, const std::string& path,
                             const std::filesystem::path& baseFolder) {
  JsonObject o(json, where, path);
  LFCAM_TRY(o.requireObject());
  Texture t;
  std::string type = "constant";
  LFCAM_TRY(o.string("type", type));
  static const std::pair<const char*, TextureKind> kinds[] = {{"constant", TextureKind::Constant},
                                                              {"image", TextureKind::Image},
                                                              {"checkerboard", TextureKind::Checkerboard},
                                                              {"chart", TextureKind::Chart},
                                                              {"siemens", TextureKind::SiemensStar},
                                                              {"text", TextureKind::Text},
                                                              {"noise", TextureKind::Noise},
                                                              {"edge", TextureKind::Edge}};
  bool found = false;
  for (const auto& [n, k] : kinds)
    if (type == n) {
      t.kind = k;
      found = true;
    }
  if (!found)
    return o.fail(o.keyPath("type"),
                  "expected constant, image, checkerboard, chart, siemens, text, noise or edge, got \"" + type + "\"");
  if (t.kind == TextureKind::Constant) t.light = {1, 1, 1};
  LFCAM_TRY(o.colour("dark", t.dark));
  LFCAM_TRY(o.colour("light", t.light));
  if (o.has("colour")) LFCAM_TRY(o.colour("colour", t.light));
  o.markSeen("colour");
  LFCAM_TRY(o.number("period_mm", t.periodMm, 0, 1e9, true));
  LFCAM_TRY(o.integer("groups", t.groups, 1, 100));
  LFCAM_TRY(o.number("min_frequency", t.minFrequency, 0, 1e6, true));
  LFCAM_TRY(o.number("max_frequency", t.maxFrequency, 0, 1e6, true));
  LFCAM_TRY(o.integer("spokes", t.spokes, 1, 10000));
  LFCAM_TRY(o.number("angle_deg", t.angleDeg, -360, 360));
  LFCAM_TRY(o.unsignedInteger("seed", t.seed));
  LFCAM_TRY(o.string("file", t.imagePath));
  if (t.kind == TextureKind::Image) {
    if (t.imagePath.empty()) return o.fail(o.keyPath("file"), "an image texture needs a file");
    std::filesystem::path file = t.imagePath;
    if (file.is_relative()) file = baseFolder / file;
    auto image = readImage(file);
    if (!image) return makeError(image.error().code, where + ": " + o.keyPath("file") + ": " + image.error().message);
    for (int c = 0; c < image->channels(); ++c)
      for (std::size_t i = 0; i < image->planeSize(); ++i)
        if (!std::isfinite(image->plane(c)[i]))
          return o.fail(o.keyPath("file"), file.string() + " holds NaN or infinite values");
    t.image = std::make_shared<const Image>(std::move(*image));
  }
  LFCAM_TRY(o.noUnknownKeys());
  return t;
}

}  // namespace

Result<Scene> parseScene(const std::string& text, const std::string& where, const std::filesystem::path& baseFolder) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax, and numbers out of range (1e999)
    std::string message = e.what();
    const auto colon = message.find("parse error");
    if (colon != std::string::npos) message = message.substr(colon);
    return makeError(ErrorCode::Format, where + ": not valid JSON: " + message);
  }
  JsonObject root(json, where, "");
  LFCAM_TRY(root.requireObject());
  Scene scene;
  scene.name = std::filesystem::path(where).stem().string();
  LFCAM_TRY(root.string("name", scene.name));
  LFCAM_TRY(root.colour("background", scene.background));
  CameraModel camera = CameraModel::paperPrototype();
  if (root.has("camera")) {
    LFCAM_ASSIGN_OR_RETURN(auto parsed, cameraFromJson(root.at("camera"), camera, where));
    camera = std::move(parsed);
  }
  root.markSeen("camera");
  scene.camera = camera;

  // A built-in scene to start from, framed for this camera; planes and lights are added to it.
  if (root.has("builtin")) {
    std::string name;
    LFCAM_TRY(root.string("builtin", name));
    if (!isBuiltinSceneName(name)) return root.fail("builtin", "unknown built-in scene \"" + name + "\"");
    LFCAM_ASSIGN_OR_RETURN(auto base, builtinScene(name, camera));
    const std::string keepName = scene.name;
    const Rgb background = scene.background;
    scene = std::move(base);
    scene.name = keepName;
    if (root.has("background")) scene.background = background;
  }
  root.markSeen("builtin");

  if (root.has("planes")) {
    const auto& planes = root.at("planes");
    if (!planes.is_array()) return root.fail("planes", "expected an array of objects");
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const std::string path = "planes[" + std::to_string(k) + "]";
      JsonObject o(planes[k], where, path);
      LFCAM_TRY(o.requireObject());
      Plane plane;
      plane.name = "plane " + std::to_string(k);
      LFCAM_TRY(o.string("name", plane.name));
      if (!o.has("centre_mm")) return o.fail(o.keyPath("centre_mm"), "missing: [x, y, z] of the plane's centre");
      LFCAM_TRY(o.numbers("centre_mm", plane.centreMm, -1e9, 1e9));
      if (!(plane.centreMm[2] > 0)) return o.fail(o.keyPath("centre_mm"), "z must be positive (in front of the lens)");
      std::array<double, 2> size{plane.widthMm, plane.heightMm};
      LFCAM_TRY(o.numbers("size_mm", size, 1e-9, 1e9));
      plane.widthMm = size[0];
      plane.heightMm = size[1];
      std::array<double, 2> tilt{0, 0};
      LFCAM_TRY(o.numbers("tilt_deg", tilt, -89, 89));
      plane.tiltXDeg = tilt[0];
      plane.tiltYDeg = tilt[1];
      LFCAM_TRY(o.number("reflectance", plane.reflectance, 0, 1));
      if (o.has("texture")) {
        LFCAM_ASSIGN_OR_RETURN(auto texture, parseTexture(o.at("texture"), where, o.keyPath("texture"), baseFolder));
        plane.texture = std::move(texture);
      } else {
        plane.texture.kind = TextureKind::Constant;
        plane.texture.light = {1, 1, 1};
      }
      o.markSeen("texture");
      LFCAM_TRY(o.noUnknownKeys());
      scene.planes.push_back(std::move(plane));
    }
  }
  root.markSeen("planes");

  if (root.has("lights")) {
    const auto& lights = root.at("lights");
    if (!lights.is_array()) return root.fail("lights", "expected an array of objects");
    for (std::size_t k = 0; k < lights.size(); ++k) {
      const std::string path = "lights[" + std::to_string(k) + "]";
      JsonObject o(lights[k], where, path);
      LFCAM_TRY(o.requireObject());
      PointLight light;
      light.name = "light " + std::to_string(k);
      LFCAM_TRY(o.string("name", light.name));
      if (!o.has("position_mm")) return o.fail(o.keyPath("position_mm"), "missing: [x, y, z] of the light");
      LFCAM_TRY(o.numbers("position_mm", light.positionMm, -1e9, 1e9));
      if (!(light.positionMm[2] > 0))
        return o.fail(o.keyPath("position_mm"), "z must be positive (in front of the lens)");
      LFCAM_TRY(o.number("radius_mm", light.radiusMm, 0, 1e9, true));
      LFCAM_TRY(o.colour("radiance", light.radiance));
      LFCAM_TRY(o.noUnknownKeys());
      scene.lights.push_back(light);
    }
  }
  root.markSeen("lights");
  LFCAM_TRY(root.noUnknownKeys());
  return scene;
}

Result<Scene> loadScene(const std::string& nameOrPath) {
  std::error_code ec;
  if (!std::filesystem::exists(nameOrPath, ec) && isBuiltinSceneName(nameOrPath))
    return builtinScene(nameOrPath, CameraModel::paperPrototype());
  if (!std::filesystem::exists(nameOrPath, ec)) {
    std::string names;
    for (const auto& n : builtinSceneNames()) names += (names.empty() ? "" : ", ") + n;
    return makeError(ErrorCode::Io, nameOrPath + ": no such scene file, and not a built-in scene (" + names + ")");
  }
  if (std::filesystem::is_directory(nameOrPath, ec))
    return makeError(ErrorCode::Usage, nameOrPath + ": is a folder, expected a scene file (.json)");
  std::ifstream in(nameOrPath, std::ios::binary);
  if (!in) return makeError(ErrorCode::Io, nameOrPath + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return makeError(ErrorCode::Io, nameOrPath + ": cannot read");
  const std::filesystem::path base = std::filesystem::path(nameOrPath).parent_path();
  return parseScene(text.str(), nameOrPath, base.empty() ? std::filesystem::path(".") : base);
}

}  // namespace lfcam
