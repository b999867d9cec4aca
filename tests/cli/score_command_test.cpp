// `lfcam score` as a user runs it: the benchmark's scores of a disparity map, as text and JSON,
// and one-line errors for inputs that cannot be scored.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

Image disparityImage(int width, int height, double offsetRightHalf) {
  Image image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y, 0) = float(0.01 * x + (x >= width / 2 ? offsetRightHalf : 0.0));
  return image;
}

TEST(CliScore, PrintsTheBenchmarkScoresAsTextAndJson) {
  test::TempDir dir;
  // Truth a slanted plane; the estimate 0.05 too far on the right half: BadPix(0.03) 50 %, (0.07) 0.
  ASSERT_TRUE(writeImage(dir / "truth.pfm", disparityImage(64, 64, 0.0)));
  ASSERT_TRUE(writeImage(dir / "estimate.pfm", disparityImage(64, 64, -0.05)));
  const std::string estimate = (dir / "estimate.pfm").string(), truth = (dir / "truth.pfm").string();
  const auto text = runLfcam({"score", estimate, truth, "--border", "0"}, dir.path());
  ASSERT_EQ(text.exitStatus, 0) << text.err;
  EXPECT_NE(text.out.find("BadPix(0.03)    50.00 %"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("BadPix(0.07)     0.00 %"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Bumpiness"), std::string::npos) << text.out;

  const auto json = runLfcam({"score", estimate, truth, "--json"}, dir.path());
  ASSERT_EQ(json.exitStatus, 0) << json.err;
  const auto scores = nlohmann::json::parse(json.out);
  EXPECT_DOUBLE_EQ(scores["badpix_0.01"].get<double>(), 100.0 * 17 / 34);  // 34 columns inside the border
  EXPECT_NEAR(scores["mse_x100"].get<double>(), 100.0 * 0.05 * 0.05 * 17 / 34, 1e-4);
  EXPECT_GT(scores["bumpiness"].get<double>(), 0.0) << "the step of the error is bumpy";
  EXPECT_EQ(scores["pixels"].get<long>(), 34 * 34);

  // More thresholds: the error 0.05 on the right half is bad at 0.04, not at 0.06.
  const auto more =
      runLfcam({"score", estimate, truth, "--border", "0", "--badpix", "0.04", "--badpix", "0.06"}, dir.path());
  ASSERT_EQ(more.exitStatus, 0) << more.err;
  EXPECT_NE(more.out.find("BadPix(0.04)    50.00 %"), std::string::npos) << more.out;
  EXPECT_NE(more.out.find("BadPix(0.06)     0.00 %"), std::string::npos) << more.out;
  EXPECT_NE(more.out.find("BadPix(0.07)     0.00 %"), std::string::npos) << more.out;
  const auto moreJson = runLfcam({"score", estimate, truth, "--badpix", "0.035", "--json"}, dir.path());
  ASSERT_EQ(moreJson.exitStatus, 0) << moreJson.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(moreJson.out)["badpix_0.035"].get<double>(), 50.0) << moreJson.out;

  // A mask of planes away from the error's step: no bumpiness.
  Image planes(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) planes.at(x, y, 0) = x < 24 ? 1.0f : 0.0f;
  ASSERT_TRUE(writeImage(dir / "planes.png", planes));
  const auto masked =
      runLfcam({"score", estimate, truth, "--mask", (dir / "planes.png").string(), "--json"}, dir.path());
  ASSERT_EQ(masked.exitStatus, 0) << masked.err;
  EXPECT_NEAR(nlohmann::json::parse(masked.out)["bumpiness"].get<double>(), 0.0, 1e-6);
}

TEST(CliScore, ErrorsNameTheFileInOneLine) {
  test::TempDir dir;
  ASSERT_TRUE(writeImage(dir / "truth.pfm", disparityImage(64, 64, 0.0)));
  ASSERT_TRUE(writeImage(dir / "small.pfm", disparityImage(32, 64, 0.0)));
  ASSERT_TRUE(writeImage(dir / "colour.png", Image(64, 64, 3)));
  const auto at = [&](const char* name) { return (dir / name).string(); };
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string names;
  } cases[] = {
      {{"score", at("small.pfm"), at("truth.pfm")}, 2, "truth.pfm"},                             // another size
      {{"score", at("missing.pfm"), at("truth.pfm")}, 1, "missing.pfm"},                         // unreadable
      {{"score", at("colour.png"), at("truth.pfm")}, 2, "colour.png"},                           // not one channel
      {{"score", at("truth.pfm"), at("truth.pfm"), "--mask", at("small.pfm")}, 2, "small.pfm"},  // mask's size
      {{"score", at("truth.pfm")}, 2, "truth"},                                                  // no ground truth
      {{"score", at("truth.pfm"), at("truth.pfm"), "--badpix", "0"}, 2, "--badpix"},             // no threshold
  };
  for (const Case& c : cases) {
    const auto result = runLfcam(c.args, dir.path());
    EXPECT_EQ(result.exitStatus, c.status) << testing::PrintToString(c.args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(c.args) << ": " << result.err;
    EXPECT_NE(result.err.find(c.names), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
  }
}

}  // namespace
}  // namespace lfcam
