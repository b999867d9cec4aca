// `lfcam info` and `lfcam extract` on Lytro containers (the real processed files when present),
// `lfcam simulate --container`, and damaged containers: one line, exit 1, no output folder.
#include <gtest/gtest.h>

#include "cli/cli_support.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/lytro_container.hpp"

namespace lfcam {
namespace {

using test::runLfcam;

TEST(RawIoCommands, InfoListsRealContainers) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-lfp", data);
  test::TempDir dir;
  auto result = runLfcam({"info", (data / "IMG_0001-stk.lfp").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_NE(result.out.find("15 sections"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("refocus-stack slice (JPEG), 1080 x 1080"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("depth map"), std::string::npos);

  result = runLfcam({"info", (data / "demo.LFP").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_NE(result.out.find("7728 x 5368, 10-bit, GRBG, black 64, white 1023"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("hexagonal, pitch 14.2857 px"), std::string::npos) << result.out;

  result = runLfcam({"info", (data / "IMG_0002-stk.lfp").string(), "--json"}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["format"], "lytro-container");
  EXPECT_EQ(json["summary"]["items"]["h264"], 2);
}

TEST(RawIoCommands, ExtractWritesSlicesStreamsAndDepth) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-lfp", data);
  test::TempDir dir;
  auto result = runLfcam({"extract", (data / "IMG_0001-stk.lfp").string(), "-o", (dir / "stk").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "stk" / "slice_00.jpg"));
  EXPECT_TRUE(std::filesystem::exists(dir / "stk" / "slice_11.jpg"));
  EXPECT_TRUE(std::filesystem::exists(dir / "stk" / "depth.pfm"));
  EXPECT_TRUE(std::filesystem::exists(dir / "stk" / "depth.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "stk" / "metadata.json"));
  EXPECT_EQ(test::readBytes(dir / "stk" / "slice_00.jpg").substr(0, 2), "\xff\xd8");  // JPEG as stored

  result = runLfcam({"extract", (data / "IMG_0002-stk.lfp").string(), "-o", (dir / "h264").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_EQ(test::readBytes(dir / "h264" / "edofParallax_00.h264").substr(0, 4), std::string("\0\0\0\1", 4));
  EXPECT_TRUE(std::filesystem::exists(dir / "h264" / "refocusStack_00.h264"));

  result = runLfcam({"extract", (data / "IMG_0002-dm.lfp").string(), "-o", (dir / "dm").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "dm" / "confidence.pfm"));
  EXPECT_TRUE(std::filesystem::exists(dir / "dm" / "depth.png"));

  result = runLfcam({"extract", (data / "demo.LFP").string(), "-o", (dir / "demo").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  const auto index = nlohmann::json::parse(test::readBytes(dir / "demo" / "index.json"));
  EXPECT_EQ(index["summary"]["frame"]["bayer"], "GRBG");
  EXPECT_TRUE(std::filesystem::exists(dir / "demo" / "slice_09.jpg"));
}

TEST(RawIoCommands, SimulateWritesContainersThatReadBack) {
  test::TempDir dir;
  auto result = runLfcam({"simulate", "chart", "--size", "48", "--samples", "1", "--no-ground-truth", "--hexagonal",
                          "--container", "lfr", "-o", (dir / "cap").string()},
                         dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  auto png = readRaw(dir / "cap" / "raw.png");
  auto lfr = readRaw(dir / "cap" / "raw.lfr");
  ASSERT_TRUE(png && lfr);
  EXPECT_TRUE(std::equal(png->mosaic.pixels().begin(), png->mosaic.pixels().end(), lfr->mosaic.pixels().begin()));
  EXPECT_TRUE(std::filesystem::exists(dir / "cap" / "white.lfr"));
  result = runLfcam({"info", (dir / "cap" / "raw.lfr").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_NE(result.out.find("raw sensor frame"), std::string::npos) << result.out;
  result = runLfcam({"extract", (dir / "cap" / "raw.lfr").string(), "-o", (dir / "x").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "x" / "raw.tiff"));
  EXPECT_TRUE(std::filesystem::exists(dir / "x" / "frame_metadata.json"));
}

TEST(RawIoCommands, DamagedContainersFailInOneLine) {
  test::TempDir dir;
  std::vector<LytroSection> components;
  components.push_back(makeLytroSection(LytroSectionKind::Component, std::string(5000, 'j')));
  const nlohmann::json toc = {{"picture", {{"accelerationArray", {{{"imageRef", components[0].name}}}}}}};
  const auto good = serializeLytroContainer(makeLytroContainer(toc, std::move(components)));
  const std::string bytes(good.begin(), good.end());
  std::string badSha = bytes;
  badSha[bytes.size() - 100] ^= 1;
  std::string wrongMagic = bytes;
  wrongMagic[2] = 'X';
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"truncated.lfp", bytes.substr(0, bytes.size() / 2)}, {"badsha.lfp", badSha}, {"magic.lfp", wrongMagic}};
  for (const auto& [name, content] : cases) {
    test::writeBytes(dir / name, content);
    auto result = runLfcam({"extract", (dir / name).string(), "-o", (dir / "out").string()}, dir.path());
    EXPECT_EQ(result.exitStatus, 1) << name << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_EQ(result.err.rfind("lfcam: " + (dir / name).string() + ": ", 0), 0u) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << name;
    if (name != "magic.lfp") {  // wrong magic: not a container, so info tries other formats
      result = runLfcam({"info", (dir / name).string()}, dir.path());
      EXPECT_EQ(result.exitStatus, 1) << name;
      EXPECT_EQ(result.errLines(), 1) << result.err;
    }
  }
}

}  // namespace
}  // namespace lfcam
