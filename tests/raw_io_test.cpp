// readRaw: PNG/TIFF lenslet images (with and without camera.json), Lytro containers written from
// simulator captures (first-generation and Illum style, exact mosaics and metadata), camera raws
// through LibRaw (a minimal DNG written here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "lfcam/io/image_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "raw_io/lytro_raw.hpp"
#include "test_support.hpp"
#include "tiff_with_levels.hpp"

namespace lfcam {
namespace {

Image randomMosaic(int w, int h, int maxValue, unsigned seed) {
  std::mt19937 rng(seed);
  Image m(w, h, 1);
  for (float& v : m.pixels()) v = float(rng() % unsigned(maxValue + 1));
  return m;
}

void expectSameMosaic(const Image& a, const Image& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.channels(), b.channels());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.pixels().size(); ++k) differing += a.pixels()[k] != b.pixels()[k];
  EXPECT_EQ(differing, 0u);
}

TEST(RawIo, SixteenBitPngHoldsDnAndOptionsNameTheRest) {
  test::TempDir dir;
  Image dn = randomMosaic(40, 30, 4095, 1);
  Image codes = dn.copy();
  for (float& v : codes.pixels()) v /= 65535.0f;
  ASSERT_TRUE(writeImage(dir / "lenslet.png", codes, {.sampleType = SampleType::UInt16}));
  auto raw = readRaw(dir / "lenslet.png");
  ASSERT_TRUE(raw) << raw.error().message;
  expectSameMosaic(raw->mosaic, dn);
  EXPECT_EQ(raw->colorFilter, ColorFilter::Mono);
  EXPECT_EQ(raw->whiteLevel, 65535);
  EXPECT_EQ(raw->source, "image");
  auto named = readRaw(dir / "lenslet.png", {.colorFilter = ColorFilter::GRBG, .blackLevel = 64, .whiteLevel = 4095});
  ASSERT_TRUE(named);
  EXPECT_EQ(named->colorFilter, ColorFilter::GRBG);
  EXPECT_EQ(named->blackLevel, 64);
  EXPECT_EQ(named->whiteLevel, 4095);
  auto impossible = readRaw(dir / "lenslet.png", {.blackLevel = 100, .whiteLevel = 50});
  ASSERT_FALSE(impossible);
  EXPECT_EQ(impossible.error().code, ErrorCode::Usage);
}

// A black level given by the caller is checked against the file: negative, at the white level or
// at the largest value the file holds (every sample would be black) are usage errors.
TEST(RawIo, GivenBlackLevelOutOfRangeIsAUsageError) {
  test::TempDir dir;
  Image dn = randomMosaic(40, 30, 4095, 3);
  dn.pixels()[0] = 4095;
  Image codes = dn.copy();
  for (float& v : codes.pixels()) v /= 65535.0f;
  ASSERT_TRUE(writeImage(dir / "lenslet.png", codes, {.sampleType = SampleType::UInt16}));
  for (const double black : {-1.0, double(NAN), 4095.0, 5000.0, 65535.0, 70000.0}) {
    auto raw = readRaw(dir / "lenslet.png", {.blackLevel = black});
    ASSERT_FALSE(raw) << black;
    EXPECT_EQ(raw.error().code, ErrorCode::Usage) << raw.error().message;
    EXPECT_EQ(raw.error().message.rfind((dir / "lenslet.png").string() + ": black level", 0), 0u)
        << raw.error().message;
    EXPECT_EQ(raw.error().message.find('\n'), std::string::npos);
  }
  auto highest = readRaw(dir / "lenslet.png", {.blackLevel = 4094});
  ASSERT_TRUE(highest) << highest.error().message;
  EXPECT_EQ(highest->blackLevel, 4094);
}

// The DNG BlackLevel and WhiteLevel tags of a plain TIFF:
// one value or a pattern (its mean), SHORT or RATIONAL, either byte order; a given level wins.
TEST(RawIo, TiffBlackAndWhiteLevelTags) {
  test::TempDir dir;
  const Image dn = randomMosaic(24, 16, 4095, 4);
  struct Case {
    test::TiffLevelTags tags;
    double black, white;
  };
  const std::vector<Case> cases = {{{.black = {64}}, 64, 65535},
                                   {{.black = {64}, .white = 4095, .bigEndian = true}, 64, 4095},
                                   {{.black = {60, 62, 66, 68}, .white = 4095}, 64, 4095},
                                   {{.black = {64.5}, .rational = true}, 64.5, 65535},
                                   {{.black = {200, 201}, .rational = true, .bigEndian = true}, 200.5, 65535},
                                   {{}, 0, 65535}};
  for (const Case& c : cases) {
    const auto path = dir / "tagged.tif";
    test::writeTiffWithLevels(path, dn, c.tags);
    auto raw = readRaw(path);
    ASSERT_TRUE(raw) << raw.error().message;
    expectSameMosaic(raw->mosaic, dn);
    EXPECT_DOUBLE_EQ(raw->blackLevel, c.black);
    EXPECT_DOUBLE_EQ(raw->whiteLevel, c.white);
    auto given = readRaw(path, {.blackLevel = 10});
    ASSERT_TRUE(given);
    EXPECT_EQ(given->blackLevel, 10);
  }
  // A tagged level above the file's white level is the file's fault, not the caller's.
  test::writeTiffWithLevels(dir / "wrong.tif", dn, {.black = {5000}, .white = 4095});
  auto wrong = readRaw(dir / "wrong.tif");
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().code, ErrorCode::Format) << wrong.error().message;
}

TEST(RawIo, EightBitPngGivesItsCodes) {
  test::TempDir dir;
  Image dn = randomMosaic(16, 16, 255, 2);
  Image linear = dn.copy();
  for (float& v : linear.pixels()) v = linearFromSrgb(v / 255.0f);
  ASSERT_TRUE(writeImage(dir / "l8.png", linear));
  auto raw = readRaw(dir / "l8.png");
  ASSERT_TRUE(raw) << raw.error().message;
  expectSameMosaic(raw->mosaic, dn);
  EXPECT_EQ(raw->whiteLevel, 255);
}

// A small simulated capture (few rays) in `folder`.
CameraModel smallCamera(bool illum) {
  CameraModel camera = CameraModel::paperPrototype(72, 60);
  camera.microlenses->pitchMm = 7.3 * camera.sensor.pixelPitchMm;
  camera.microlenses->focalLengthMm = 4 * camera.microlenses->pitchMm;
  camera.microlenses->rotationDeg = 0.4;
  camera.microlenses->offsetMm = {0.003, -0.002};
  if (illum) {
    camera.microlenses->packing = Packing::Hexagonal;
    camera.sensor.colorFilter = ColorFilter::GRBG;
    camera.sensor.bitDepth = 10;
    camera.sensor.blackLevel = 64;
    camera.sensor.whiteLevel = 1023;
  } else {
    camera.sensor.colorFilter = ColorFilter::BGGR;
  }
  return camera;
}

void simulateInto(const std::filesystem::path& folder, const CameraModel& camera) {
  auto scene = builtinScene("chart", camera);
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_TRUE(writeSimulation(folder, *scene, camera, {.samplesPerPixel = 1}, {.white = true, .groundTruth = false}));
}

void expectSameHint(const RawImage& a, const RawImage& b) {
  ASSERT_TRUE(a.lenslet && b.lenslet);
  EXPECT_NEAR(a.lenslet->pitchPx, b.lenslet->pitchPx, 1e-9);
  EXPECT_NEAR(a.lenslet->rotationRad, b.lenslet->rotationRad, 1e-12);
  EXPECT_NEAR(a.lenslet->offsetPx[0], b.lenslet->offsetPx[0], 1e-9);
  EXPECT_NEAR(a.lenslet->offsetPx[1], b.lenslet->offsetPx[1], 1e-9);
  EXPECT_EQ(a.lenslet->packing, b.lenslet->packing);
}

TEST(RawIo, SimulatorCaptureThroughFirstGenerationLfp) {
  test::TempDir dir;
  const CameraModel camera = smallCamera(false);
  simulateInto(dir.path(), camera);
  auto png = readRaw(dir / "raw.png");
  ASSERT_TRUE(png) << png.error().message;
  EXPECT_EQ(png->source, "simulator");
  EXPECT_EQ(png->colorFilter, ColorFilter::BGGR);
  EXPECT_EQ(png->blackLevel, 64);
  EXPECT_EQ(png->whiteLevel, 4095);
  ASSERT_TRUE(png->lenslet);
  EXPECT_NEAR(png->lenslet->rotationRad, 0.4 * std::numbers::pi / 180, 1e-12);

  ASSERT_TRUE(writeSimulationContainers(dir.path(), LytroStyle::FirstGeneration));
  EXPECT_FALSE(std::filesystem::exists(dir / "white.lfp"));
  // 12-bit big-endian packing, as the F01's: 3 bytes per 2 pixels plus headers.
  const auto size = std::filesystem::file_size(dir / "raw.lfp");
  EXPECT_GT(size, 72u * 60 * 3 / 2);
  EXPECT_LT(size, 72u * 60 * 3 / 2 + 12000);
  auto lfp = readRaw(dir / "raw.lfp");
  ASSERT_TRUE(lfp) << lfp.error().message;
  EXPECT_EQ(lfp->source, "lytro-lfp");
  expectSameMosaic(lfp->mosaic, png->mosaic);
  EXPECT_EQ(lfp->colorFilter, ColorFilter::BGGR);
  EXPECT_EQ(lfp->blackLevel, 64);
  EXPECT_EQ(lfp->whiteLevel, 4095);
  expectSameHint(*lfp, *png);
  EXPECT_EQ(nlohmann::json::parse(lfp->metadataJson)["image"]["rawDetails"]["pixelPacking"]["bitsPerPixel"], 12);
}

TEST(RawIo, SimulatorCaptureThroughIllumLfrWithWhiteImage) {
  test::TempDir dir;
  const CameraModel camera = smallCamera(true);
  simulateInto(dir.path(), camera);
  ASSERT_TRUE(writeSimulationContainers(dir.path(), LytroStyle::Illum));
  for (const char* stem : {"raw", "white"}) {
    auto png = readRaw(dir / (std::string(stem) + ".png"));
    auto lfr = readRaw(dir / (std::string(stem) + ".lfr"));
    ASSERT_TRUE(png && lfr);
    EXPECT_EQ(lfr->source, "lytro-lfr");
    expectSameMosaic(lfr->mosaic, png->mosaic);
    EXPECT_EQ(lfr->colorFilter, ColorFilter::GRBG);
    EXPECT_EQ(lfr->blackLevel, 64);
    EXPECT_EQ(lfr->whiteLevel, 1023);
    expectSameHint(*lfr, *png);
    EXPECT_EQ(lfr->lenslet->packing, Packing::Hexagonal);
    EXPECT_EQ(nlohmann::json::parse(lfr->metadataJson)["image"]["pixelPacking"]["bitsPerPixel"],
              10);  // Illum layout, 10-bit
  }
  auto white = readLytroContainer(dir / "white.lfr");
  ASSERT_TRUE(white);
  EXPECT_EQ(white->tableOfContents["frames"][0]["parameters"]["vendorContent"]["com.lytro.tags"]["modulationFrame"],
            true);
}

TEST(RawIo, LytroRawKeepsColourMetadataAndUses16BitWhenNeeded) {
  RawImage raw;
  raw.mosaic = randomMosaic(33, 17, 60000, 3);  // odd sizes: partial packing groups
  raw.colorFilter = ColorFilter::RGGB;
  raw.blackLevel = 1000;
  raw.whiteLevel = 60000;
  raw.whiteBalance = std::array<double, 3>{1.5, 1.0, 1.25};
  raw.colorMatrix = std::array<double, 9>{2, -0.5, -0.5, -0.25, 1.5, -0.25, 0, -0.75, 1.75};
  for (LytroStyle style : {LytroStyle::FirstGeneration, LytroStyle::Illum}) {
    auto container = makeLytroRawContainer(raw, {.style = style}, "mem");
    ASSERT_TRUE(container) << container.error().message;
    auto back = rawFromLytroContainer(*container, "mem");
    ASSERT_TRUE(back) << back.error().message;
    expectSameMosaic(back->mosaic, raw.mosaic);
    EXPECT_EQ(back->whiteBalance, raw.whiteBalance);
    EXPECT_EQ(back->colorMatrix, raw.colorMatrix);
    EXPECT_FALSE(back->lenslet);
  }
  raw.mosaic.pixels()[5] = 0.5f;
  EXPECT_FALSE(makeLytroRawContainer(raw, {}, "mem"));  // not a whole DN
}

TEST(RawIo, ContainersWithoutARawFrameOrWithAShortOneAreRefused) {
  LytroContainer processed = makeLytroContainer({{"picture", {{"frameArray", nlohmann::json::array()}}}}, {});
  auto none = rawFromLytroContainer(processed, "p.lfp");
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, ErrorCode::Unsupported);

  RawImage raw;
  raw.mosaic = randomMosaic(8, 8, 4095, 4);
  raw.whiteLevel = 4095;
  auto container = makeLytroRawContainer(raw, {}, "mem");
  ASSERT_TRUE(container);
  for (LytroSection& s : container->sections)
    if (s.payload.size() == 96) s.payload.resize(50);  // the 8x8 12-bit frame, cut short
  auto shortFrame = rawFromLytroContainer(*container, "s.lfp");
  ASSERT_FALSE(shortFrame);
  EXPECT_NE(shortFrame.error().message.find("need 96"), std::string::npos) << shortFrame.error().message;
}

// A minimal uncompressed DNG (TIFF with the DNG tags and a 2x2 CFA), little-endian.
std::string minimalDng(const Image& mosaic, const std::uint8_t cfa[4], int black, int white) {
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count;
    std::string data;  // the value's bytes
  };
  auto u16 = [](std::uint16_t v) { return std::string{char(v & 0xff), char(v >> 8)}; };
  auto u32 = [](std::uint32_t v) {
    return std::string{char(v & 0xff), char(v >> 8 & 0xff), char(v >> 16 & 0xff), char(v >> 24)};
  };
  const std::uint32_t w = std::uint32_t(mosaic.width()), h = std::uint32_t(mosaic.height());
  std::string pixels;
  for (float v : mosaic.pixels()) pixels += u16(std::uint16_t(v));
  std::string identity;
  for (int k = 0; k < 9; ++k) identity += u32(k % 4 == 0 ? 1 : 0) + u32(1);
  std::vector<Entry> entries = {{254, 4, 1, u32(0)},
                                {256, 4, 1, u32(w)},
                                {257, 4, 1, u32(h)},
                                {258, 3, 1, u16(16)},
                                {259, 3, 1, u16(1)},
                                {262, 3, 1, u16(32803)},
                                {271, 2, 6, std::string("lfcam", 6)},
                                {272, 2, 5, std::string("test", 5)},
                                {273, 4, 1, u32(0)},  // strip offset, patched below
                                {274, 3, 1, u16(1)},
                                {277, 3, 1, u16(1)},
                                {278, 4, 1, u32(h)},
                                {279, 4, 1, u32(w * h * 2)},
                                {284, 3, 1, u16(1)},
                                {33421, 3, 2, u16(2) + u16(2)},
                                {33422, 1, 4, std::string(reinterpret_cast<const char*>(cfa), 4)},
                                {50706, 1, 4, std::string("\x01\x04\x00\x00", 4)},
                                {50708, 2, 11, std::string("lfcam test", 11)},
                                {50714, 4, 1, u32(std::uint32_t(black))},
                                {50717, 4, 1, u32(std::uint32_t(white))},
                                {50721, 10, 9, identity},
                                {50778, 3, 1, u16(21)}};
  const std::uint32_t ifdAt = 8, ifdSize = 2 + 12 * std::uint32_t(entries.size()) + 4;
  std::string extra;
  std::uint32_t extraAt = ifdAt + ifdSize;
  std::string ifd = u16(std::uint16_t(entries.size()));
  std::uint32_t pixelsAt = 0;
  // Out-of-line values first, then the pixels.
  std::uint32_t cursor = extraAt;
  for (const Entry& e : entries)
    if (e.data.size() > 4) cursor += std::uint32_t((e.data.size() + 1) / 2 * 2);
  pixelsAt = cursor;
  for (Entry& e : entries) {
    if (e.tag == 273) e.data = u32(pixelsAt);
    ifd += u16(e.tag) + u16(e.type) + u32(e.count);
    if (e.data.size() <= 4) {
      std::string inline4 = e.data;
      inline4.resize(4, '\0');
      ifd += inline4;
    } else {
      ifd += u32(extraAt + std::uint32_t(extra.size()));
      extra += e.data;
      if (extra.size() % 2) extra += '\0';
    }
  }
  ifd += u32(0);
  return std::string("II*\0", 4) + u32(ifdAt) + ifd + extra + pixels;
}

TEST(RawIo, CameraRawThroughLibRaw) {
  test::TempDir dir;
  const Image mosaic = randomMosaic(64, 48, 4095, 5);
  const std::uint8_t grbg[4] = {1, 0, 2, 1};
  test::writeBytes(dir / "test.dng", minimalDng(mosaic, grbg, 128, 4095));
  auto raw = readRaw(dir / "test.dng");
  ASSERT_TRUE(raw) << raw.error().message;
  EXPECT_EQ(raw->source, "libraw");
  expectSameMosaic(raw->mosaic, mosaic);
  EXPECT_EQ(raw->colorFilter, ColorFilter::GRBG);
  EXPECT_EQ(raw->blackLevel, 128);
  EXPECT_EQ(raw->whiteLevel, 4095);

  test::writeBytes(dir / "broken.dng", "II*\0garbage");
  auto broken = readRaw(dir / "broken.dng");
  ASSERT_FALSE(broken);
  EXPECT_EQ(broken.error().message.rfind((dir / "broken.dng").string() + ": ", 0), 0u);
}

}  // namespace
}  // namespace lfcam
