// A focused plenoptic capture through the command line as a user meets it: simulated with its
// RayCalibData beside it, recognised with no flag, and, moved away from its calibration,
// calibrated by `lfcam calibrate --focused` or on the fly with `--focused`.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "focused_camera.hpp"
#include "lfcam/focused/focused_calibration.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

// tests/data/focused_multifocus_scene.json: the Galilean multi-focus camera of
// tests/focused_camera.hpp at 480 x 360 (5.5 um pixels, 50 mm focused at 2 m, microlenses 0.4 mm
// from the sensor, 20 px micro-images, types sharp near v = 3, 4.5 and 7) before a value-noise
// plane at 1 m (v ~ 3.4) and a card at 0.8 m (v ~ 5.1).
const fs::path kScene = fs::path(LFCAM_TEST_DATA_DIR) / "focused_multifocus_scene.json";

class CliFocused : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const auto made = runLfcam(
        {"simulate", kScene.string(), "-o", (*dir_ / "capture").string(), "--samples", "4", "--no-ground-truth"},
        dir_->path());
    ASSERT_EQ(made.exitStatus, 0) << made.err;
    // The same capture with no calibration beside it.
    fs::create_directories(*dir_ / "bare");
    fs::copy_file(*dir_ / "capture" / "raw.png", *dir_ / "bare" / "capture.png");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static nlohmann::json info(const std::vector<std::string>& args) {
    std::vector<std::string> all{"info", "--json"};
    all.insert(all.end(), args.begin(), args.end());
    const auto result = runLfcam(all, dir_->path());
    EXPECT_EQ(result.exitStatus, 0) << result.err;
    return result.exitStatus == 0 ? nlohmann::json::parse(result.out) : nlohmann::json();
  }
  static fs::path at(const std::string& name) { return *dir_ / name; }
  static test::TempDir* dir_;
};
test::TempDir* CliFocused::dir_ = nullptr;

TEST_F(CliFocused, ACaptureWithItsXmlBesideItIsRecognisedWithNoFlag) {
  ASSERT_TRUE(fs::exists(at("capture/raw.xml")));
  const auto json = info({at("capture/raw.png").string()});
  EXPECT_EQ(json["format"], "focused plenoptic capture");
  EXPECT_EQ(json["lens_types"].size(), 3u);
  EXPECT_EQ(json["packing"], "hexagonal");
  const auto text = runLfcam({"info", at("capture/raw.png").string()}, dir_->path());
  EXPECT_NE(text.out.find("focused plenoptic capture (plenoptic 2.0), 3 lens types"), std::string::npos) << text.out;
}

TEST_F(CliFocused, CalibrateWritesARayCalibDataThatMatchesTheCameras) {
  const auto truth = info({at("capture/raw.png").string()});
  for (const bool fromWhite : {true, false}) {
    const fs::path xml = at(fromWhite ? "bare/from-white.xml" : "bare/from-capture.xml");
    std::vector<std::string> args{"calibrate", "--focused", at("bare/capture.png").string(), "-o", xml.string()};
    if (fromWhite) args.insert(args.end(), {"--white", at("capture/white.png").string()});
    const auto result = runLfcam(args, dir_->path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    EXPECT_NE(result.out.find("hexagonal micro-images"), std::string::npos) << result.out;
    const auto found = info({at("bare/capture.png").string(), "--focused-calibration", xml.string()});
    EXPECT_NEAR(found["micro_image_diameter_px"].get<double>(), truth["micro_image_diameter_px"].get<double>(), 0.05)
        << (fromWhite ? "from the white" : "from the capture");
    EXPECT_EQ(found["micro_image_orientation"], "upright");
    auto truthGrid = readFocusedCalibration(at("capture/raw.xml"), 480, 360);
    auto foundGrid = readFocusedCalibration(xml, 480, 360);
    ASSERT_TRUE(truthGrid.ok() && foundGrid.ok());
    // From the simulator's calibration tests: 0.02 px from a white, 0.4 px from a capture.
    const double worst = test::centreErrors(*foundGrid, *truthGrid, truthGrid->diameterPx()).worst;
    std::printf("calibrated from the %s: worst centre error %.3f px\n", fromWhite ? "white" : "capture", worst);
    EXPECT_LT(worst, fromWhite ? 0.1 : 0.6);
    if (fromWhite) {
      EXPECT_EQ(found["lens_types"].size(), 3u);
    }
  }
}

TEST_F(CliFocused, WithFocusedAnUncalibratedCaptureIsCalibratedOnTheFly) {
  const auto json = info({at("bare/capture.png").string(), "--focused", "--white", at("capture/white.png").string()});
  EXPECT_NE(json["calibration"].get<std::string>().find("self-calibrated from the white image"), std::string::npos);
  const fs::path photo = at("bare/total-focus.png");
  const auto edof =
      runLfcam({"edof", at("bare/capture.png").string(), "--focused", "-o", photo.string()}, dir_->path());
  ASSERT_EQ(edof.exitStatus, 0) << edof.err;
  EXPECT_TRUE(fs::exists(photo));
}

TEST_F(CliFocused, ExportHtmlWritesALivingPictureOverItsVirtualDepths) {
  const fs::path page = at("page.html");
  const auto result =
      runLfcam({"export-html", at("capture/raw.png").string(), "--slices", "6", "--frames", "4", "-o", page.string()},
               dir_->path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  const std::string html = test::readBytes(page);
  EXPECT_NE(html.find("a focused plenoptic capture: 6 slices, virtual depth"), std::string::npos);
  // Six slices at virtual depths, a depth position per pixel, a total focus and four viewpoints.
  std::size_t slices = 0;
  for (auto at = html.find("\"virtualDepth\""); at != std::string::npos; at = html.find("\"virtualDepth\"", at + 1))
    ++slices;
  EXPECT_EQ(slices, 6u);
  EXPECT_NE(html.find("\"positions\""), std::string::npos);
  EXPECT_NE(html.find("\"allInFocus\":\"data:image/jpeg;base64,"), std::string::npos);
  EXPECT_NE(html.find("\"sweepUnit\""), std::string::npos);
}

TEST_F(CliFocused, BatchTakesAFolderOfCapturesWithTheirXmlAndTheStepsThatApply) {
  const fs::path inputs = at("batch-in"), out = at("batch-out");
  fs::create_directories(inputs);
  fs::copy_file(at("capture/raw.png"), inputs / "f.png");
  fs::copy_file(at("capture/raw.xml"), inputs / "f.xml");
  const auto result =
      runLfcam({"batch", inputs.string(), "-o", out.string(), "--steps", "edof,depth,page"}, dir_->path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  for (const char* file : {"all-in-focus.png", "depth.pfm", "depth.png", "page.html"})
    EXPECT_TRUE(fs::is_regular_file(out / "f" / file)) << file;
  const auto report = nlohmann::json::parse(test::readBytes(out / "batch-report.json"));
  EXPECT_EQ(report["done"], 1);  // the XML is part of its capture, not one more input
  // A light field's step is refused for it, by name, in the report.
  const auto refocus =
      runLfcam({"batch", inputs.string(), "-o", at("batch-refocus").string(), "--steps", "refocus:0.5"}, dir_->path());
  EXPECT_NE(refocus.exitStatus, 0);
  const auto failed = nlohmann::json::parse(test::readBytes(at("batch-refocus") / "batch-report.json"));
  EXPECT_EQ(failed["failed"], 1);
  EXPECT_NE(failed["captures"][0]["error"].get<std::string>().find("a focused plenoptic capture takes edof"),
            std::string::npos)
      << failed["captures"][0]["error"];
}

TEST_F(CliFocused, DepthGivesDistancesWithTheOpticsTheSimulatorWroteAndRefusesThemWithout) {
  const auto result = runLfcam(
      {"depth", at("capture/raw.png").string(), "-o", at("v.pfm").string(), "--distance", at("distance.pfm").string()},
      dir_->path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  auto distance = readImage(at("distance.pfm"));
  ASSERT_TRUE(distance) << distance.error().message;
  std::vector<float> values(distance->pixels().begin(), distance->pixels().end());
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  // Most of the frame is the plane at 1 m.
  EXPECT_NEAR(values[values.size() / 2], 1000, 100);
  // Calibrated from itself, the capture has no optics: no distance, and nothing written.
  const auto without =
      runLfcam({"depth", at("bare/capture.png").string(), "--focused", "-o", at("bare/v.pfm").string(), "--metric"},
               dir_->path());
  EXPECT_EQ(without.exitStatus, 2) << without.err;
  EXPECT_EQ(without.errLines(), 1) << without.err;
  EXPECT_NE(without.err.find("no optics"), std::string::npos) << without.err;
  EXPECT_FALSE(fs::exists(at("bare/v.pfm")));
}

TEST_F(CliFocused, CalibrateRefusesWhatItCannotDoInOneLine) {
  // Not a calibration's extension: wrong usage, nothing written.
  const auto extension = runLfcam(
      {"calibrate", "--focused", at("bare/capture.png").string(), "-o", at("bare/cal.txt").string()}, dir_->path());
  EXPECT_EQ(extension.exitStatus, 2) << extension.err;
  EXPECT_EQ(extension.errLines(), 1) << extension.err;
  EXPECT_FALSE(fs::exists(at("bare/cal.txt")));
  // A capture that has its calibration beside it is not silently calibrated anew.
  const auto beside = runLfcam(
      {"calibrate", "--focused", at("capture/raw.png").string(), "-o", at("bare/again.xml").string()}, dir_->path());
  EXPECT_EQ(beside.exitStatus, 2) << beside.err;
  EXPECT_EQ(beside.errLines(), 1) << beside.err;
  EXPECT_NE(beside.err.find("raw.xml"), std::string::npos) << beside.err;
  EXPECT_FALSE(fs::exists(at("bare/again.xml")));
}

TEST_F(CliFocused, RefusesBadInputInOneLineNamingTheFileAndWritesNothing) {
  struct Case {
    const char* what;
    std::vector<std::string> args;
    const char* named;  // the file or flag the line names
  };
  std::ofstream(at("bare/not-ray.xml")) << "<?xml version=\"1.0\"?><Settings><Width>480</Width></Settings>\n";
  // A corner of the capture a micro-image and a half across, with the whole capture's calibration.
  auto raw = readImage(at("capture/raw.png"));
  ASSERT_TRUE(raw) << raw.error().message;
  Image tiny(30, 30, raw->channels());
  for (int c = 0; c < tiny.channels(); ++c)
    for (int y = 0; y < tiny.height(); ++y) std::copy_n(raw->row(y, c), tiny.width(), tiny.row(y, c));
  ASSERT_TRUE(writeImage(at("bare/tiny.png"), tiny));
  const std::vector<Case> cases{
      {"an XML that is not a RayCalibData",
       {"edof", at("bare/capture.png").string(), "--focused-calibration", at("bare/not-ray.xml").string(), "-o",
        at("bare/out.png").string()},
       "not-ray.xml"},
      {"patches whose virtual depth leaves holes",
       {"refocus", at("capture/raw.png").string(), "--virtual-depth", "1", "--patches", "-o",
        at("bare/out.png").string()},
       "past the micro-images"},
      {"an image smaller than a few micro-images",
       {"edof", at("bare/tiny.png").string(), "--focused-calibration", at("capture/raw.xml").string(), "-o",
        at("bare/out.png").string()},
       "raw.xml: the image (30x30) is smaller than three micro-images of 20 pixels"},
  };
  for (const Case& c : cases) {
    const auto result = runLfcam(c.args, dir_->path());
    EXPECT_NE(result.exitStatus, 0) << c.what;
    EXPECT_EQ(result.errLines(), 1) << c.what << ": " << result.err;
    EXPECT_NE(result.err.find(c.named), std::string::npos) << c.what << ": " << result.err;
    EXPECT_FALSE(fs::exists(at("bare/out.png"))) << c.what;
  }
}

}  // namespace
}  // namespace lfcam
