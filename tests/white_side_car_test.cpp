// The white-image database beyond Lytro calibration data: PNG whites with a side-car naming serial
// and steps (a microscope's or another camera's), a Lytro white container, and a PNG capture with a
// side-car choosing among them; a side-car of the wrong shape refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "lfcam/calibrate/white_database.hpp"
#include "lfcam/decode/decode_files.hpp"
#include "lytro_caldata.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

// raw.png, white.png and camera.json of a chart through the camera of `lattice`, in `folder`.
void simulateInto(const fs::path& folder, int lattice) {
  const CameraModel camera = test::lytroLikeCamera(false, {.lattice = lattice});
  auto scene = builtinScene("chart", camera);
  ASSERT_TRUE(scene.ok());
  ASSERT_TRUE(writeSimulation(folder, *scene, camera, {.samplesPerPixel = 4}, {.white = true, .groundTruth = false}));
}

void writeSideCar(const fs::path& path, double zoom, double focus) {
  test::writeBytes(path, nlohmann::json{{"serial", "MICRO-1"}, {"zoom_step", zoom}, {"focus_step", focus}}.dump());
}

TEST(WhiteSideCar, PngWhitesAndALytroWhiteChooseForAPngCapture) {
  test::TempDir dir;
  simulateInto(dir / "z100", 0);
  simulateInto(dir / "z300", 2);
  writeSideCar(dir / "z100" / "white.json", 100, 0);
  writeSideCar(dir / "z300" / "white.json", 300, 0);
  // The same white as a Lytro container of zoom step 500, named by its metadata.
  auto white = readRaw(dir / "z300" / "white.png");
  ASSERT_TRUE(white);
  fs::create_directories(dir / "lytro");
  LytroWriteOptions options{.style = LytroStyle::Illum, .modulationFrame = true};
  options.setting = {.serial = "MICRO-1", .zoomStep = 500, .focusStep = 0};
  ASSERT_TRUE(writeLytroRaw(dir / "lytro" / "W500.lfr", *white, options));

  auto database =
      indexWhites({dir / "z100" / "white.png", dir / "z300" / "white.png", dir / "lytro"}, dir / "whites.json");
  ASSERT_TRUE(database) << database.error().message;
  ASSERT_EQ(database->whites.size(), 3u);
  EXPECT_EQ(database->whites[0].setting.metadataKeys, "side-car");
  EXPECT_EQ(database->whites[2].setting.metadataKeys, "lytro-frame");
  EXPECT_EQ(database->whites[2].white, dir / "lytro" / "W500.lfr");

  // The capture's side-car: zoom step 280, nearest the white of 300.
  writeSideCar(dir / "z300" / "raw.json", 280, 10);
  std::string told;
  auto chosen = decodeRawFiles({.raw = (dir / "z300" / "raw.png").string(),
                                .whites = (dir / "whites.json").string(),
                                .onWhiteChosen = [&](const std::string& reason) { told = reason; }});
  ASSERT_TRUE(chosen) << chosen.error().message;
  EXPECT_NE(told.find("z300/white.png (zoom step 300, focus step 0): of 3 whites of camera MICRO-1"), std::string::npos)
      << told;
  auto byHand =
      decodeRawFiles({.raw = (dir / "z300" / "raw.png").string(), .white = (dir / "z300" / "white.png").string()});
  ASSERT_TRUE(byHand);
  EXPECT_TRUE(std::equal(chosen->samples().begin(), chosen->samples().end(), byHand->samples().begin(),
                         byHand->samples().end()));

  // A side-car whose serial is no string names itself.
  test::writeBytes(dir / "z100" / "raw.json", R"({"serial": 5, "zoom_step": 100, "focus_step": 0})");
  auto wrong = readRaw(dir / "z100" / "raw.png");
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().message, (dir / "z100" / "raw.json").string() + ": serial: expected a string");
}

}  // namespace
}  // namespace lfcam
