// TIFF layouts lfcam does not write but reads (tiles, separate planes, palettes, other sample
// formats), made with libtiff itself; and lfcam's own TIFFs with many channels and alpha.
#include <gtest/gtest.h>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "lfcam/io/image_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

struct TiffCloser {
  void operator()(TIFF* tiff) const { TIFFClose(tiff); }
};

// A width x height TIFF whose tags `setTags` sets and whose first strip or tile per plane `write` fills.
void writeTiffWith(const fs::path& path, const std::function<void(TIFF*)>& setTags,
                   const std::function<void(TIFF*)>& write) {
  std::unique_ptr<TIFF, TiffCloser> tiff(TIFFOpen(path.c_str(), "w"));
  ASSERT_TRUE(tiff);
  setTags(tiff.get());
  write(tiff.get());
}

void setSize(TIFF* tiff, std::uint32_t width, std::uint32_t height, std::uint16_t channels, std::uint16_t bits,
             std::uint16_t format, std::uint16_t photometric) {
  TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, width);
  TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, height);
  TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, channels);
  TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, bits);
  TIFFSetField(tiff, TIFFTAG_SAMPLEFORMAT, format);
  TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, photometric);
}

TEST(TiffFile, TiledSeparatePlanesWithAlphaKeepTheirCodes) {
  test::TempDir dir;
  const std::uint32_t width = 37, height = 21;  // neither a multiple of the 16 x 16 tiles
  const auto code = [](std::uint32_t x, std::uint32_t y, int c) { return std::uint16_t(x * 1000 + y * 10 + c); };
  writeTiffWith(
      dir / "tiled.tif",
      [&](TIFF* tiff) {
        setSize(tiff, width, height, 4, 16, SAMPLEFORMAT_UINT, PHOTOMETRIC_RGB);
        TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_SEPARATE);
        TIFFSetField(tiff, TIFFTAG_TILEWIDTH, 16);
        TIFFSetField(tiff, TIFFTAG_TILELENGTH, 16);
        const std::uint16_t alpha[] = {EXTRASAMPLE_UNASSALPHA};
        TIFFSetField(tiff, TIFFTAG_EXTRASAMPLES, 1, alpha);
      },
      [&](TIFF* tiff) {
        std::vector<std::uint16_t> tile(16 * 16);
        for (int c = 0; c < 4; ++c)
          for (std::uint32_t ty = 0; ty < height; ty += 16)
            for (std::uint32_t tx = 0; tx < width; tx += 16) {
              for (std::uint32_t y = 0; y < 16; ++y)
                for (std::uint32_t x = 0; x < 16; ++x) tile[y * 16 + x] = code(tx + x, ty + y, c);
              ASSERT_GE(TIFFWriteTile(tiff, tile.data(), tx, ty, 0, std::uint16_t(c)), 0);
            }
      });
  auto header = readImageHeader(dir / "tiled.tif");
  ASSERT_TRUE(header) << header.error().message;
  EXPECT_EQ(header->sampleType, SampleType::UInt16);
  auto image = readImage(dir / "tiled.tif");
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->channels(), 4);
  for (int c = 0; c < 4; ++c)
    for (std::uint32_t y = 0; y < height; ++y)
      for (std::uint32_t x = 0; x < width; ++x)
        ASSERT_EQ(std::lround(image->at(int(x), int(y), c) * 65535.0f), code(x, y, c)) << x << "," << y << "," << c;
}

TEST(TiffFile, OtherSampleFormatsBecomeFloat) {
  test::TempDir dir;
  const std::int16_t signedCodes[] = {-32767, 0, 32767};
  const double doubles[] = {-2.5, 0.25, 1e6};
  const auto writeRow = [&](const fs::path& path, std::uint16_t bits, std::uint16_t format, const void* row) {
    writeTiffWith(
        path, [&](TIFF* tiff) { setSize(tiff, 3, 1, 1, bits, format, PHOTOMETRIC_MINISBLACK); },
        [&](TIFF* tiff) { ASSERT_GE(TIFFWriteScanline(tiff, const_cast<void*>(row), 0, 0), 0); });
  };
  writeRow(dir / "int16.tif", 16, SAMPLEFORMAT_INT, signedCodes);
  writeRow(dir / "double.tif", 64, SAMPLEFORMAT_IEEEFP, doubles);
  auto fromSigned = readImage(dir / "int16.tif");
  ASSERT_TRUE(fromSigned) << fromSigned.error().message;
  EXPECT_EQ(fromSigned->at(0, 0, 0), -1.0f);
  EXPECT_EQ(fromSigned->at(1, 0, 0), 0.0f);
  EXPECT_EQ(fromSigned->at(2, 0, 0), 1.0f);
  auto fromDouble = readImage(dir / "double.tif");
  ASSERT_TRUE(fromDouble) << fromDouble.error().message;
  EXPECT_EQ(readImageHeader(dir / "double.tif")->sampleType, SampleType::Float32);
  for (int x = 0; x < 3; ++x) EXPECT_EQ(fromDouble->at(x, 0, 0), float(doubles[x]));
}

TEST(TiffFile, PaletteBecomesRgb) {
  test::TempDir dir;
  std::vector<std::uint16_t> red(256, 0), green(256, 0), blue(256, 0);
  red[1] = 65535;  // index 1: pure red; index 0: black
  writeTiffWith(
      dir / "palette.tif",
      [&](TIFF* tiff) {
        setSize(tiff, 2, 1, 1, 8, SAMPLEFORMAT_UINT, PHOTOMETRIC_PALETTE);
        TIFFSetField(tiff, TIFFTAG_COLORMAP, red.data(), green.data(), blue.data());
      },
      [&](TIFF* tiff) {
        std::uint8_t row[] = {0, 1};
        ASSERT_GE(TIFFWriteScanline(tiff, row, 0, 0), 0);
      });
  auto image = readImage(dir / "palette.tif");
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->channels(), 3);
  EXPECT_EQ(image->at(0, 0, 0), 0.0f);
  EXPECT_EQ(image->at(1, 0, 0), 1.0f);
  EXPECT_EQ(image->at(1, 0, 1), 0.0f);
}

TEST(TiffFile, ManyChannelsRoundTripAndDamageIsAnErrorNamingTheFile) {
  test::TempDir dir;
  Image image(23, 17, 6);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) image.pixels()[i] = float(i % 251) / 250.0f;
  ASSERT_TRUE(writeImage(dir / "six.tif", image, {.sampleType = SampleType::Float32}));
  auto read = readImage(dir / "six.tif");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->channels(), 6);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) ASSERT_EQ(read->pixels()[i], image.pixels()[i]);

  const std::string bytes = test::readBytes(dir / "six.tif");
  for (std::size_t length : {bytes.size() / 2, std::size_t(12)}) {
    test::writeBytes(dir / "cut.tif", bytes.substr(0, length));
    auto cut = readImage(dir / "cut.tif");
    ASSERT_FALSE(cut) << length;
    EXPECT_NE(cut.error().message.find((dir / "cut.tif").string()), std::string::npos) << cut.error().message;
  }
}

}  // namespace
}  // namespace lfcam
