// The lfcam command line, run as a user runs it: outputs, --json, exit statuses.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

TEST(Cli, HelpForEverySubcommand) {
  test::TempDir dir;
  for (const char* sub : {"info", "convert", "views", "refocus", "stack", "observer", "animate", "bench", "depth",
                          "edof", "synth", "simulate", "demo"}) {
    const auto result = runLfcam({sub, "--help"}, dir.path());
    EXPECT_EQ(result.exitStatus, 0) << sub;
    EXPECT_NE(result.out.find("Usage"), std::string::npos) << sub;
  }
  EXPECT_EQ(runLfcam({"--help"}, dir.path()).exitStatus, 0);
}

TEST(Cli, UsageErrorsExitTwoWithOneLine) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const std::vector<std::vector<std::string>> cases = {
      {"frobnicate"},
      {"info", input.string(), "--no-such-flag"},
      {"refocus", input.string(), "-o", (dir / "a.png").string()},  // no depth
      {"refocus", input.string(), "--slope", "1", "--alpha", "1.1", "-o", (dir / "a.png").string()},
      {"refocus", input.string(), "--slope", "abc", "-o", (dir / "a.png").string()},
      {"synth", "--views", "0", "-o", (dir / "b.lf.h5").string()},
  };
  for (const auto& args : cases) {
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << testing::PrintToString(args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(args) << ": " << result.err;
  }
  EXPECT_FALSE(fs::exists(dir / "a.png"));
  EXPECT_FALSE(fs::exists(dir / "b.lf.h5"));
}

TEST(Cli, InfoJsonDescribesTheLightField) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const auto result = runLfcam({"info", input.string(), "--json"}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["angular"], nlohmann::json::array({5, 5}));
  EXPECT_EQ(json["spatial"], nlohmann::json::array({48, 48}));
  EXPECT_EQ(json["channels"], 3);
  EXPECT_TRUE(json.contains("optics"));
  const auto text = runLfcam({"info", input.string()}, dir.path());
  EXPECT_EQ(text.exitStatus, 0);
  EXPECT_NE(text.out.find("5 x 5 views"), std::string::npos) << text.out;
}

TEST(Cli, SynthTakesOneSizeOrWidthAndHeight) {
  test::TempDir dir;
  const std::string output = (dir / "wide.lf.h5").string();
  const auto made = runLfcam({"synth", "--views", "3", "--size", "40", "24", "-o", output}, dir.path());
  ASSERT_EQ(made.exitStatus, 0) << made.err;
  const auto json = nlohmann::json::parse(runLfcam({"info", output, "--json"}, dir.path()).out);
  EXPECT_EQ(json["spatial"], nlohmann::json::array({40, 24}));
  const auto tooMany = runLfcam({"synth", "--size", "40", "24", "8", "-o", output}, dir.path());
  EXPECT_EQ(tooMany.exitStatus, 2) << tooMany.err;
}

TEST(Cli, ConvertThroughEveryFormatKeepsTheShape) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const std::vector<std::vector<std::string>> targets = {
      {(dir / "hci").string()},         {(dir / "rowcol").string(), "--layout", "rowcol"},
      {(dir / "lenslet.png").string()}, {(dir / "lenslet16.tif").string()},
      {(dir / "again.lf.h5").string()},
  };
  for (const auto& target : targets) {
    std::vector<std::string> args = {"convert", input.string(), "-o"};
    args.insert(args.end(), target.begin(), target.end());
    const auto converted = runLfcam(args, dir.path());
    ASSERT_EQ(converted.exitStatus, 0) << target[0] << ": " << converted.err;
    const auto info = runLfcam({"info", target[0], "--json"}, dir.path());
    ASSERT_EQ(info.exitStatus, 0) << target[0] << ": " << info.err;
    const auto json = nlohmann::json::parse(info.out);
    EXPECT_EQ(json["angular"], nlohmann::json::array({5, 5})) << target[0];
    EXPECT_EQ(json["spatial"], nlohmann::json::array({48, 48})) << target[0];
  }
  EXPECT_EQ(nlohmann::json::parse(runLfcam({"info", (dir / "hci").string(), "--json"}, dir.path()).out)["format"],
            "hci-folder");
  EXPECT_EQ(nlohmann::json::parse(runLfcam({"info", (dir / "rowcol").string(), "--json"}, dir.path()).out)["format"],
            "rowcol-folder");
}

TEST(Cli, ViewsWritesEveryViewAndAContactSheet) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  const auto result = runLfcam(
      {"views", input.string(), "-o", (dir / "views").string(), "--mosaic", (dir / "sheet.png").string()}, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  int pngs = 0;
  for (const auto& entry : fs::directory_iterator(dir / "views")) pngs += entry.path().extension() == ".png";
  EXPECT_EQ(pngs, 25);
  EXPECT_TRUE(fs::exists(dir / "views" / "view_03_03.png"));
  auto sheet = readImageHeader(dir / "sheet.png");
  ASSERT_TRUE(sheet) << sheet.error().message;
  EXPECT_GE(sheet->width, 5 * 48);
}

TEST(Cli, RefocusBySlopeAndByAlpha) {
  test::TempDir dir;
  const fs::path input = test::makeSynthLightField(dir);
  auto bySlope = runLfcam({"refocus", input.string(), "--slope", "0.8", "-o", (dir / "s.png").string()}, dir.path());
  ASSERT_EQ(bySlope.exitStatus, 0) << bySlope.err;
  auto image = readImage(dir / "s.png");
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->width(), 48);
  // The synthetic light field carries optics, so alpha converts to a slope.
  auto byAlpha = runLfcam({"refocus", input.string(), "--alpha", "1.02", "-o", (dir / "a.exr").string()}, dir.path());
  EXPECT_EQ(byAlpha.exitStatus, 0) << byAlpha.err;
  EXPECT_TRUE(fs::exists(dir / "a.exr"));
  // A row/column folder of views has no optics (an HCI folder keeps them in parameters.cfg):
  // --alpha is a usage error that says why.
  ASSERT_EQ(runLfcam({"convert", input.string(), "--layout", "rowcol", "-o", (dir / "rowcol").string()}, dir.path())
                .exitStatus,
            0);
  auto noOptics =
      runLfcam({"refocus", (dir / "rowcol").string(), "--alpha", "1.02", "-o", (dir / "b.png").string()}, dir.path());
  EXPECT_EQ(noOptics.exitStatus, 2);
  EXPECT_NE(noOptics.err.find("optics"), std::string::npos) << noOptics.err;
  EXPECT_FALSE(fs::exists(dir / "b.png"));
}

// The example of `lfcam demo --help`, run: it writes a page and every picture the page shows.
TEST(Cli, DemoExampleWritesAPageAndItsPictures) {
  test::TempDir dir;
  const auto words = test::helpExample("demo", dir);
  ASSERT_EQ(words.size(), 4u);
  ASSERT_EQ(words[2], "-o");
  const fs::path out = dir / words[3];
  const auto result = test::runExample(words, dir);
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  const std::string page = test::readBytes(out / "index.html");
  ASSERT_FALSE(page.empty());
  // Every picture the page shows exists.
  std::size_t at = 0;
  int pictures = 0;
  while ((at = page.find("src=\"", at)) != std::string::npos) {
    at += 5;
    const std::string name = page.substr(at, page.find('"', at) - at);
    EXPECT_TRUE(fs::exists(out / name)) << name;
    ++pictures;
  }
  EXPECT_GE(pictures, 5);
  EXPECT_TRUE(fs::exists(out / "lightfield.lf.h5"));
}

}  // namespace
}  // namespace lfcam
