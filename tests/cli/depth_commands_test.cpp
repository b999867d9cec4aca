// `lfcam depth` and `lfcam edof` run as a user runs them: outputs, messages, exit statuses.
#include <gtest/gtest.h>

#include <fstream>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

TEST(CliDepth, WritesDisparityConfidencePictureAndDistance) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const auto result =
      runLfcam({"depth", input.string(), "-o", (dir / "d.pfm").string(), "--confidence", (dir / "c.pfm").string(),
                "--png", (dir / "d.png").string(), "--distance", (dir / "z.exr").string()},
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

// --metric writes millimetres where the disparity was, the same as --distance; --ply a point cloud
// of the sure points; without optics all three are usage errors before any work.
TEST(CliDepth, MetresAndPointCloudWhenTheOpticsAreKnown) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const auto result = runLfcam({"depth", input.string(), "-o", (dir / "z.pfm").string(), "--metric", "--distance",
                                (dir / "same.pfm").string(), "--ply", (dir / "all.ply").string()},
                               dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  auto metric = readImage(dir / "z.pfm");
  auto distance = readImage(dir / "same.pfm");
  ASSERT_TRUE(metric && distance);
  EXPECT_EQ(metric->pixels().size(), distance->pixels().size());
  for (std::size_t i = 0; i < metric->pixels().size(); ++i) ASSERT_EQ(metric->pixels()[i], distance->pixels()[i]);
  for (float z : metric->pixels()) ASSERT_GT(z, 100.0f);  // beyond the synthetic camera's 90 mm focal length
  auto vertices = [](const std::string& ply) {
    const std::size_t at = ply.find("element vertex ");
    return at == std::string::npos ? -1L : std::stol(ply.substr(at + 15));
  };
  const long all = vertices(test::readBytes(dir / "all.ply"));
  EXPECT_GT(all, 48 * 48 / 2);
  ASSERT_EQ(runLfcam({"depth", input.string(), "-o", (dir / "d.pfm").string(), "--ply", (dir / "sure.ply").string(),
                      "--min-confidence", "0.9"},
                     dir.path())
                .exitStatus,
            0);
  EXPECT_LT(vertices(test::readBytes(dir / "sure.ply")), all);

  ASSERT_EQ(runLfcam({"convert", input.string(), "--layout", "rowcol", "-o", (dir / "rowcol").string()}, dir.path())
                .exitStatus,
            0);
  for (const std::vector<std::string>& flags : {std::vector<std::string>{"--metric"}, {"--ply", "x.ply"}}) {
    std::vector<std::string> args{"depth", (dir / "rowcol").string(), "-o", (dir / "n.pfm").string()};
    args.insert(args.end(), flags.begin(), flags.end());
    const auto noOptics = runLfcam(args, dir.path());
    EXPECT_EQ(noOptics.exitStatus, 2) << noOptics.err;
    EXPECT_EQ(noOptics.errLines(), 1) << noOptics.err;
    EXPECT_NE(noOptics.err.find("optics"), std::string::npos) << noOptics.err;
  }
  EXPECT_FALSE(fs::exists(dir / "n.pfm"));
  EXPECT_FALSE(fs::exists(dir / "x.ply"));
}

TEST(CliEdof, WithAndWithoutADepthMap) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  ASSERT_EQ(runLfcam({"depth", input.string(), "-o", (dir / "d.pfm").string()}, dir.path()).exitStatus, 0);
  for (const bool withDepth : {false, true}) {
    std::vector<std::string> args{
        "edof", input.string(), "-o", (dir / "all.png").string(), "--slices-png", (dir / "slices.png").string()};
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

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(CliDepth, EverySettingFromAnOptionsFileOrAFlagThatWins) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const std::string output = (dir / "d.pfm").string();
  // The file's range is empty (2 above the metadata's 1.6): refused, unless a flag gives another min.
  writeText(dir / "empty-range.json", R"({"min": 2, "median-radius": 0, "occlusion-band": 0})");
  const auto refused =
      runLfcam({"depth", input.string(), "-o", output, "--options", (dir / "empty-range.json").string()}, dir.path());
  EXPECT_EQ(refused.exitStatus, 2) << refused.err;
  EXPECT_NE(refused.err.find("is empty"), std::string::npos) << refused.err;
  const auto flagWins =
      runLfcam({"depth", input.string(), "-o", output, "--options", (dir / "empty-range.json").string(), "--min", "-1"},
               dir.path());
  EXPECT_EQ(flagWins.exitStatus, 0) << flagWins.err;
  // Every setting of the table is a flag, shown with its stage in --help.
  const auto help = runLfcam({"depth", "--help"}, dir.path());
  for (const char* flag : {"--labels", "--defocus-weight", "--filter-radius", "--filter-epsilon", "--smoothness",
                           "--refine-steps", "--refine-radius", "--refine-smooth-radius", "--refine-rounds",
                           "--fill-lambda", "--fill-sigma", "--occlusion-band", "--median-radius", "--median-sigma"})
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
}

TEST(CliDepth, ErrorsSayWhatIsWrongInOneLine) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  writeText(dir / "typo.json", R"({"smoothnes": 0.5})");     // an unknown key
  writeText(dir / "bad.json", R"({"median-radius": 2.5})");  // not an integer
  struct Case {
    std::vector<std::string> args;
    int status;
  } cases[] = {
      {{"depth", input.string()}, 2},                                                              // no output
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--min", "1", "--max", "1"}, 2},  // empty range
      {{"depth", (dir / "missing.lf.h5").string(), "-o", (dir / "d.pfm").string()}, 1},
      {{"edof", input.string(), "-o", (dir / "e.png").string(), "--depth", (dir / "missing.pfm").string()}, 1},
      {{"edof", input.string(), "-o", (dir / "e.png").string(), "--step", "-1"}, 2},
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--min", "1", "--max", "0.5"}, 2},  // min above max
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--options", (dir / "typo.json").string()}, 1},
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--options", (dir / "bad.json").string()}, 1},
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--options", (dir / "no.json").string()}, 1},
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--median-radius", "-1"}, 2},
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--ply", (dir / "no" / "c.ply").string()}, 2},
      {{"depth", input.string(), "-o", (dir / "d.pfm").string(), "--ply", "c.ply", "--min-confidence", "2"}, 2},
  };
  for (const Case& c : cases) {
    const auto result = runLfcam(c.args, dir.path());
    EXPECT_EQ(result.exitStatus, c.status) << testing::PrintToString(c.args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(c.args) << ": " << result.err;
  }
  EXPECT_FALSE(fs::exists(dir / "d.pfm"));
  EXPECT_FALSE(fs::exists(dir / "e.png"));
  EXPECT_FALSE(fs::exists(dir / "c.ply"));
}

}  // namespace
}  // namespace lfcam
