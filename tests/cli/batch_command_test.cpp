// `lfcam batch` run as a user runs it: the outputs of every capture, the report, resuming a
// previous run, going on past a bad capture, the spec file, and the usage errors found before any work.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/io/volume_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

// Two small captures, a.lf.h5 and b.lf.h5, in dir/in.
fs::path makeTwoCaptures(const test::TempDir& dir) {
  const fs::path synth = test::makeSynthLightField(dir), folder = dir / "in";
  fs::create_directories(folder);
  fs::copy_file(synth, folder / "a.lf.h5");
  fs::copy_file(synth, folder / "b.lf.h5");
  return folder;
}

nlohmann::json readJson(const fs::path& file) { return nlohmann::json::parse(test::readBytes(file)); }

// A light-field microscope's time series in dir/series: t0, t1, t2.lf.h5, each 7 x 7 views of 6 x 5
// lenslets (volume_command_test.cpp's frame, a spot under each lenslet, brighter at each time).
fs::path makeMicroscopeSeries(const test::TempDir& dir) {
  const fs::path folder = dir / "series";
  fs::create_directories(folder);
  for (int time = 0; time < 3; ++time) {
    LightField frame({.nu = 7, .nv = 7, .ns = 6, .nt = 5, .channels = 1});
    for (int v = 0; v < 7; ++v)
      for (int u = 0; u < 7; ++u)
        for (int t = 0; t < 5; ++t)
          for (int s = 0; s < 6; ++s) frame.at(u, v, s, t, 0) = u == 3 && v == 3 ? 0.6f + 0.1f * time : 0.1f;
    // (path "t" + digits + ".lf.h5" by concat: GCC 12 warns falsely on that string sum, -Wrestrict)
    EXPECT_TRUE(writeLightField((folder / "t").concat(std::to_string(time)).concat(".lf.h5"), frame));
  }
  return folder;
}

// Its microscope (20x/0.5 water, 500 nm, 40 um lenslets of 800 um, 5.714 um pixels: 7 pixels a
// lenslet) as napari-LF's settings, less any key of `without`.
fs::path writeMicroscopeSettings(const test::TempDir& dir, const std::string& without = "") {
  nlohmann::json calibrate{{"objective_magnification", 20},
                           {"objective_na", 0.5},
                           {"medium_index", 1.333},
                           {"center_wavelength", 500},
                           {"ulens_pitch", 40},
                           {"ulens_focal_length", 800},
                           {"pixel_size", 5.714},
                           {"num_slices", 3},
                           {"um_per_slice", 3},
                           {"supersample", 1}};
  calibrate.erase(without);
  const fs::path file = dir / (without.empty() ? "optics.json" : "optics-" + without + ".json");
  test::writeBytes(file, nlohmann::json{{"calibrate", calibrate}, {"deconvolve", {{"max_iter", 2}}}}.dump(2));
  return file;
}

std::vector<fs::path> psfCaches(const fs::path& folder) {
  std::vector<fs::path> caches;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().rfind("lfcam-psf-", 0) == 0) caches.push_back(entry.path());
  return caches;
}

TEST(CliBatch, EveryStepWritesItsFilesPerCaptureAndTheReportSaysSo) {
  test::TempDir dir;
  const fs::path inputs = makeTwoCaptures(dir), out = dir / "out";
  const auto result = runLfcam({"batch", inputs.string(), "-o", out.string(), "--steps",
                                "refocus:0.5,stack:-1:1:3,edof,depth,page", "--jobs", "2"},
                               dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << result.err;
  const std::vector<std::string> files{"refocus_0.5.png",  "stack/slice_000.png", "stack/slice_002.png",
                                       "stack/stack.json", "all-in-focus.png",    "depth.pfm",
                                       "depth.png",        "page.html",           ".batch-done.json"};
  for (const char* capture : {"a", "b"})
    for (const std::string& file : files)
      EXPECT_TRUE(fs::is_regular_file(out / capture / file)) << capture << "/" << file;
  auto photo = readImageHeader(out / "a" / "refocus_0.5.png");
  ASSERT_TRUE(photo) << photo.error().message;
  EXPECT_EQ(photo->width, 48);
  EXPECT_EQ(readJson(out / "a" / "stack" / "stack.json")["slices"].size(), 3u);

  const auto report = readJson(out / "batch-report.json");
  EXPECT_EQ(report["done"], 2);
  EXPECT_EQ(report["failed"], 0);
  ASSERT_EQ(report["captures"].size(), 2u);
  const auto& a = report["captures"][0];
  EXPECT_EQ(a["name"], "a");
  EXPECT_EQ(a["input"], (inputs / "a.lf.h5").string());
  EXPECT_EQ(a["status"], "done");
  EXPECT_TRUE(a["error"].is_null());
  EXPECT_GT(a["seconds"].get<double>(), 0.0);
  EXPECT_EQ(a["outputs"].size(), 9u);  // refocus, stack.json and 3 slices, edof, depth and its picture, page
  EXPECT_EQ(a["outputs"][0], "a/refocus_0.5.png");
}

// A rerun leaves a complete capture alone (marker and outputs untouched), redoes one whose
// marker is gone (half-done) and one whose input changed.
TEST(CliBatch, ResumeSkipsCompleteCapturesAndRedoesHalfDoneOrChangedOnes) {
  test::TempDir dir;
  const fs::path inputs = makeTwoCaptures(dir), out = dir / "out";
  const std::vector<std::string> args{"batch", inputs.string(), "-o", out.string(), "--steps", "refocus:0.5,depth"};
  ASSERT_EQ(runLfcam(args, dir.path()).exitStatus, 0);
  const auto markerTime = fs::last_write_time(out / "a" / ".batch-done.json");
  const auto photoTime = fs::last_write_time(out / "a" / "refocus_0.5.png");
  fs::remove(out / "b" / ".batch-done.json");
  fs::remove(out / "b" / "depth.png");

  const auto rerun = runLfcam(args, dir.path());
  ASSERT_EQ(rerun.exitStatus, 0) << rerun.err;
  EXPECT_NE(rerun.out.find("1 done, 1 skipped"), std::string::npos) << rerun.out;
  EXPECT_EQ(fs::last_write_time(out / "a" / ".batch-done.json"), markerTime);
  EXPECT_EQ(fs::last_write_time(out / "a" / "refocus_0.5.png"), photoTime);
  EXPECT_TRUE(fs::is_regular_file(out / "b" / "depth.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "b" / ".batch-done.json"));
  auto report = readJson(out / "batch-report.json");
  EXPECT_EQ(report["captures"][0]["status"], "skipped");
  EXPECT_EQ(report["captures"][1]["status"], "done");

  // A changed input is redone; so is every capture when the steps change.
  fs::last_write_time(inputs / "a.lf.h5", fs::last_write_time(inputs / "a.lf.h5") + std::chrono::seconds(5));
  ASSERT_EQ(runLfcam(args, dir.path()).exitStatus, 0);
  report = readJson(out / "batch-report.json");
  EXPECT_EQ(report["captures"][0]["status"], "done");
  EXPECT_EQ(report["captures"][1]["status"], "skipped");
  ASSERT_EQ(runLfcam({"batch", inputs.string(), "-o", out.string(), "--steps", "refocus:0.5"}, dir.path()).exitStatus,
            0);
  EXPECT_EQ(readJson(out / "batch-report.json")["done"], 2);
}

TEST(CliBatch, ABadCaptureIsListedAndTheOthersComplete) {
  test::TempDir dir;
  const fs::path inputs = makeTwoCaptures(dir), out = dir / "out";
  test::writeBytes(inputs / "broken.lf.h5", std::string("\x89HDF\r\n\x1a\n", 8) + "not really HDF5");
  const auto result =
      runLfcam({"batch", inputs.string(), "-o", out.string(), "--steps", "refocus:0", "--jobs", "2"}, dir.path());
  EXPECT_EQ(result.exitStatus, 1);
  EXPECT_NE(result.err.find("failed: " + (inputs / "broken.lf.h5").string() + ": "), std::string::npos) << result.err;
  EXPECT_EQ(result.errLines(), 2) << result.err;  // the failure, then the summary
  for (const char* capture : {"a", "b"}) EXPECT_TRUE(fs::is_regular_file(out / capture / ".batch-done.json"));
  EXPECT_FALSE(fs::exists(out / "broken")) << "no output of an unreadable input";
  const auto report = readJson(out / "batch-report.json");
  EXPECT_EQ(report["failed"], 1);
  EXPECT_EQ(report["done"], 2);
  const auto& broken = report["captures"][2];
  EXPECT_EQ(broken["name"], "broken");
  EXPECT_EQ(broken["status"], "failed");
  EXPECT_TRUE(broken["outputs"].empty());
  EXPECT_NE(broken["error"].get<std::string>().find("broken.lf.h5"), std::string::npos);
}

TEST(CliBatch, QuotedGlobsAndSpecFileStandForTheArguments) {
  test::TempDir dir;
  const fs::path inputs = makeTwoCaptures(dir);
  const auto globbed =
      runLfcam({"batch", (inputs / "*.lf.h5").string(), "-o", (dir / "g").string(), "--steps", "edof"}, dir.path());
  ASSERT_EQ(globbed.exitStatus, 0) << globbed.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "g" / "a" / "all-in-focus.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "g" / "b" / "all-in-focus.png"));

  const nlohmann::json spec{{"inputs", {(inputs / "b.lf.h5").string()}},
                            {"steps", {"refocus:1", "stack:0:1:2"}},
                            {"output", (dir / "s").string()},
                            {"jobs", 1},
                            {"report", (dir / "report.json").string()}};
  test::writeBytes(dir / "spec.json", spec.dump());
  const auto fromSpec = runLfcam({"batch", "--spec", (dir / "spec.json").string()}, dir.path());
  ASSERT_EQ(fromSpec.exitStatus, 0) << fromSpec.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "s" / "b" / "refocus_1.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "s" / "b" / "stack" / "slice_001.png"));
  EXPECT_FALSE(fs::exists(dir / "s" / "a"));
  EXPECT_EQ(readJson(dir / "report.json")["steps"], nlohmann::json({"refocus:1", "stack:0:1:2"}));
}

// Each a one-line usage error before any work: no output folder made.
TEST(CliBatch, BadArgumentsAreOneLineUsageErrors) {
  test::TempDir dir;
  const fs::path inputs = makeTwoCaptures(dir), out = dir / "out";
  test::writeBytes(dir / "spec.json", R"({"inputs": ["x"], "stpes": ["edof"]})");
  const fs::path noSlices = writeMicroscopeSettings(dir, "num_slices");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "edof,sharpen"}, "unknown step 'sharpen'"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "refocus:near"}, "refocus:SLOPE"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "stack:0:1"}, "stack:FROM:TO:N"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "photo:p?slope=1&f-number=0.5"},
       "'photo:p?slope=1&f-number=0.5': f-number: must be 1 (the whole lens) or more"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "photo:p?tilt=1"}, "give the focus"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "photo:a/b?slope=1"}, "photo:NAME?FIELD=TEXT"},
      {{"batch", (dir / "*.lfp").string(), "-o", out.string(), "--steps", "edof"},
       (dir / "*.lfp").string() + ": no file matches"},
      {{"batch", "--spec", (dir / "spec.json").string()}, (dir / "spec.json").string() + ": unknown key 'stpes'"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "edof,volume:" + (dir / "none.json").string()},
       "--steps: 'volume:" + (dir / "none.json").string() + "': cannot read " + (dir / "none.json").string()},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "volume:" + noSlices.string()},
       noSlices.string() + ": num_slices missing"},
      {{"batch", inputs.string(), "-o", out.string(), "--steps", "volume:" + (dir / "spec.json").string()},
       "'volume:" + (dir / "spec.json").string() + "': "},
  };
  for (const auto& [args, message] : cases) {
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << args.back();
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(out)) << args.back();
  }
}

// A volume step reconstructs every capture of a microscope time series, the PSF computed once into
// OUTDIR before the captures run: they only read it, even all redone at once.
TEST(CliBatch, AVolumeStepReconstructsEveryCaptureFromOnePsf) {
  test::TempDir dir;
  const fs::path series = makeMicroscopeSeries(dir), settings = writeMicroscopeSettings(dir), out = dir / "out";
  const std::string step = "volume:" + settings.string();
  const std::vector<std::string> args{"batch", series.string(), "-o", out.string(), "--steps", step, "--jobs", "3"};
  const auto result = runLfcam(args, dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  EXPECT_NE(result.out.find("3 done"), std::string::npos) << result.out;
  const auto caches = psfCaches(out);
  ASSERT_EQ(caches.size(), 1u);
  const auto cacheTime = fs::last_write_time(caches.front());
  for (const char* capture : {"t0", "t1", "t2"}) {
    const auto volume = readVolume(out / capture / "volume.tif");
    ASSERT_TRUE(volume) << volume.error().message;
    EXPECT_EQ(volume->width(), 6);
    EXPECT_EQ(volume->height(), 5);
    EXPECT_EQ(volume->depth(), 3);
    EXPECT_NEAR(volume->voxelDepthUm, 3, 1e-9);
    EXPECT_LE(cacheTime, fs::last_write_time(out / capture / "volume.tif")) << "the PSF before every capture";
    EXPECT_EQ(readJson(out / capture / ".batch-done.json")["steps"], nlohmann::json({step}));
  }
  // Every capture redone at once reads the cache, rewriting it nowhere.
  for (const char* capture : {"t0", "t1", "t2"}) fs::remove(out / capture / ".batch-done.json");
  const auto rerun = runLfcam(args, dir.path());
  ASSERT_EQ(rerun.exitStatus, 0) << rerun.err;
  EXPECT_NE(rerun.out.find("3 done"), std::string::npos) << rerun.out;
  EXPECT_EQ(psfCaches(out), caches);
  EXPECT_EQ(fs::last_write_time(caches.front()), cacheTime);
}

// A photograph step is any photograph request, named: its fields' commas do not split --steps, and
// the file is the one lfcam refocus writes with the same flags.
TEST(CliBatch, APhotoStepIsAnyPhotographRequest) {
  test::TempDir dir;
  const fs::path inputs = makeTwoCaptures(dir), out = dir / "out";
  const auto result = runLfcam({"batch", inputs.string(), "-o", out.string(), "--steps",
                                "edof,photo:plane?focus-plane=5,5:30,8:20,30&f-number=2,refocus:0.5", "--jobs", "1"},
                               dir.path());
  ASSERT_EQ(result.exitStatus, 0) << result.err;
  const auto single = runLfcam({"refocus", (inputs / "a.lf.h5").string(), "--focus-plane", "5,5:30,8:20,30",
                                "--f-number", "2", "-o", (dir / "single.png").string()},
                               dir.path());
  ASSERT_EQ(single.exitStatus, 0) << single.err;
  EXPECT_EQ(test::readBytes(out / "a" / "photo_plane.png"), test::readBytes(dir / "single.png"));
  EXPECT_TRUE(fs::exists(out / "a" / "refocus_0.5.png"));
  EXPECT_TRUE(fs::exists(out / "a" / "all-in-focus.png"));
}

}  // namespace
}  // namespace lfcam
