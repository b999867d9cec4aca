// `lfcam depth` and `lfcam edof` run as a user runs them: outputs, messages, exit statuses.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "lfcam/image_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;


TEST(CliDepth, WritesDisparityConfidencePictureAndDistance) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const auto result = runLfcam({"depth", input.string(), "-o", (dir / "d.pfm").string(), "--confidence",
                                (dir / "c.pfm").string(), "--png", (dir / "d.png").string(), "--distance",
                                (dir / "z.exr").string()},
                               dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << result.err;
  for (const char* name : {"d.pfm", "c.pfm", "d.png", "z.exr"}) {
    auto header = readImageHeader(dir / name);
    ASSERT_TRUE(header) << name << ": " << header.error().message;
    EXPECT_EQ(header->width, 48) << name;
    EXPECT_EQ(header->channels, std::string(name) == "d.png" ? 3 : 1) << name;
  }
  // Disparities within the synthetic scene's range, distances positive.
  auto disparity = readImage(dir / "d.pfm");
  auto distance = readImage(dir / "z.exr");
  ASSERT_TRUE(disparity && distance);
  for (float d : disparity->pixels()) ASSERT_TRUE(d >= -1.0f && d <= 1.6f) << d;
  for (float z : distance->pixels()) ASSERT_GT(z, 0.0f);
}

TEST(CliEdof, WithAndWithoutADepthMap) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  ASSERT_EQ(runLfcam({"depth", input.string(), "-o", (dir / "d.pfm").string()}, dir.path()).exitStatus, 0);
  for (const bool withDepth : {false, true}) {
    std::vector<std::string> args{"edof", input.string(), "-o", (dir / "all.png").string(), "--slices-png",
                                  (dir / "slices.png").string()};
    if (withDepth) args.insert(args.end(), {"--depth", (dir / "d.pfm").string()});
    const auto result = runLfcam(args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    auto header = readImageHeader(dir / "all.png");
    ASSERT_TRUE(header);
    EXPECT_EQ(header->width, 48);
    EXPECT_EQ(header->channels, 3);
    EXPECT_TRUE(fs::exists(dir / "slices.png"));
  }
}

TEST(CliDepth, ErrorsSayWhatIsWrongInOneLine) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  struct Case {
    std::vector<std::string> args;
    int status;
  } cases[] = {
      {{"depth", input.string()}, 2},                                                             // no output
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--min", "1", "--max", "1"}, 2},  // empty range
      {{"depth", (dir / "missing.lf.h5").string(), "-o", (dir / "d.pfm").string()}, 1},
      {{"edof", input.string(), "-o", (dir / "e.png").string(), "--depth", (dir / "missing.pfm").string()}, 1},
      {{"edof", input.string(), "-o", (dir / "e.png").string(), "--step", "-1"}, 2},
  };
  for (const Case& c : cases) {
    const auto result = runLfcam(c.args, dir.path());
    EXPECT_EQ(result.exitStatus, c.status) << testing::PrintToString(c.args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(c.args) << ": " << result.err;
  }
  EXPECT_FALSE(fs::exists(dir / "d.pfm"));
  EXPECT_FALSE(fs::exists(dir / "e.png"));
}

}  // namespace
}  // namespace lfcam
