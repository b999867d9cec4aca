// Scene files and built-in scenes: parsing, errors that name the file and the key, textures; the
// tracer's mirror reflection.
#include <gtest/gtest.h>

#include <fstream>

#include "lfcam/io/image_io.hpp"
#include "lfcam/simulate/scene.hpp"
#include "simulate/tracing.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

Result<Scene> parse(const std::string& text) { return parseScene(text, "scene.json", "."); }

void expectError(const std::string& text, const std::string& fragment) {
  auto scene = parse(text);
  ASSERT_FALSE(scene) << text;
  EXPECT_NE(scene.error().message.find("scene.json: "), std::string::npos) << scene.error().message;
  EXPECT_NE(scene.error().message.find(fragment), std::string::npos) << scene.error().message;
}

TEST(SimulateScene, ParsesAFullSceneFile) {
  auto scene = parse(R"({
    "name": "desk",
    "background": [0.1, 0.2, 0.3],
    "camera": {
      "main_lens": {"focal_length_mm": 80, "image_f_number": 4, "focus_distance_mm": 600},
      "microlenses": {"pitch_mm": 0.1, "focal_length_mm": 0.4, "packing": "hexagonal", "rotation_deg": 0.5,
                      "offset_mm": [0.01, -0.02], "fill_factor": 0.9},
      "sensor": {"width": 300, "height": 200, "pixel_pitch_mm": 0.007, "color_filter": "GRBG", "bit_depth": 10,
                 "black_level": 32, "read_noise": 2.5, "hot_pixels": 0.001, "seed": 9}
    },
    "planes": [{"name": "card", "centre_mm": [0, 0, 550], "size_mm": [40, 30], "tilt_deg": [10, -5],
                "reflectance": 0.04, "texture": {"type": "chart", "min_frequency": 0.5, "max_frequency": 4, "groups": 5}}],
    "lights": [{"position_mm": [1, 2, 900], "radius_mm": 0.2, "radiance": 5}]
  })");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_EQ(scene->name, "desk");
  const CameraModel& camera = scene->camera;
  EXPECT_NEAR(camera.mainLens.imageSideFNumber(), 4.0, 1e-12);
  ASSERT_TRUE(camera.microlenses);
  EXPECT_EQ(camera.microlenses->packing, Packing::Hexagonal);
  EXPECT_EQ(camera.sensor.colorFilter, ColorFilter::GRBG);
  EXPECT_EQ(camera.sensor.whiteLevel, 1023);  // from the bit depth
  ASSERT_EQ(scene->planes.size(), 1u);
  EXPECT_EQ(scene->planes[0].texture.kind, TextureKind::Chart);
  EXPECT_EQ(scene->planes[0].tiltXDeg, 10);
  EXPECT_EQ(scene->planes[0].reflectance, 0.04);
  ASSERT_EQ(scene->lights.size(), 1u);
  EXPECT_EQ(scene->lights[0].radiance[1], 5.0f);
}

TEST(SimulateScene, ConventionalCameraAndBuiltinBase) {
  auto scene = parse(R"({"builtin": "chart", "camera": {"microlenses": false}})");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_FALSE(scene->camera.microlenses);
  EXPECT_EQ(scene->planes.size(), 1u);
}

TEST(SimulateScene, ErrorsNameTheFileAndTheKey) {
  expectError("{ not json", "not valid JSON");
  expectError("[1, 2]", "expected an object");
  expectError(R"({"camera": {"sensor": {"width": -3}}})", "camera.sensor.width");
  expectError(R"({"camera": {"sensor": {"widht": 30}}})", "camera.sensor.widht: unknown key");
  expectError(R"({"camera": {"main_lens": {"f_number": "fast"}}})", "camera.main_lens.f_number: expected a number");
  expectError(R"({"camera": {"main_lens": {"focal_length_mm": 100, "focus_distance_mm": 50}}})",
              "camera.main_lens.focus_distance_mm");
  expectError(R"({"camera": {"microlenses": {"packing": "round"}}})", "camera.microlenses.packing");
  expectError(R"({"camera": {"sensor": {"color_filter": "XYZW"}}})", "camera.sensor.color_filter");
  expectError(R"({"planes": [{"centre_mm": [0, 0, 100]}, {"size_mm": [1, 1]}]})", "planes[1].centre_mm: missing");
  expectError(R"({"planes": [{"centre_mm": [0, 0, -5]}]})", "planes[0].centre_mm");
  expectError(R"({"planes": [{"centre_mm": [0, 0, 5], "texture": {"type": "plaid"}}]})", "planes[0].texture.type");
  expectError(R"({"planes": [{"centre_mm": [0, 0, 5], "texture": {"type": "image", "file": "missing.png"}}]})",
              "planes[0].texture.file");
  expectError(R"({"lights": [{"position_mm": [0, 0, 5], "radiance": [1, 2]}]})", "lights[0].radiance");
  expectError(R"({"planes": [{"centre_mm": [0, 0, 5], "reflectance": 1.5}]})", "planes[0].reflectance");
  expectError(R"({"builtin": "zoo"})", "builtin");
  expectError(R"({"colour": 1})", "colour: unknown key");
}

TEST(SimulateScene, LoadsFilesAndBuiltins) {
  test::TempDir dir;
  for (const auto& name : builtinSceneNames()) {
    auto scene = loadScene(name);
    ASSERT_TRUE(scene) << name;
    EXPECT_EQ(scene->name, name);
  }
  auto missing = loadScene((dir / "nothing.json").string());
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::Io);
  std::ofstream(dir / "bad.json") << R"({"camera": {"sensor": {"bit_depth": 40}}})";
  auto bad = loadScene((dir / "bad.json").string());
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find((dir / "bad.json").string() + ": camera.sensor.bit_depth"), std::string::npos)
      << bad.error().message;
}

TEST(SimulateScene, ImageTextureRelativeToTheSceneFile) {
  test::TempDir dir;
  Image picture(4, 2, 3);
  for (int c = 0; c < 3; ++c) picture.at(3, 1, c) = 1.0f;  // bottom-right pixel white
  ASSERT_TRUE(writeImage(dir / "picture.png", picture, {.sampleType = SampleType::UInt16}));
  std::ofstream(dir / "scene.json")
      << R"({"planes": [{"centre_mm": [0, 0, 500], "size_mm": [40, 20], "texture": {"type": "image", "file": "picture.png"}}]})";
  auto scene = loadScene((dir / "scene.json").string());
  ASSERT_TRUE(scene) << scene.error().message;
  const Texture& texture = scene->planes[0].texture;
  EXPECT_NEAR(texture.evaluate(35, 15, 40, 20)[1], 1.0, 1e-4);  // centre of the bottom-right texel
  EXPECT_NEAR(texture.evaluate(5, 5, 40, 20)[1], 0.0, 1e-4);
}

TEST(SimulateScene, ProceduralTextures) {
  Texture chart;
  chart.kind = TextureKind::Chart;
  chart.groups = 2;
  chart.minFrequency = 1;
  chart.maxFrequency = 2;
  // Group 0 (x in [0, 50) of a 100 mm chart), top half: vertical bars of 1 cycle/mm from x = 5.
  EXPECT_EQ(chart.evaluate(5.2, 25, 100, 100), chart.dark);
  EXPECT_EQ(chart.evaluate(5.7, 25, 100, 100), chart.light);
  EXPECT_EQ(chart.evaluate(6.2, 25, 100, 100), chart.dark);
  Texture checker;
  checker.kind = TextureKind::Checkerboard;
  checker.periodMm = 10;
  EXPECT_NE(checker.evaluate(51, 51, 100, 100), checker.evaluate(41, 51, 100, 100));
  EXPECT_EQ(checker.evaluate(51, 51, 100, 100), checker.evaluate(41, 41, 100, 100));
  Texture star;
  star.kind = TextureKind::SiemensStar;
  star.spokes = 4;
  EXPECT_NE(star.evaluate(90, 51, 100, 100), star.evaluate(90, 49, 100, 100));
  Texture edge;
  edge.kind = TextureKind::Edge;
  EXPECT_EQ(edge.evaluate(10, 50, 100, 100), edge.dark);
  EXPECT_EQ(edge.evaluate(90, 50, 100, 100), edge.light);
}

// A white card of reflectance 0.04 before a grey background: facing the ray it shows 96 % of its
// white and 4 % of the grey behind the camera; turned 80 degrees away, Schlick's
// 0.04 + 0.96 (1 - cos 80)^5 = 0.418 of what it mirrors, the grey that lies beyond it.
TEST(SimulateTrace, ReflectiveCardMirrorsMoreAtGrazingAngles) {
  for (double tilt : {0.0, 80.0}) {
    Scene scene;
    scene.background = {0.5f, 0.5f, 0.5f};
    Plane card;
    card.centreMm = {0, 0, 1000};
    card.widthMm = card.heightMm = 1000;
    card.tiltYDeg = tilt;
    card.texture.kind = TextureKind::Constant;
    card.texture.light = {1, 1, 1};
    card.reflectance = 0.04;
    scene.planes.push_back(card);
    const simulate_detail::PreparedScene prepared(scene, CameraModel::paperPrototype());
    const simulate_detail::Hit hit = prepared.trace({0, 0, 0}, {0, 0, 1});
    const double cosine = std::cos(tilt * M_PI / 180), fresnel = 0.04 + 0.96 * std::pow(1 - cosine, 5);
    EXPECT_NEAR(hit.radiance[0], (1 - fresnel) * 1.0 + fresnel * 0.5, 1e-5) << tilt;
    EXPECT_NEAR(hit.depth, 1000, 1e-6) << tilt;
    card.reflectance = 0;
    scene.planes = {card};
    EXPECT_NEAR(
        simulate_detail::PreparedScene(scene, CameraModel::paperPrototype()).trace({0, 0, 0}, {0, 0, 1}).radiance[0],
        1.0, 1e-6);
  }
}

}  // namespace
}  // namespace lfcam
