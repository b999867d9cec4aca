// lfcam decode, and other commands reading a raw with --white: a small simulator capture decoded
// through the whole command line.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "test_support.hpp"

namespace lfcam::test {
namespace {

TEST(DecodeCommand, DecodesASimulatorCapture) {
  TempDir dir;
  const std::string sim = (dir / "sim").string();
  auto simulate = runLfcam({"simulate", "people", "--size", "160", "--pixels-per-lens", "13.37", "--hexagonal",
                            "--samples", "4", "--noise", "off", "-o", sim},
                           dir.path());
  ASSERT_EQ(simulate.exitStatus, 0) << simulate.err;
  const std::string out = (dir / "out.lf.h5").string();
  auto decode = runLfcam({"decode", sim + "/raw.png", "--white", sim + "/white.png", "--sampling", "integral",
                          "--demosaic", "ha", "-o", out},
                         dir.path());
  ASSERT_EQ(decode.exitStatus, 0) << decode.err;
  auto lf = readLightField(out);
  ASSERT_TRUE(lf.ok());
  auto ideal = readLightField(sim + "/ideal.lf.h5");
  ASSERT_TRUE(ideal.ok());
  EXPECT_EQ(lf->nu(), ideal->nu());
  EXPECT_EQ(lf->channels(), 3);
  EXPECT_TRUE(lf->hasWeight());
  ASSERT_TRUE(lf->metadata.optics.has_value());  // from camera.json
  EXPECT_NEAR(lf->metadata.optics->lensStepMm, ideal->metadata.optics->lensStepMm, 1e-9);

  // Any command takes the raw directly with its white image.
  auto refocus = runLfcam(
      {"refocus", sim + "/raw.png", "--white", sim + "/white.png", "--slope", "0", "-o", (dir / "photo.png").string()},
      dir.path());
  EXPECT_EQ(refocus.exitStatus, 0) << refocus.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "photo.png"));
  // ... with the decoder's method options, as `lfcam decode` takes them.
  auto views = runLfcam({"refocus", sim + "/raw.png", "--white", sim + "/white.png", "--demosaic", "lenslet",
                         "--sampling", "integral", "--slope", "0", "-o", (dir / "photo2.png").string()},
                        dir.path());
  EXPECT_EQ(views.exitStatus, 0) << views.err;
  auto bad = runLfcam({"refocus", sim + "/raw.png", "--white", sim + "/white.png", "--demosaic", "nearest", "--slope",
                       "0", "-o", (dir / "photo3.png").string()},
                      dir.path());
  EXPECT_EQ(bad.exitStatus, 2);
  EXPECT_NE(bad.err.find("--demosaic"), std::string::npos) << bad.err;
}

TEST(DecodeCommand, NamesAWhiteImageOfAnotherSize) {
  TempDir dir;
  const std::string sim = (dir / "sim").string(), other = (dir / "other").string();
  ASSERT_EQ(
      runLfcam({"simulate", "white", "--size", "64", "--samples", "1", "--no-white", "-o", sim}, dir.path()).exitStatus,
      0);
  ASSERT_EQ(runLfcam({"simulate", "white", "--size", "48", "--samples", "1", "--no-white", "-o", other}, dir.path())
                .exitStatus,
            0);
  auto decode = runLfcam(
      {"decode", sim + "/raw.png", "--white", other + "/raw.png", "-o", (dir / "out.lf.h5").string()}, dir.path());
  EXPECT_EQ(decode.exitStatus, 2);
  EXPECT_NE(decode.err.find("lfcam: " + other + "/raw.png: white image of 48x48 pixels does not match"),
            std::string::npos)
      << decode.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.lf.h5"));
}

// Neither grid nor white image: the grid comes from the raw itself, and the light field says so;
// a raw too small to hold a lattice fails in one line naming it.
TEST(DecodeCommand, WithoutGridOrWhiteImageCalibratesFromTheRaw) {
  TempDir dir;
  const std::string sim = (dir / "sim").string(), tiny = (dir / "tiny").string();
  ASSERT_EQ(runLfcam({"simulate", "white", "--size", "160", "--samples", "1", "--no-white", "-o", sim}, dir.path())
                .exitStatus,
            0);
  const std::string out = (dir / "out.lf.h5").string();
  auto decode = runLfcam({"decode", sim + "/raw.png", "-o", out}, dir.path());
  ASSERT_EQ(decode.exitStatus, 0) << decode.err;
  auto info = runLfcam({"info", out}, dir.path());
  ASSERT_EQ(info.exitStatus, 0) << info.err;
  EXPECT_NE(info.out.find("grid self-calibrated from the raw (residual RMS 0.0"), std::string::npos) << info.out;

  ASSERT_EQ(runLfcam({"simulate", "white", "--size", "64", "--samples", "1", "--no-white", "-o", tiny}, dir.path())
                .exitStatus,
            0);
  decode = runLfcam({"decode", tiny + "/raw.png", "-o", (dir / "tiny.lf.h5").string()}, dir.path());
  EXPECT_EQ(decode.exitStatus, 1);
  EXPECT_EQ(decode.err, "lfcam: " + tiny + "/raw.png: too few microlens images found (4) to fit a lattice\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "tiny.lf.h5"));
}

}  // namespace
}  // namespace lfcam::test
