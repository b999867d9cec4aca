// lfcam simulate, run as a user runs it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

TEST(CliSimulate, WritesEveryOutputOfABuiltinScene) {
  test::TempDir dir;
  const auto result =
      runLfcam({"simulate", "chart", "-o", (dir / "capture").string(), "--size", "160", "--samples", "4"}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  for (const char* name : {"raw.png", "white.png", "camera.json", "depth.pfm", "ideal.lf.h5"})
    EXPECT_TRUE(fs::exists(dir / "capture" / name)) << name;
  // The ideal light field is a light field lfcam reads.
  const auto info = runLfcam({"info", (dir / "capture" / "ideal.lf.h5").string(), "--json"}, dir.path());
  ASSERT_EQ(info.exitStatus, 0) << info.err;
  EXPECT_GT(nlohmann::json::parse(info.out)["angular"][0].get<int>(), 4);
}

TEST(CliSimulate, BadSceneFilesFailWithOneLineNamingTheKey) {
  test::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"not json at all", "bad.json"},
      {R"({"camera": {"sensor": {"width": "wide"}}})", "width"},
      {R"({"objects": [{"type": "plane", "distance_mm": -5}]})", "bad.json"},
  };
  for (const auto& [text, mentioned] : scenes) {
    test::writeBytes(dir / "bad.json", text);
    const auto result = runLfcam({"simulate", (dir / "bad.json").string(), "-o", (dir / "out").string()}, dir.path());
    EXPECT_EQ(result.signal, 0) << text;
    EXPECT_TRUE(result.exitStatus == 1 || result.exitStatus == 2) << text << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << text << ": " << result.err;
    EXPECT_NE(result.err.find(mentioned), std::string::npos) << text << ": " << result.err;
    EXPECT_FALSE(fs::exists(dir / "out")) << text;
  }
  const auto unknown = runLfcam({"simulate", "no-such-scene", "-o", (dir / "out").string()}, dir.path());
  EXPECT_NE(unknown.exitStatus, 0);
  EXPECT_EQ(unknown.errLines(), 1) << unknown.err;
}

}  // namespace
}  // namespace lfcam
