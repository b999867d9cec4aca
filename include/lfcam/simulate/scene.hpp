// Scene: what the simulated camera looks at. Objects at given distances in front of the main lens
// (frames and units of camera_model.hpp: mm, x right, y down, z away from the camera):
//   - textured planes (rectangles), optionally tilted, with an image file or a procedural texture;
//   - point lights: small emitting discs facing the camera (the pinhole target of section 6.1);
//   - a uniform background radiance for rays that hit nothing (1: the white field of a white
//     image).
// Radiance is linear RGB, 1 = white. The scene file format (JSON) is in docs/formats.md.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/simulate/camera_model.hpp"

namespace lfcam {

using Rgb = std::array<float, 3>;

enum class TextureKind {
  Constant,      // `colour` everywhere
  Image,         // an image file stretched over the plane (bilinear, linear light)
  Checkerboard,  // squares of `period` mm
  Chart,         // resolution chart: bar groups of known frequencies (cycles/mm on the plane)
  SiemensStar,   // `spokes` black and white sectors around the plane's centre
  Text,          // text-like rows of glyphs of `period` mm height
  Noise,         // value noise with features of `period` mm
  Edge,          // a straight edge through the centre: dark left of it, light right of it
};

struct Texture {
  TextureKind kind = TextureKind::Constant;
  Rgb dark{0.05f, 0.05f, 0.05f};  // the two colours of the procedural patterns
  Rgb light{0.9f, 0.9f, 0.9f};
  double periodMm = 10;  // checker square, glyph height, noise feature
  // Chart: `groups` bar groups, frequencies geometric from minFrequency to maxFrequency
  // (cycles/mm on the plane), left to right; vertical bars in the top half, horizontal below.
  int groups = 6;
  double minFrequency = 0.2, maxFrequency = 2.0;
  int spokes = 36;                     // Siemens star
  double angleDeg = 0;                 // edge: the edge's angle from vertical, clockwise
  std::uint64_t seed = 1;              // text and noise
  std::shared_ptr<const Image> image;  // Image: RGB, linear
  std::string imagePath;               // where it came from (for messages and camera.json)

  Rgb evaluate(double x, double y, double width, double height) const;  // plane coordinates, mm
};

struct Plane {
  std::string name;
  std::array<double, 3> centreMm{0, 0, 1000};
  double widthMm = 100, heightMm = 100;
  double tiltXDeg = 0;  // about the plane's horizontal axis: positive turns its top away
  double tiltYDeg = 0;  // about its vertical axis: positive turns its right side away
  Texture texture;
  // Mirror reflectance at normal incidence, rising towards grazing angles (Schlick's
  // approximation of Fresnel's equations): 0.04 for glass, marble or varnish. The texture shows
  // through the rest; what the plane reflects is traced one bounce.
  double reflectance = 0;
};

struct PointLight {
  std::string name;
  std::array<double, 3> positionMm{0, 0, 1000};
  double radiusMm = 0.05;  // of the emitting disc
  Rgb radiance{1, 1, 1};
};

struct Scene {
  std::string name;
  std::vector<Plane> planes;
  std::vector<PointLight> lights;
  Rgb background{0, 0, 0};
  // The camera the scene file asks for (its "camera" object over the paper prototype).
  CameraModel camera = CameraModel::paperPrototype();
};

// The built-in scenes: "people", "chart", "pinhole", "white". They are framed for `camera` (cards
// sized to its field of view). Unknown name: a Usage error listing the names.
Result<Scene> builtinScene(const std::string& name, const CameraModel& camera);
bool isBuiltinSceneName(const std::string& name);
std::vector<std::string> builtinSceneNames();

// Parses a scene from JSON text; `where` names its source in errors ("scene.json: planes[1].size:
// expected ..."). Relative image paths are taken from `baseFolder`.
Result<Scene> parseScene(const std::string& text, const std::string& where, const std::filesystem::path& baseFolder);
// A built-in name or a JSON file.
Result<Scene> loadScene(const std::string& nameOrPath);

}  // namespace lfcam
