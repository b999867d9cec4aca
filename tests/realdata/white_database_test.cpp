// The white-image database: each firmware's metadata keys, indexing simulated Lytro calibration
// data (an Illum's tar archive, an F01's loose MOD files with their dark twins), the choice of the
// nearest white (LFToolbox's rule), decoding with it, and the inputs it refuses.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/calibrate/white_database.hpp"
#include "lfcam/decode/decode_files.hpp"
#include "lytro_caldata.hpp"
#include "raw_io/lytro_container.hpp"
#include "raw_io/lytro_setting.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::LytroSetting;

const char* kIllum = "B5143909630";
const char* kF01 = "A102430881";

// The Illum's four settings, one lattice each, in a tar archive as its camera stores them.
const std::vector<LytroSetting> kIllumWhites{
    {kIllum, -1040, -300, 0}, {kIllum, -1040, 200, 1}, {kIllum, -560, -300, 2}, {kIllum, -560, 200, 3}};

void writeIllumTar(const fs::path& path, const std::vector<LytroSetting>& whites) {
  std::vector<std::pair<std::string, std::string>> members;
  for (std::size_t k = 0; k < whites.size(); ++k) {
    auto [raw, txt] = test::lytroWhiteFiles(true, whites[k]);
    const std::string stem = "T1CALIB/MOD_000" + std::to_string(k);
    members.emplace_back(stem + ".RAW", std::move(raw));
    members.emplace_back(stem + ".TXT", std::move(txt));
  }
  test::writeTar(path, members);
}

// Writes the caldata: the Illum's tar, and an F01's folder with a dark twin of its first white.
void writeCaldata(const fs::path& dir) {
  writeIllumTar(dir / "caldata-B5143909630.tar", kIllumWhites);
  fs::create_directories(dir / "f01");
  test::writeLytroWhite(dir / "f01", "MOD_0000", false, {kF01, 981, 582, 1, 0.02});
  test::writeLytroWhite(dir / "f01", "MOD_0001", false, {kF01, 981, 582, 0, 0.005});
  test::writeLytroWhite(dir / "f01", "MOD_0002", false, {kF01, 600, 400, 3, 0.02});
}

struct Indexed {
  Result<WhiteDatabase> database;
  std::string notes;
};

Indexed index(const std::vector<fs::path>& sources, const fs::path& output) {
  std::string notes;
  auto database = indexWhites(sources, output, {}, [&](const std::string& line, bool passedOver) {
    if (passedOver) notes += line + "\n";
  });
  return {std::move(database), notes};
}

CameraSetting capture(const std::string& serial, double zoom, double focus) {
  return {.serial = serial, .zoomStep = zoom, .focusStep = focus};
}

TEST(LytroCameraSetting, ReadsEachFirmwaresKeys) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", folder);
  const auto read = [&](const char* name) {
    std::ifstream in(folder / name);
    return lytroCameraSetting(nlohmann::json::parse(in), nullptr);
  };
  // Illum white images of two firmware dates: frame keys, the serial inside the wrapper.
  const CameraSetting mod = read("MOD_0015.TXT");
  EXPECT_EQ(mod.metadataKeys, "lytro-frame");
  EXPECT_EQ(mod.serial, "B5152102610");
  EXPECT_EQ(*mod.zoomStep, -560);
  EXPECT_EQ(*mod.focusStep, -20);
  EXPECT_EQ(mod.model, "B01");
  EXPECT_NE(mod.firmware.find("Lightfield Engine 21"), std::string::npos);
  const CameraSetting older = read("lenslet_whiteimage.TXT");
  EXPECT_EQ(older.serial, "B5143909630");
  EXPECT_EQ(*older.zoomStep, -1040);
  EXPECT_EQ(*older.focusStep, -300);
  EXPECT_NEAR(*older.exposureS, 0.00722, 1e-5);
  // An F01 raw frame: frame keys; its serial is in a section apart, not here.
  const CameraSetting f01 = read("IMG_0001__frame.json");
  EXPECT_EQ(f01.metadataKeys, "lytro-frame");
  EXPECT_EQ(f01.model, "F01");
  EXPECT_EQ(*f01.zoomStep, 981);
  EXPECT_EQ(*f01.focusStep, 582);
  EXPECT_EQ(f01.serial, "");
  // An Illum picture's public metadata: the keys at the top.
  const CameraSetting illumPicture = read("toy.json");
  EXPECT_EQ(illumPicture.metadataKeys, "lytro-public");
  EXPECT_EQ(illumPicture.serial, "B5152102610");
  EXPECT_EQ(*illumPicture.zoomStep, -563);
  EXPECT_EQ(*illumPicture.focusStep, -17);
}

TEST(WhiteDatabase, IndexesBothGenerationsAndChoosesTheNearestZoomThenFocus) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  test::TempDir dir;
  writeCaldata(dir.path());
  const auto [database, notes] = index({dir / "caldata-B5143909630.tar", dir / "f01"}, dir / "whites.json");
  ASSERT_TRUE(database) << database.error().message;
  ASSERT_EQ(database->whites.size(), 6u) << notes;
  EXPECT_NE(notes.find("MOD_0001.RAW: a shorter exposure at the zoom and focus of"), std::string::npos) << notes;
  for (const WhiteRecord& white : database->whites) {
    EXPECT_EQ(white.setting.metadataKeys, "lytro-frame");
    EXPECT_FALSE(white.setting.firmware.empty());
    EXPECT_TRUE(fs::exists(white.white)) << white.white;
    EXPECT_LT(white.residualPx, 0.3) << white.name;
    auto grid = readGrid(white.grid);
    ASSERT_TRUE(grid) << grid.error().message;
    EXPECT_NEAR(grid->pitchX, 10, 0.05);
  }
  // The tar's whites were copied out of it, beside the index; the F01's stay where they are.
  EXPECT_EQ(database->whites[2].white.parent_path(), dir / "whites.cache");
  EXPECT_EQ(database->whites[0].white, dir / "f01" / "MOD_0002.RAW");

  auto reread = readWhiteDatabase(dir / "whites.json");
  ASSERT_TRUE(reread) << reread.error().message;
  ASSERT_EQ(reread->whites.size(), 6u);
  EXPECT_EQ(fs::canonical(reread->whites[3].white), fs::canonical(database->whites[3].white));
  EXPECT_EQ(reread->whites[3].setting.firmware, database->whites[3].setting.firmware);

  // Nearest zoom first (-560 over -1040), then nearest focus among those: MOD_0003.
  auto chosen = chooseWhite(*reread, capture(kIllum, -600, 150), 160, 128, false, "capture.lfr");
  ASSERT_TRUE(chosen) << chosen.error().message;
  EXPECT_NE(chosen->white.name.find("MOD_0003.RAW"), std::string::npos) << chosen->reason;
  EXPECT_NE(chosen->reason.find("of 4 whites of camera B5143909630"), std::string::npos) << chosen->reason;
  // A focus step nearer to another zoom's white does not win over the zoom.
  chosen = chooseWhite(*reread, capture(kIllum, -1000, -250), 160, 128, false, "capture.lfr");
  ASSERT_TRUE(chosen);
  EXPECT_NE(chosen->white.name.find("MOD_0000.RAW"), std::string::npos) << chosen->reason;
  // The F01's dark twin was passed over: its brighter white is chosen.
  chosen = chooseWhite(*reread, capture(kF01, 990, 580), 160, 128, false, "capture.lfp");
  ASSERT_TRUE(chosen);
  EXPECT_EQ(chosen->white.white, dir / "f01" / "MOD_0000.RAW");
}

TEST(WhiteDatabase, ReadsAFirstGenerationBackupAcrossItsVolumes) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  test::TempDir dir;
  fs::create_directories(dir / "backup");
  // Each white's .RAW in one volume and its .TXT in the next, as files named by the camera.
  const auto [raw0, txt0] = test::lytroWhiteFiles(false, {kF01, 981, 582, 1, 0.02});
  const auto [raw1, txt1] = test::lytroWhiteFiles(false, {kF01, 600, 400, 3, 0.02});
  const auto volume = [&](const fs::path& path, const std::vector<std::pair<std::string, std::string>>& files,
                          const char* next) {
    nlohmann::json toc = {{"files", nlohmann::json::array()}};
    if (next) toc["nextFile"] = next;
    std::vector<LytroSection> sections;
    for (const auto& [name, bytes] : files) {
      sections.push_back(makeLytroSection(LytroSectionKind::Component, bytes));
      toc["files"].push_back({{"name", name}, {"dataRef", sections.back().name}});
    }
    ASSERT_TRUE(writeLytroContainer(path, makeLytroContainer(toc, std::move(sections))));
  };
  volume(dir / "backup" / "data.C.0", {{"C:\\T1CALIB\\MOD_0000.RAW", raw0}, {"C:\\T1CALIB\\MOD_0001.TXT", txt1}},
         "data.C.1");
  volume(dir / "backup" / "data.C.1", {{"C:\\T1CALIB\\MOD_0000.TXT", txt0}, {"C:\\T1CALIB\\MOD_0001.RAW", raw1}},
         nullptr);
  const auto [database, notes] = index({dir / "backup"}, dir / "whites.json");
  ASSERT_TRUE(database) << database.error().message;
  ASSERT_EQ(database->whites.size(), 2u) << notes;
  EXPECT_EQ(database->whites[0].name, (dir / "backup" / "data.C.1").string() + ":C:/T1CALIB/MOD_0001.RAW");
  EXPECT_EQ(*database->whites[1].setting.zoomStep, 981);
  EXPECT_EQ(database->whites[1].setting.model, "F01");
  for (const WhiteRecord& white : database->whites) {
    EXPECT_EQ(white.white.parent_path(), dir / "whites.cache");
    EXPECT_TRUE(fs::exists(fs::path(white.white).replace_extension(".TXT")));
  }
}

TEST(WhiteDatabase, RefusesAnotherCameraUnlessAskedAndACaptureWithoutSteps) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  test::TempDir dir;
  writeIllumTar(dir / "caldata.tar", {kIllumWhites[0], kIllumWhites[3]});
  auto database = indexWhites({dir / "caldata.tar"}, dir / "whites.json");
  ASSERT_TRUE(database) << database.error().message;
  auto other = chooseWhite(*database, capture("B0000000000", -560, 200), 160, 128, false, "capture.lfr");
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().code, ErrorCode::Usage);
  EXPECT_NE(other.error().message.find("capture.lfr: camera B0000000000 has no white in"), std::string::npos)
      << other.error().message;
  EXPECT_NE(other.error().message.find("--any-camera"), std::string::npos);
  auto any = chooseWhite(*database, capture("B0000000000", -560, 200), 160, 128, true, "capture.lfr");
  ASSERT_TRUE(any) << any.error().message;
  EXPECT_NE(any->reason.find("--any-camera"), std::string::npos) << any->reason;

  CameraSetting noFocus = capture(kIllum, -560, 0);
  noFocus.focusStep.reset();
  auto missing = chooseWhite(*database, noFocus, 160, 128, false, "capture.lfr");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::Format);
  EXPECT_NE(missing.error().message.find("capture.lfr: its metadata gives no focus step"), std::string::npos);
  auto size = chooseWhite(*database, capture(kIllum, -560, 200), 200, 100, false, "capture.lfr");
  ASSERT_FALSE(size);
  EXPECT_NE(size.error().message.find("200x100 pixels match no white of camera B5143909630"), std::string::npos)
      << size.error().message;
}

TEST(WhiteDatabase, DecodesACaptureWithTheWhiteOfItsSetting) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  test::TempDir dir;
  fs::create_directories(dir / "whites");
  test::writeLytroWhite(dir / "whites", "MOD_0000", true, kIllumWhites[0]);
  test::writeLytroWhite(dir / "whites", "MOD_0001", true, kIllumWhites[2]);
  ASSERT_TRUE(indexWhites({dir / "whites"}, dir / "whites.json"));
  const fs::path raw = dir / "capture.lfr";
  test::writeLytroCapture(raw, true, {kIllum, -570, -280, 2});
  std::string told;
  auto chosen = decodeRawFiles({.raw = raw.string(),
                                .whites = (dir / "whites.json").string(),
                                .onWhiteChosen = [&](const std::string& reason) { told = reason; }});
  ASSERT_TRUE(chosen) << chosen.error().message;
  EXPECT_NE(told.find("MOD_0001.RAW"), std::string::npos) << told;
  EXPECT_NE(chosen->metadata.source.find("white " + (dir / "whites" / "MOD_0001.RAW").string()), std::string::npos)
      << chosen->metadata.source;
  // The same light field as with that white given by hand; another white's differs.
  auto right = decodeRawFiles({.raw = raw.string(), .white = (dir / "whites" / "MOD_0001.RAW").string()});
  auto wrong = decodeRawFiles({.raw = raw.string(), .white = (dir / "whites" / "MOD_0000.RAW").string()});
  ASSERT_TRUE(right && wrong);
  ASSERT_EQ(chosen->shape().ns, right->shape().ns);
  const auto samples = [](const LightField& lf) {
    return std::vector<float>(lf.samples().begin(), lf.samples().end());
  };
  EXPECT_EQ(samples(*chosen), samples(*right));
  EXPECT_NE(samples(*chosen), samples(*wrong));
}

TEST(WhiteDatabase, RefusesDamagedArchivesOtherSensorsAndAnotherVersion) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", metadata);
  test::TempDir dir;
  writeIllumTar(dir / "caldata.tar", {kIllumWhites[0], kIllumWhites[1]});
  // Truncated: an error naming the archive, nothing written.
  const std::string whole = test::readBytes(dir / "caldata.tar");
  test::writeBytes(dir / "cut.tar", whole.substr(0, whole.size() / 2 + 100));
  auto cut = indexWhites({dir / "cut.tar"}, dir / "cut.json");
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().code, ErrorCode::Format);
  EXPECT_NE(cut.error().message.find((dir / "cut.tar").string() + ": damaged or truncated tar archive"),
            std::string::npos)
      << cut.error().message;
  EXPECT_FALSE(fs::exists(dir / "cut.json"));
  EXPECT_FALSE(fs::exists(dir / "cut.cache"));
  // A tar of something else.
  test::writeTar(dir / "notes.tar", {{"README.md", "not calibration data"}});
  auto notLytro = indexWhites({dir / "notes.tar"}, dir / "notes.json");
  ASSERT_FALSE(notLytro);
  EXPECT_NE(notLytro.error().message.find("notes.tar: holds no Lytro calibration data"), std::string::npos)
      << notLytro.error().message;
  // A white of another sensor size among the camera's: passed over, saying so.
  fs::create_directories(dir / "mixed");
  test::writeLytroWhite(dir / "mixed", "MOD_0000", true, kIllumWhites[0]);
  test::writeLytroWhite(dir / "mixed", "MOD_0001", true, kIllumWhites[1]);
  LytroSetting small = kIllumWhites[2];
  small.width = small.height = 128;
  test::writeLytroWhite(dir / "mixed", "MOD_0002", true, small);
  const auto [mixed, notes] = index({dir / "mixed"}, dir / "mixed.json");
  ASSERT_TRUE(mixed) << mixed.error().message;
  EXPECT_EQ(mixed->whites.size(), 2u);
  EXPECT_NE(notes.find("MOD_0002.RAW: a white of 128x128 pixels where camera B5143909630's others are 160x128"),
            std::string::npos)
      << notes;
  // Grids another lfcam made are refused.
  std::string text = test::readBytes(dir / "mixed.json");
  const std::string madeBy = whiteCalibrationVersion();
  text.replace(text.find(madeBy), madeBy.size(), "lfcam 0.0.1, calibration 1");
  test::writeBytes(dir / "mixed.json", text);
  auto old = readWhiteDatabase(dir / "mixed.json");
  ASSERT_FALSE(old);
  EXPECT_NE(old.error().message.find("mixed.json: its grids were made by lfcam 0.0.1"), std::string::npos)
      << old.error().message;
  EXPECT_NE(old.error().message.find("run `lfcam whites index` again"), std::string::npos);
}

}  // namespace
}  // namespace lfcam
