// lfcam calibrate: a simulator white image in, grid.json out; one-line errors and exit statuses.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_support.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "simulate/simulated_grid.hpp"

namespace lfcam::test {
namespace {

TEST(CalibrateCommand, WritesTheGridOfASimulatedWhiteImage) {
  const TempDir dir;
  CameraModel camera = CameraModel::paperPrototype(300, 300);
  camera.microlenses->packing = Packing::Hexagonal;
  camera.microlenses->rotationDeg = 0.5;
  camera.sensor.colorFilter = ColorFilter::Mono;
  auto scene = builtinScene("white", camera);
  ASSERT_TRUE(scene.ok());
  Image white = simulateCapture(*scene, camera, {.samplesPerPixel = 4}).irradiance;
  for (float& v : white.pixels()) v *= 10;  // into [0, 1] for a 16-bit file
  ASSERT_TRUE(writeImage(dir / "white.tif", white).ok());
  const auto result =
      runLfcam({"calibrate", (dir / "white.tif").string(), "-o", (dir / "grid.json").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_NE(result.out.find("hexagonal grid"), std::string::npos) << result.out;
  auto grid = readGrid(dir / "grid.json");
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  const LensletGrid truth = gridFromCamera(camera);
  EXPECT_EQ(grid->packing, Packing::Hexagonal);
  EXPECT_NEAR(grid->pitchX, truth.pitchX, 0.01);
  EXPECT_NEAR(grid->rotationRad, truth.rotationRad, 0.001);
}

TEST(CalibrateCommand, ErrorsAreOneLine) {
  const TempDir dir;
  auto missing = runLfcam({"calibrate", (dir / "none.png").string(), "-o", (dir / "g.json").string()}, dir.path());
  EXPECT_EQ(missing.exitStatus, 1);
  EXPECT_EQ(missing.errLines(), 1) << missing.err;
  EXPECT_NE(missing.err.find("none.png"), std::string::npos);
  Image flat(64, 64, 1);
  ASSERT_TRUE(writeImage(dir / "flat.png", flat).ok());
  auto badBayer = runLfcam(
      {"calibrate", (dir / "flat.png").string(), "--bayer", "XYZ", "-o", (dir / "g.json").string()}, dir.path());
  EXPECT_EQ(badBayer.exitStatus, 2);
  EXPECT_EQ(badBayer.errLines(), 1) << badBayer.err;
  auto noLattice = runLfcam({"calibrate", (dir / "flat.png").string(), "-o", (dir / "g.json").string()}, dir.path());
  EXPECT_EQ(noLattice.exitStatus, 1);
  EXPECT_EQ(noLattice.errLines(), 1) << noLattice.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "g.json"));
}

}  // namespace
}  // namespace lfcam::test
