// --black-level: the camera offset of a PNG/TIFF raw that carries no metadata, given on the command
// line or read from the file's TIFF BlackLevel tag, decodes as the simulator's own camera.json
// does; a dark frame wins over it; a level out of range is a one-line usage error writing nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "test_support.hpp"
#include "tiff_with_levels.hpp"

namespace lfcam::test {
namespace {

namespace fs = std::filesystem;

// PSNR of `a` against `b` over their samples, the peak being 1 (the white image's level).
double psnr(const LightField& a, const LightField& b) {
  EXPECT_EQ(a.shape(), b.shape());
  double sum = 0;
  for (std::size_t i = 0; i < a.samples().size(); ++i) {
    const double d = double(a.samples()[i]) - b.samples()[i];
    sum += d * d;
  }
  return sum == 0 ? INFINITY : 10 * std::log10(double(a.samples().size()) / sum);
}

class BlackLevel : public ::testing::Test {
 protected:
  // A simulator capture (black level 64 DN in camera.json), its raw and white image copied to a
  // folder without camera.json, and one grid for every decode so that only the levels differ.
  void SetUp() override {
    const std::string sim = (dir / "sim").string();
    auto simulate =
        runLfcam({"simulate", "chart", "--size", "120", "--samples", "1", "--noise", "off", "-o", sim}, dir.path());
    ASSERT_EQ(simulate.exitStatus, 0) << simulate.err;
    fs::create_directories(dir / "bare");
    for (const char* name : {"raw.png", "white.png"}) fs::copy_file(dir / "sim" / name, dir / "bare" / name);
    auto calibrate = runLfcam({"calibrate", sim + "/white.png", "--black-level", "64", "-o", grid()}, dir.path());
    ASSERT_EQ(calibrate.exitStatus, 0) << calibrate.err;
  }

  std::string grid() const { return (dir / "grid.json").string(); }
  std::string bare(const char* name) const { return (dir / "bare" / name).string(); }

  // Decodes `raw` with `white` and the extra flags into NAME.lf.h5 and reads it back.
  LightField decode(const std::string& raw, const std::string& white, std::vector<std::string> flags,
                    const std::string& name) {
    const std::string out = (dir / (name + ".lf.h5")).string();
    std::vector<std::string> args{"decode", raw, "--white", white, "--grid", grid(), "-o", out};
    args.insert(args.end(), flags.begin(), flags.end());
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 0) << result.err;
    auto read = readLightField(out);
    EXPECT_TRUE(read) << name;
    return read ? std::move(*read) : LightField();
  }

  TempDir dir;
};

TEST_F(BlackLevel, GivenOrTaggedDecodesAsTheCamerasOwnLevel) {
  // The same raw and white image as 16-bit TIFFs carrying the levels: BlackLevel = 64 alone (the
  // white level stays the codes' full scale, as for the PNG), and with the sensor's WhiteLevel.
  for (const char* name : {"raw", "white"}) {
    auto codes = readImage(dir / "bare" / (std::string(name) + ".png"));
    ASSERT_TRUE(codes);
    for (float& v : codes->pixels()) v = std::round(v * 65535.0f);
    writeTiffWithLevels(dir / "bare" / (std::string(name) + ".tif"), *codes, {.black = {64}});
    writeTiffWithLevels(dir / "bare" / (std::string(name) + "_12bit.tif"), *codes, {.black = {64}, .white = 4095});
  }
  const std::vector<std::string> rggb{"--bayer", "RGGB"};
  const LightField reference =
      decode((dir / "sim" / "raw.png").string(), (dir / "sim" / "white.png").string(), {}, "reference");
  const LightField tagged12 = decode(bare("raw_12bit.tif"), bare("white_12bit.tif"), rggb, "tagged12");
  const LightField tagged = decode(bare("raw.tif"), bare("white.tif"), rggb, "tagged");
  const LightField none = decode(bare("raw.png"), bare("white.png"), rggb, "none");
  const LightField given =
      decode(bare("raw.png"), bare("white.png"), {"--bayer", "RGGB", "--black-level", "64"}, "given");
  ASSERT_FALSE(reference.empty() || tagged12.empty() || tagged.empty() || none.empty() || given.empty());

  const double tagsAsCamera = psnr(tagged12, reference), withoutLevel = psnr(none, tagged),
               withLevel = psnr(given, tagged);
  std::printf(
      "[ black   ] TIFF BlackLevel 64 + WhiteLevel 4095 tags against camera.json: PSNR %.2f dB; PNG raw "
      "against the TIFF tagged BlackLevel 64: %.2f dB without a black level, %.2f dB with --black-level 64\n",
      tagsAsCamera, withoutLevel, withLevel);
  EXPECT_EQ(tagsAsCamera, INFINITY);
  EXPECT_EQ(withLevel, INFINITY);
  EXPECT_LT(withoutLevel, 40);
}

TEST_F(BlackLevel, ADarkFrameWinsOverIt) {
  // A dark frame of the sensor's offset, 64 DN everywhere.
  Image dark(120, 120, 1);
  for (float& v : dark.pixels()) v = 64.0f / 65535.0f;
  ASSERT_TRUE(writeImage(dir / "dark.png", dark, {.sampleType = SampleType::UInt16}));
  const std::string darkPath = (dir / "dark.png").string();
  const LightField darkOnly =
      decode(bare("raw.png"), bare("white.png"), {"--bayer", "RGGB", "--dark", darkPath}, "dark");
  const LightField both = decode(bare("raw.png"), bare("white.png"),
                                 {"--bayer", "RGGB", "--dark", darkPath, "--black-level", "1000"}, "both");
  ASSERT_FALSE(darkOnly.empty() || both.empty());
  EXPECT_EQ(psnr(both, darkOnly), INFINITY);
}

TEST_F(BlackLevel, OutOfRangeIsAOneLineUsageErrorWritingNothing) {
  const std::string raw = bare("raw.png"), white = bare("white.png");
  const std::string out = (dir / "out.lf.h5").string(), photo = (dir / "photo.png").string();
  const std::string newGrid = (dir / "new.json").string();
  const std::vector<std::vector<std::string>> cases = {
      {"decode", raw, "--white", white, "--grid", grid(), "--black-level", "5000", "-o", out},   // above the data
      {"decode", raw, "--white", white, "--grid", grid(), "--black-level", "70000", "-o", out},  // above white
      {"decode", raw, "--white", white, "--grid", grid(), "--black-level", "-5", "-o", out},
      {"decode", raw, "--white", white, "--grid", grid(), "--black-level", "dark", "-o", out},
      {"refocus", raw, "--white", white, "--grid", grid(), "--black-level", "5000", "--slope", "0", "-o", photo},
      {"views", raw, "--white", white, "--grid", grid(), "--black-level", "70000", "-o", (dir / "views").string()},
      {"calibrate", white, "--black-level", "70000", "-o", newGrid},
      {"refocus", (dir / "reference.lf.h5").string(), "--black-level", "64", "--slope", "0", "-o", photo},
  };
  for (const auto& args : cases) {
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << testing::PrintToString(args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(args) << ": " << result.err;
  }
  const auto above =
      runLfcam({"decode", raw, "--white", white, "--grid", grid(), "--black-level", "5000", "-o", out}, dir.path());
  EXPECT_NE(above.err.find(raw + ": black level 5000 DN"), std::string::npos) << above.err;
  for (const std::string& file : {out, photo, newGrid, (dir / "views").string()})
    EXPECT_FALSE(fs::exists(file)) << file;

  // A file whose own tags put black above white is failed work, exit 1.
  auto codes = readImage(raw);
  ASSERT_TRUE(codes);
  for (float& v : codes->pixels()) v = std::round(v * 65535.0f);
  writeTiffWithLevels(dir / "wrong.tif", *codes, {.black = {5000}, .white = 4095});
  const auto wrong =
      runLfcam({"decode", (dir / "wrong.tif").string(), "--white", white, "--grid", grid(), "-o", out}, dir.path());
  EXPECT_EQ(wrong.exitStatus, 1) << wrong.err;
  EXPECT_EQ(wrong.errLines(), 1) << wrong.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace lfcam::test
