// The rendering commands run as a user runs them: refocus with apertures, methods and
// --focus-at; stack; observer; their usage errors (exit 2, one line). (--help of every
// subcommand: commands_test.cpp.)
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/animation.hpp"
#include "random_light_field.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

TEST(CliRender, RefocusWithApertureMethodAndFocusAt) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const std::vector<std::vector<std::string>> cases = {
      {"--slope", "0.5", "--aperture", "1", "--aperture-centre", "0.5,-0.5"},
      {"--slope", "1.5", "--aperture", "0.5", "--aperture-shape", "square", "--method", "quadrature"},
      {"--alpha", "1.05", "--beta", "1.1"},
      {"--focus-at", "10,12"},
      {"--focus-plane", "5,5:35,8:20,34"},
      {"--slope", "0.5", "--tilt", "1", "--tilt-direction", "45"},
  };
  for (const auto& extra : cases) {
    std::vector<std::string> args{"refocus", input, "-o", (dir / "out.png").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = runLfcam(args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << testing::PrintToString(extra) << ": " << result.err;
    auto photo = readImage(dir / "out.png");
    ASSERT_TRUE(photo) << photo.error().message;
    EXPECT_EQ(photo->width(), 40);
    fs::remove(dir / "out.png");
  }
  // --focus-at prints the slope it chose.
  const auto result = runLfcam({"refocus", input, "--focus-at", "10,12", "-o", (dir / "f.png").string()}, dir.path());
  EXPECT_EQ(result.out.rfind("slope ", 0), 0u) << result.out;
  // --focus-plane prints the plane it chose.
  const auto plane =
      runLfcam({"refocus", input, "--focus-plane", "5,5:35,8:20,34", "-o", (dir / "p.png").string()}, dir.path());
  EXPECT_EQ(plane.out.rfind("focus plane: slope ", 0), 0u) << plane.out;
}

TEST(CliRender, RefocusUpsampledIsKTimesLarger) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  for (int factor : {1, 2, 3}) {
    const fs::path out = dir / ("up" + std::to_string(factor) + ".png");
    const auto result = runLfcam(
        {"refocus", input, "--slope", "0.5", "--upsample", std::to_string(factor), "-o", out.string()}, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    auto photo = readImage(out);
    ASSERT_TRUE(photo) << photo.error().message;
    EXPECT_EQ(photo->width(), 40 * factor);
    EXPECT_EQ(photo->height(), 40 * factor);
  }
}

// --focus-range: a synth capture's near card sharp together with a farther one, from the exact
// disparity map (--depth) or one estimated on the way; in millimetres through the capture's optics.
TEST(CliRender, RefocusFocusRangeInSlopesAndMillimetres) {
  test::TempDir dir;
  const std::string input = (dir / "cards.lf.h5").string(), truth = (dir / "truth.pfm").string();
  ASSERT_EQ(
      runLfcam({"synth", "--views", "5", "--size", "48", "-o", input, "--disparity", truth}, dir.path()).exitStatus, 0);
  auto run = [&](std::vector<std::string> extra, const std::string& name) {
    std::vector<std::string> args{"refocus", input, "-o", (dir / name).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 0) << testing::PrintToString(extra) << ": " << result.err;
    return readImage(dir / name);
  };
  auto exact = run({"--focus-range", "1.6:0.8", "--depth", truth, "--bit-depth", "float"}, "exact.tif");
  auto estimated = run({"--focus-range", "1.6:0.8", "--bit-depth", "float"}, "estimated.tif");
  auto near = run({"--slope", "1.6", "--bit-depth", "float"}, "near.tif");
  ASSERT_TRUE(exact && estimated && near);
  auto disparity = readImage(truth);
  ASSERT_TRUE(disparity);
  // On the near card (truth 1.6), away from its edges, the range renders it as focused on it.
  double worst = 0;
  int inside = 0;
  for (int y = 3; y < 45; ++y)
    for (int x = 3; x < 45; ++x) {
      bool interior = true;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) interior = interior && disparity->at(x + dx, y + dy, 0) > 1.5f;
      if (!interior) continue;
      ++inside;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(exact->at(x, y, c) - near->at(x, y, c))));
    }
  EXPECT_GT(inside, 20);
  EXPECT_LT(worst, 1e-4);
  EXPECT_EQ(estimated->width(), 48);
  // In millimetres: the same range through the synth capture's optics.
  auto millimetres = run({"--focus-range", "900mm:4000mm"}, "mm.png");
  EXPECT_TRUE(millimetres);
}

TEST(CliRender, ApertureMaskOfOneViewGivesThatView) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  Image mask(5, 5, 1);
  mask.at(4, 2, 0) = 1;  // the view right of the centre
  ASSERT_TRUE(writeImage(dir / "mask.png", mask));
  const auto result = runLfcam({"refocus", input, "--slope", "0", "--aperture-mask", (dir / "mask.png").string(), "-o",
                                (dir / "out.exr").string()},
                               dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  auto photo = readImage(dir / "out.exr");
  auto lightField = readLightField(input);
  ASSERT_TRUE(photo && lightField);
  const Image view = lightField->subApertureImage(4, 2);
  for (std::size_t i = 0; i < view.pixels().size(); ++i) ASSERT_NEAR(photo->pixels()[i], view.pixels()[i], 1e-6);
}

TEST(CliRender, StackWritesOneSlicePerDepthAndAnIndex) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const auto result = runLfcam({"stack", input, "--slopes", "-1:1:3", "-o", (dir / "stack").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  for (const char* name : {"slice_000.png", "slice_001.png", "slice_002.png", "stack.json"})
    EXPECT_TRUE(fs::exists(dir / "stack" / name)) << name;
  const auto index = nlohmann::json::parse(test::readBytes(dir / "stack" / "stack.json"));
  ASSERT_EQ(index["slices"].size(), 3u);
  EXPECT_DOUBLE_EQ(double(index["slices"][2]["slope"]), 1.0);
  EXPECT_TRUE(index["slices"][0].contains("alpha"));  // synth light fields carry optics
}

TEST(CliRender, ObserverAtAViewIsThatView) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  auto lightField = readLightField(input);
  ASSERT_TRUE(lightField);
  const auto result =
      runLfcam({"observer", input, "--u", "-2", "--v", "1", "-o", (dir / "o.exr").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  auto photo = readImage(dir / "o.exr");
  ASSERT_TRUE(photo);
  const Image view = lightField->subApertureImage(0, 3);
  for (std::size_t i = 0; i < view.pixels().size(); ++i) ASSERT_NEAR(photo->pixels()[i], view.pixels()[i], 1e-6);
  EXPECT_EQ(
      runLfcam({"observer", input, "--u", "9", "--v", "0", "--clamp", "--beta", "1.2", "-o", (dir / "c.png").string()},
               dir.path())
          .exitStatus,
      0);
}

TEST(CliRender, FourierMethodAndBenchJson) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const auto fourier =
      runLfcam({"stack", input, "--slopes", "-1:1:2", "--method", "fourier", "-o", (dir / "f").string()}, dir.path());
  ASSERT_EQ(fourier.exitStatus, 0) << fourier.err;
  EXPECT_TRUE(fs::exists(dir / "f" / "slice_001.png"));
  const auto bench = runLfcam({"bench", input, "--repeat", "1", "--json"}, dir.path());
  ASSERT_EQ(bench.exitStatus, 0) << bench.err;
  const auto json = nlohmann::json::parse(bench.out);
  ASSERT_TRUE(json.is_array());
  std::vector<std::string> methods;
  for (const auto& entry : json) {
    methods.push_back(entry["method"]);
    for (const char* key : {"seconds_per_photo", "floor_seconds", "ratio_to_floor"})
      EXPECT_GT(double(entry[key]), 0.0) << entry.dump();
  }
  EXPECT_EQ(methods,
            (std::vector<std::string>{"fast", "fast-aperture", "quadrature", "observer", "fourier", "fast-1-thread"}));
}

// Frames in a GIF: one graphic control extension (21 F9 04) precedes each.
int gifFrames(const std::string& bytes) {
  int frames = 0;
  for (std::size_t at = bytes.find("\x21\xF9\x04"); at != std::string::npos; at = bytes.find("\x21\xF9\x04", at + 1))
    ++frames;
  return frames;
}

TEST(CliRender, AnimateWritesLoopingGifs) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const auto pull =
      runLfcam({"animate", input, "--focus-pull", "--frames", "6", "-o", (dir / "p.gif").string()}, dir.path());
  ASSERT_EQ(pull.exitStatus, 0) << pull.err;
  const std::string pullBytes = test::readBytes(dir / "p.gif");
  EXPECT_EQ(pullBytes.rfind("GIF89a", 0), 0u);
  EXPECT_EQ(gifFrames(pullBytes), 6);
  const auto orbit =
      runLfcam({"animate", input, "--orbit", "--frames", "5", "-o", (dir / "o.gif").string()}, dir.path());
  ASSERT_EQ(orbit.exitStatus, 0) << orbit.err;
  EXPECT_EQ(gifFrames(test::readBytes(dir / "o.gif")), 5);
}

TEST(CliRender, AnimateWritesMp4WhenAsked) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const auto orbit =
      runLfcam({"animate", input, "--orbit", "--frames", "5", "-o", (dir / "o.mp4").string()}, dir.path());
  ASSERT_EQ(orbit.exitStatus, 0) << orbit.err;
  auto video = readVideoSummary(dir / "o.mp4");
  ASSERT_TRUE(video) << video.error().message;
  EXPECT_EQ(video->frames, 5);
  EXPECT_EQ(video->width, 40);
  EXPECT_EQ(video->height, 40);
  // An output folder that does not exist: failed work, one line, no file.
  const fs::path bad = dir / "missing" / "o.mp4";
  const auto failed = runLfcam({"animate", input, "--orbit", "--frames", "3", "-o", bad.string()}, dir.path());
  EXPECT_EQ(failed.exitStatus, 1) << failed.err;
  EXPECT_EQ(failed.errLines(), 1) << failed.err;
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

TEST(CliRender, UsageErrorsExitTwoWithOneLine) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const std::string out = (dir / "x.png").string();
  const std::vector<std::vector<std::string>> cases = {
      {"refocus", input, "--no-such-flag", "1", "-o", out},
      {"stack", input, "-o", (dir / "s").string()},
      {"stack", input, "--slopes", "1:2", "-o", (dir / "s").string()},
      {"stack", input, "--slopes", "0:1:2", "--alphas", "1:2:2", "-o", (dir / "s").string()},
      {"observer", input, "--u", "1", "-o", out},
      {"stack", input, "--slopes", "0:1:2", "--tilt", "1", "-o", (dir / "s").string()},
      {"stack", input, "--slopes", "0:1:2", "--upsample", "2", "-o", (dir / "s").string()},
      {"bench", input, "--repeat", "0"},
      {"animate", input, "-o", (dir / "a.gif").string()},
      {"animate", input, "--orbit", "-o", (dir / "a.avi").string()},
      {"animate", input, "--orbit", "--focus-pull", "-o", (dir / "a.gif").string()},
  };
  for (const auto& args : cases) {
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << testing::PrintToString(args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(args) << ": " << result.err;
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "s"));
  // A missing mask is failed work, not usage.
  const auto missing = runLfcam(
      {"refocus", input, "--slope", "0", "--aperture-mask", (dir / "none.png").string(), "-o", out}, dir.path());
  EXPECT_EQ(missing.exitStatus, 1) << missing.err;
  EXPECT_EQ(missing.errLines(), 1);
}

// The requests of the shared table (tests/photo_request/refusals.json), as flags: exit 2, the
// table's line, no output. Python and the viewer are held to the same lines.
TEST(CliRender, TheTableOfRefusalsIsRefusedWithItsLine) {
  test::TempDir dir;
  // The table's light field: 5x5 views of 40x40, no optics.
  std::mt19937 random(1);
  const std::string input = (dir / "plain.lf.h5").string();
  ASSERT_TRUE(writeLightField(
                  input, test::randomLightField({.nu = 5, .nv = 5, .ns = 40, .nt = 40, .channels = 1}, random, false))
                  .ok());
  const std::string out = (dir / "x.png").string();
  std::ifstream in(LFCAM_PHOTO_REFUSALS);
  ASSERT_TRUE(in) << LFCAM_PHOTO_REFUSALS;
  const nlohmann::json table = nlohmann::json::parse(in);
  for (const auto& entry : table.at("cases")) {
    std::vector<std::string> args{"refocus", input, "-o", out};
    for (const auto& [name, text] : entry.at("fields").items()) {
      args.push_back("--" + name);
      args.push_back(text.get<std::string>());
    }
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << testing::PrintToString(args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find(entry.at("message").get<std::string>()), std::string::npos) << result.err;
  }
  EXPECT_FALSE(fs::exists(out));
  // The refusals that need a file (not viewer parameters): a mask of other proportions than the
  // lens, a depth map of another size; Python's test gives its arrays the same lines.
  ASSERT_TRUE(writeImage(dir / "mask.png", Image(64, 32, 1)).ok());
  ASSERT_TRUE(writeImage(dir / "depth.pfm", Image(10, 10, 1)).ok());
  const std::vector<std::pair<std::vector<std::string>, std::string>> files = {
      {{"--slope", "1", "--aperture-mask", (dir / "mask.png").string()},
       "aperture-mask: the mask is 64x32 pixels, the lens 5x5 views: it must have the lens's proportions"},
      {{"--focus-range", "1:0", "--depth", (dir / "depth.pfm").string()},
       "depth: focus spread: the disparity map is 10x10x1, the views 40x40 (one channel needed)"},
  };
  for (const auto& [extra, message] : files) {
    std::vector<std::string> args{"refocus", input, "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << result.err;
    EXPECT_EQ(result.err, "lfcam: " + message + "\n");
  }
  EXPECT_FALSE(fs::exists(out));
}

// Combinations the command once refused render now: a tilt or a range through a stopped-down
// aperture, a tilt on a finer grid, an observer on a tilted plane.
TEST(CliRender, EveryCombinationOfFocusApertureAndGridRenders) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 40).string();
  const std::vector<std::vector<std::string>> cases = {
      {"--focus-plane", "5,5:35,8:20,34", "--aperture", "1"},
      {"--slope", "0.5", "--tilt", "1", "--aperture", "1.5", "--aperture-centre", "0.5,0"},
      {"--slope", "0.5", "--tilt", "1", "--upsample", "2"},
      {"--slope", "0.5", "--upsample", "2", "--f-number", "2"},
      {"--focus-range", "1.5:0.5", "--aperture", "1"},
      {"--slope", "0.2", "--tilt", "1", "--aperture", "0", "--aperture-centre", "3,0", "--clamp"},
  };
  for (const auto& extra : cases) {
    std::vector<std::string> args{"refocus", input, "-o", (dir / "c.png").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 0) << testing::PrintToString(args) << ": " << result.err;
    EXPECT_TRUE(fs::exists(dir / "c.png"));
    fs::remove(dir / "c.png");
  }
}

}  // namespace
}  // namespace lfcam
