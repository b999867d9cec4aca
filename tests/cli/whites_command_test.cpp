// lfcam whites index, and --whites where a raw is decoded: decode, info, a command decoding on the
// way, batch (flags and spec); one line and the right exit status for a camera the database does not
// hold and for a truncated archive, nothing written then.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "cli_support.hpp"
#include "lytro_caldata.hpp"
#include "test_support.hpp"

namespace lfcam::test {
namespace {

namespace fs = std::filesystem;
const char* kSerial = "B5143909630";

// An Illum's caldata tar of two whites (zoom steps -1040 and -560) and a capture near the second.
void writeCaldataAndCapture(const TempDir& dir, const std::string& captureSerial) {
  std::vector<std::pair<std::string, std::string>> members;
  const std::vector<LytroSetting> whites{{kSerial, -1040, -300, 0}, {kSerial, -560, -300, 2}};
  for (std::size_t k = 0; k < whites.size(); ++k) {
    auto [raw, txt] = lytroWhiteFiles(true, whites[k]);
    members.emplace_back("MOD_000" + std::to_string(k) + ".RAW", std::move(raw));
    members.emplace_back("MOD_000" + std::to_string(k) + ".TXT", std::move(txt));
  }
  writeTar(dir / "caldata-B5143909630.tar", members);
  writeLytroCapture(dir / "capture.lfr", true, {captureSerial, -570, -280, 2});
}

TEST(WhitesCommand, IndexesAndEveryDecodeSaysWhichWhiteAndWhy) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  TempDir dir;
  writeCaldataAndCapture(dir, kSerial);
  const auto at = [&](const char* name) { return (dir / name).string(); };
  auto index = runLfcam({"whites", "index", at("caldata-B5143909630.tar"), "-o", at("whites.json")}, dir.path());
  ASSERT_EQ(index.exitStatus, 0) << index.err;
  EXPECT_NE(index.out.find("caldata-B5143909630.tar:MOD_0001.RAW: camera B5143909630 (B01), zoom step -560"),
            std::string::npos)
      << index.out;
  EXPECT_NE(index.out.find("whites.json: 2 whites (lfcam "), std::string::npos) << index.out;

  auto decode =
      runLfcam({"decode", at("capture.lfr"), "--whites", at("whites.json"), "-o", at("capture.lf.h5")}, dir.path());
  ASSERT_EQ(decode.exitStatus, 0) << decode.err;
  EXPECT_EQ(decode.err.rfind("white: " + at("caldata-B5143909630.tar"), 0), 0u) << decode.err;
  EXPECT_NE(decode.err.find("caldata-B5143909630.tar:MOD_0001.RAW (zoom step -560, focus step -300): of 2 "
                            "whites of camera B5143909630, the nearest in zoom (10 steps off), then in focus (20 "
                            "steps off)"),
            std::string::npos)
      << decode.err;
  // The light field says which white it was decoded with; info says which a raw would take.
  auto decoded = runLfcam({"info", at("capture.lf.h5")}, dir.path());
  EXPECT_NE(decoded.out.find("caldata-B5143909630.tar:MOD_0001.RAW from " + at("whites.json")), std::string::npos)
      << decoded.out;
  auto info = runLfcam({"info", at("capture.lfr"), "--whites", at("whites.json"), "--json"}, dir.path());
  ASSERT_EQ(info.exitStatus, 0) << info.err;
  const auto json = nlohmann::json::parse(info.out);
  EXPECT_EQ(json["white"]["choice"], "database");
  EXPECT_EQ(json["white"]["name"], at("caldata-B5143909630.tar") + ":MOD_0001.RAW");
  EXPECT_TRUE(fs::exists(json["white"]["grid"].get<std::string>()));
  auto none = runLfcam({"info", at("capture.lfr")}, dir.path());
  EXPECT_NE(none.out.find("  white: none given: --whites DATABASE would choose one"), std::string::npos) << none.out;

  // A command decoding on the way, and a batch by its flags and by its spec file.
  auto refocus = runLfcam(
      {"refocus", at("capture.lfr"), "--whites", at("whites.json"), "--slope", "0", "-o", at("photo.png")}, dir.path());
  ASSERT_EQ(refocus.exitStatus, 0) << refocus.err;
  EXPECT_TRUE(fs::exists(dir / "photo.png"));
  auto batch =
      runLfcam({"batch", at("capture.lfr"), "-o", at("batch"), "--steps", "refocus:0", "--whites", at("whites.json")},
               dir.path());
  ASSERT_EQ(batch.exitStatus, 0) << batch.err;
  EXPECT_TRUE(fs::exists(dir / "batch" / "capture" / "refocus_0.png"));
  const nlohmann::json specJson = {{"inputs", {at("capture.lfr")}},
                                   {"steps", {"refocus:0"}},
                                   {"output", at("spec-batch")},
                                   {"whites", at("whites.json")}};
  writeBytes(dir / "spec.json", specJson.dump());
  auto spec = runLfcam({"batch", "--spec", at("spec.json")}, dir.path());
  ASSERT_EQ(spec.exitStatus, 0) << spec.err;
  EXPECT_TRUE(fs::exists(dir / "spec-batch" / "capture" / "refocus_0.png"));

  // The viewer decodes the raw the same way, saying which white, before it serves.
  const pid_t viewer = startLfcam({"view", at("capture.lfr"), "--whites", at("whites.json"), "--port", "0"},
                                  dir / "view.out", dir / "view.err");
  ASSERT_GT(viewer, 0);
  for (int k = 0; k < 200 && readBytes(dir / "view.out").find("serving") == std::string::npos; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ::kill(viewer, SIGTERM);
  ::waitpid(viewer, nullptr, 0);
  EXPECT_NE(readBytes(dir / "view.out").find("serving"), std::string::npos) << readBytes(dir / "view.err");
  EXPECT_NE(readBytes(dir / "view.err").find("white: " + at("caldata-B5143909630.tar") + ":MOD_0001.RAW"),
            std::string::npos);
}

TEST(WhitesCommand, AnotherCamerasCaptureIsRefusedUnlessAnyCamera) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  TempDir dir;
  writeCaldataAndCapture(dir, "B0000000001");
  const auto at = [&](const char* name) { return (dir / name).string(); };
  auto index = runLfcam({"whites", "index", dir.path().string(), "-o", at("whites.json")}, dir.path());
  ASSERT_EQ(index.exitStatus, 0) << index.err;
  // The capture in the folder is no white: passed over, saying so.
  EXPECT_NE(index.err.find("lfcam: warning: " + at("capture.lfr") +
                           ": a Lytro container of a picture, not of a white image, passed over"),
            std::string::npos)
      << index.err;
  auto refused =
      runLfcam({"decode", at("capture.lfr"), "--whites", at("whites.json"), "-o", at("out.lf.h5")}, dir.path());
  EXPECT_EQ(refused.exitStatus, 2);
  EXPECT_EQ(refused.errLines(), 1) << refused.err;
  EXPECT_NE(refused.err.find("capture.lfr: camera B0000000001 has no white in " + at("whites.json") + " (--any-camera"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir / "out.lf.h5"));
  auto any = runLfcam(
      {"decode", at("capture.lfr"), "--whites", at("whites.json"), "--any-camera", "-o", at("out.lf.h5")}, dir.path());
  ASSERT_EQ(any.exitStatus, 0) << any.err;
  EXPECT_NE(any.err.find("(--any-camera: the capture's is B0000000001)"), std::string::npos) << any.err;
  auto both = runLfcam(
      {"decode", at("capture.lfr"), "--whites", at("whites.json"), "--white", at("capture.lfr"), "-o", at("x.lf.h5")},
      dir.path());
  EXPECT_EQ(both.exitStatus, 2) << both.err;

  // A raw whose metadata gives no lens setting (a PNG without a side-car) cannot be given a white.
  ASSERT_EQ(runLfcam({"simulate", "chart", "--size", "64", "--samples", "1", "--no-ground-truth", "-o", at("plain")},
                     dir.path())
                .exitStatus,
            0);
  auto unknown =
      runLfcam({"decode", at("plain/raw.png"), "--whites", at("whites.json"), "-o", at("p.lf.h5")}, dir.path());
  EXPECT_EQ(unknown.exitStatus, 1);
  EXPECT_EQ(unknown.errLines(), 1) << unknown.err;
  EXPECT_NE(unknown.err.find(at("plain/raw.png") + ": its metadata gives no zoom step, so no white of "),
            std::string::npos)
      << unknown.err;
  EXPECT_FALSE(fs::exists(dir / "p.lf.h5"));
}

TEST(WhitesCommand, TruncatedArchiveFailsInOneLineAndWritesNothing) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  TempDir dir;
  writeCaldataAndCapture(dir, kSerial);
  const auto at = [&](const char* name) { return (dir / name).string(); };
  const std::string whole = readBytes(dir / "caldata-B5143909630.tar");
  writeBytes(dir / "cut.tar", whole.substr(0, whole.size() - 5000));
  auto cut = runLfcam({"whites", "index", at("cut.tar"), "-o", at("whites.json")}, dir.path());
  EXPECT_EQ(cut.exitStatus, 1);
  EXPECT_EQ(cut.errLines(), 1) << cut.err;
  EXPECT_NE(cut.err.find("cut.tar: damaged or truncated tar archive"), std::string::npos) << cut.err;
  EXPECT_FALSE(fs::exists(dir / "whites.json"));
  EXPECT_FALSE(fs::exists(dir / "whites.cache"));
  auto notCaldata =
      runLfcam({"whites", "index", at("capture.lfr"), at("no-such-folder"), "-o", at("whites.json")}, dir.path());
  EXPECT_EQ(notCaldata.exitStatus, 1) << notCaldata.err;
  EXPECT_EQ(notCaldata.errLines(), 1) << notCaldata.err;
}

}  // namespace
}  // namespace lfcam::test
