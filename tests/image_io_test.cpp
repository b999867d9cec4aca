#include "lfcam/io/image_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

// An image of values in [0, 1]; `quantise` snaps them to what the sample type holds exactly.
Image randomImage(int width, int height, int channels, unsigned seed) {
  Image image(width, height, channels);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& value : image.pixels()) value = uniform(random);
  return image;
}

// 8-bit: colour channels on the sRGB codes, alpha (last of 2 or 4) on linear codes.
void quantiseTo8Bit(Image& image) {
  const bool hasAlpha = image.channels() == 2 || image.channels() == 4;
  for (int c = 0; c < image.channels(); ++c) {
    const bool alpha = hasAlpha && c == image.channels() - 1;
    for (std::size_t i = 0; i < image.planeSize(); ++i) {
      float& value = image.plane(c)[i];
      value = alpha ? std::round(value * 255.0f) / 255.0f
                    : linearFromSrgb(std::round(srgbFromLinear(value) * 255.0f) / 255.0f);
    }
  }
}

std::size_t entriesIn(const fs::path& folder) {
  return std::size_t(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

float maxDifference(const Image& a, const Image& b) {
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  EXPECT_EQ(a.channels(), b.channels());
  if (a.pixels().size() != b.pixels().size()) return INFINITY;
  float worst = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) worst = std::max(worst, std::abs(a.pixels()[i] - b.pixels()[i]));
  return worst;
}

// The error's message names the file.
template <class T>
void expectErrorNaming(const Result<T>& result, const fs::path& path) {
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find(path.filename().string()), std::string::npos) << result.error().message;
  EXPECT_EQ(result.error().message.find('\n'), std::string::npos) << result.error().message;
}

// The file `full` cut to half its length, and to its first `headerBytes`: each read is an error
// naming the cut file, not an image padded with grey.
void expectCutShortCopiesFail(const fs::path& full, std::size_t headerBytes) {
  const std::string bytes = test::readBytes(full);
  const std::string extension = full.extension().string();
  const fs::path half = full.parent_path() / ("half" + extension), header = full.parent_path() / ("header" + extension);
  test::writeBytes(half, bytes.substr(0, bytes.size() / 2));
  expectErrorNaming(readImage(half), half);
  test::writeBytes(header, bytes.substr(0, headerBytes));
  expectErrorNaming(readImage(header), header);
}

TEST(ImageIoSrgb, TransferFunctionIsTheStandardOne) {
  EXPECT_FLOAT_EQ(linearFromSrgb(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(linearFromSrgb(1.0f), 1.0f);
  EXPECT_NEAR(linearFromSrgb(0.5f), 0.214041f, 1e-6);
  EXPECT_NEAR(srgbFromLinear(0.214041f), 0.5f, 1e-6);
  EXPECT_NEAR(linearFromSrgb(0.04045f), 0.04045f / 12.92f, 1e-7);
}

TEST(ImageIoPng, EveryEightBitCodeRoundTripsExactly) {
  test::TempDir dir;
  Image image(256, 1, 1);
  for (int code = 0; code < 256; ++code) image.at(code, 0, 0) = linearFromSrgb(code / 255.0f);
  ASSERT_TRUE(writeImage(dir / "codes.png", image));
  auto read = readImage(dir / "codes.png");
  ASSERT_TRUE(read) << read.error().message;
  for (int code = 0; code < 256; ++code) EXPECT_EQ(read->at(code, 0, 0), image.at(code, 0, 0)) << code;
}

TEST(ImageIoPng, EightBitRoundTripIsExactForEveryChannelCount) {
  test::TempDir dir;
  for (int channels = 1; channels <= 4; ++channels) {
    Image image = randomImage(37, 23, channels, 10 + channels);
    quantiseTo8Bit(image);
    const fs::path path = dir / (std::to_string(channels) + "-channels.png");
    ASSERT_TRUE(writeImage(path, image));
    auto header = readImageHeader(path);
    ASSERT_TRUE(header);
    EXPECT_EQ(header->width, 37);
    EXPECT_EQ(header->height, 23);
    EXPECT_EQ(header->channels, channels);
    EXPECT_EQ(header->sampleType, SampleType::UInt8);
    auto read = readImage(path);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(maxDifference(*read, image), 0.0f) << channels << " channels";
  }
}

TEST(ImageIoPng, WritingClampsToTheCodeRange) {
  test::TempDir dir;
  Image image(3, 1, 1);
  image.at(0, 0, 0) = -0.5f;
  image.at(1, 0, 0) = 7.0f;
  image.at(2, 0, 0) = NAN;
  for (SampleType type : {SampleType::UInt8, SampleType::UInt16}) {
    ASSERT_TRUE(writeImage(dir / "clamp.png", image, {.sampleType = type}));
    auto read = readImage(dir / "clamp.png");
    ASSERT_TRUE(read);
    EXPECT_EQ(read->at(0, 0, 0), 0.0f);
    EXPECT_EQ(read->at(1, 0, 0), 1.0f);
    EXPECT_EQ(read->at(2, 0, 0), 0.0f);
  }
}

TEST(ImageIoPng, SixteenBitIsLinearWithinOneCode) {
  test::TempDir dir;
  for (int channels : {1, 3, 4}) {
    const Image image = randomImage(41, 17, channels, 20 + channels);
    const fs::path path = dir / "deep.png";
    ASSERT_TRUE(writeImage(path, image, {.sampleType = SampleType::UInt16}));
    auto header = readImageHeader(path);
    ASSERT_TRUE(header);
    EXPECT_EQ(header->sampleType, SampleType::UInt16);
    auto read = readImage(path);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_LE(maxDifference(*read, image), 0.5f / 65535.0f + 1e-7f);
  }
}

TEST(ImageIoTiff, EightSixteenAndFloatRoundTrip) {
  test::TempDir dir;
  Image image = randomImage(19, 11, 3, 3);
  // Default for TIFF is 16-bit.
  ASSERT_TRUE(writeImage(dir / "a.tif", image));
  auto header = readImageHeader(dir / "a.tif");
  ASSERT_TRUE(header);
  EXPECT_EQ(header->sampleType, SampleType::UInt16);
  auto read16 = readImage(dir / "a.tif");
  ASSERT_TRUE(read16);
  EXPECT_LE(maxDifference(*read16, image), 0.5f / 65535.0f + 1e-7f);

  ASSERT_TRUE(writeImage(dir / "f.tiff", image, {.sampleType = SampleType::Float32}));
  auto readFloat = readImage(dir / "f.tiff");
  ASSERT_TRUE(readFloat);
  EXPECT_EQ(maxDifference(*readFloat, image), 0.0f);

  quantiseTo8Bit(image);
  ASSERT_TRUE(writeImage(dir / "b.tif", image, {.sampleType = SampleType::UInt8}));
  auto read8 = readImage(dir / "b.tif");
  ASSERT_TRUE(read8);
  EXPECT_EQ(maxDifference(*read8, image), 0.0f);
}

TEST(ImageIoExr, FloatRoundTripIsExactIncludingValuesOutsideZeroOne) {
  test::TempDir dir;
  for (int channels : {1, 2, 3, 4, 5, 12}) {  // 12: channel10 and channel11 come after channel9
    Image image = randomImage(13, 9, channels, 30 + channels);
    image.at(0, 0, 0) = -2.5f;
    image.at(1, 0, 0) = 1e6f;
    ASSERT_TRUE(writeImage(dir / "a.exr", image));
    auto header = readImageHeader(dir / "a.exr");
    ASSERT_TRUE(header);
    EXPECT_EQ(header->sampleType, SampleType::Float32);
    EXPECT_EQ(header->channels, channels);
    auto read = readImage(dir / "a.exr");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(maxDifference(*read, image), 0.0f) << channels;
  }
}

TEST(ImageIoJpeg, LossyButClose) {
  test::TempDir dir;
  Image image(64, 48, 3);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) image.at(x, y, c) = linearFromSrgb((x + y + 20.0f * c) / 160.0f);
  ASSERT_TRUE(writeImage(dir / "a.jpg", image, {.jpegQuality = 98}));
  auto read = readImage(dir / "a.jpg");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_LT(maxDifference(*read, image), 0.03f);
  EXPECT_FALSE(writeImage(dir / "b.jpg", image, {.sampleType = SampleType::UInt16}));
  EXPECT_FALSE(writeImage(dir / "c.jpg", image, {.jpegQuality = 0}));
}

TEST(ImageIoExr, TruncatedFileIsAnErrorNamingIt) {
  test::TempDir dir;
  ASSERT_TRUE(writeImage(dir / "full.exr", randomImage(64, 64, 3, 12)));
  expectCutShortCopiesFail(dir / "full.exr", 40);
}

TEST(ImageIoJpeg, GreyRoundTripsAndDamageIsAnError) {
  test::TempDir dir;
  const Image grey = randomImage(40, 30, 1, 11);
  ASSERT_TRUE(writeImage(dir / "grey.jpg", grey, {.jpegQuality = 100}));
  auto header = readImageHeader(dir / "grey.jpg");
  ASSERT_TRUE(header) << header.error().message;
  EXPECT_EQ(header->channels, 1);
  EXPECT_EQ(header->width, 40);
  auto read = readImage(dir / "grey.jpg");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->channels(), 1);

  expectCutShortCopiesFail(dir / "grey.jpg", 20);
}

TEST(ImageIoDescription, RoundTripsInEveryFormatThatHasOne) {
  test::TempDir dir;
  const Image image = randomImage(8, 8, 3, 5);
  for (const char* name : {"d.png", "d.tif", "d.exr", "d.jpg"}) {
    ASSERT_TRUE(writeImage(dir / name, image, {.description = "lfcam lenslet nu=9 nv=9"})) << name;
    auto description = readImageDescription(dir / name);
    ASSERT_TRUE(description) << description.error().message;
    EXPECT_EQ(*description, "lfcam lenslet nu=9 nv=9") << name;
    ASSERT_TRUE(writeImage(dir / name, image));
    description = readImageDescription(dir / name);
    ASSERT_TRUE(description);
    EXPECT_EQ(*description, "") << name;
  }
  ASSERT_TRUE(writeImage(dir / "d.pfm", image, {.description = "dropped"}));
  auto description = readImageDescription(dir / "d.pfm");
  ASSERT_TRUE(description);
  EXPECT_EQ(*description, "");
}

TEST(ImageIoPfm, RoundTripsOneAndThreeChannels) {
  test::TempDir dir;
  for (int channels : {1, 3}) {
    Image image = randomImage(7, 5, channels, 40 + channels);
    image.at(0, 0, 0) = -3.25f;
    ASSERT_TRUE(writeImage(dir / "a.pfm", image));
    const std::string bytes = test::readBytes(dir / "a.pfm");
    EXPECT_EQ(bytes.substr(0, 3), channels == 3 ? "PF\n" : "Pf\n");
    auto read = readImage(dir / "a.pfm");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(maxDifference(*read, image), 0.0f);
  }
  EXPECT_FALSE(writeImage(dir / "b.pfm", Image(2, 2, 2)));
  EXPECT_FALSE(writeImage(dir / "b.pfm", Image(2, 2, 1), {.sampleType = SampleType::UInt8}));
}

// A PFM written by hand: rows bottom to top, in either byte order.
std::string handMadePfm(bool bigEndian, const std::vector<float>& valuesBottomRowFirst, int width, int height) {
  std::string bytes =
      "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n" + (bigEndian ? "1.0" : "-1.0") + "\n";
  for (float value : valuesBottomRowFirst) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, 4);
    for (int i = 0; i < 4; ++i) {
      const int shift = bigEndian ? 24 - 8 * i : 8 * i;
      bytes += char((bits >> shift) & 0xff);
    }
  }
  return bytes;
}

TEST(ImageIoPfm, ReadsBothByteOrdersBottomRowFirst) {
  test::TempDir dir;
  // File order: bottom row (1, 2), then top row (3, 4).
  for (bool bigEndian : {false, true}) {
    test::writeBytes(dir / "h.pfm", handMadePfm(bigEndian, {1, 2, 3, 4}, 2, 2));
    auto read = readImage(dir / "h.pfm");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->at(0, 0, 0), 3.0f);
    EXPECT_EQ(read->at(1, 0, 0), 4.0f);
    EXPECT_EQ(read->at(0, 1, 0), 1.0f);
    EXPECT_EQ(read->at(1, 1, 0), 2.0f);
  }
}

TEST(ImageIoPfm, TruncatedAndAbsurdHeadersAreErrors) {
  test::TempDir dir;
  const fs::path truncated = dir / "short.pfm";
  std::string bytes = handMadePfm(false, {1, 2, 3, 4}, 2, 2);
  test::writeBytes(truncated, bytes.substr(0, bytes.size() - 3));
  auto read = readImage(truncated);
  expectErrorNaming(read, truncated);
  EXPECT_NE(read.error().message.find("truncated: expected 16 bytes of pixels, found 13"), std::string::npos)
      << read.error().message;

  const fs::path absurd = dir / "absurd.pfm";
  test::writeBytes(absurd, "PF\n2147483647 2147483647\n-1\n" + std::string(1000, '\0'));
  read = readImage(absurd);
  expectErrorNaming(read, absurd);
  EXPECT_NE(read.error().message.find("truncated"), std::string::npos);
  EXPECT_FALSE(readImageHeader(absurd));

  for (const char* header : {"PF\n-3 4\n-1\n", "PF\n3 4\n0\n", "PF\n3 x\n-1\n", "PF\n3 4\n-1"}) {
    test::writeBytes(dir / "bad.pfm", std::string(header) + std::string(200, '\0'));
    expectErrorNaming(readImage(dir / "bad.pfm"), dir / "bad.pfm");
  }
}

TEST(ImageIoDetection, ByContentNotByName) {
  test::TempDir dir;
  const Image image = randomImage(4, 4, 3, 6);
  ASSERT_TRUE(writeImage(dir / "a.png", image));
  fs::rename(dir / "a.png", dir / "a.dat");
  EXPECT_TRUE(looksLikeImageFile(dir / "a.dat"));
  EXPECT_TRUE(readImage(dir / "a.dat"));
  ASSERT_TRUE(writeImage(dir / "b.pfm", image));
  fs::rename(dir / "b.pfm", dir / "b.png");
  EXPECT_TRUE(looksLikeImageFile(dir / "b.png"));
  auto pfm = readImage(dir / "b.png");
  ASSERT_TRUE(pfm) << pfm.error().message;
  EXPECT_EQ(maxDifference(*pfm, image), 0.0f);
  test::writeBytes(dir / "text.png", "hello, not an image");
  EXPECT_FALSE(looksLikeImageFile(dir / "text.png"));
  EXPECT_FALSE(looksLikeImageFile(dir / "missing.png"));
  EXPECT_FALSE(looksLikeImageFile(dir.path()));
  for (const char* name : {"t.tif", "e.exr", "j.jpg"}) {
    ASSERT_TRUE(writeImage(dir / name, image));
    EXPECT_TRUE(looksLikeImageFile(dir / name)) << name;
  }
}

TEST(ImageIoErrors, MissingFileFolderAndNonImage) {
  test::TempDir dir;
  auto missing = readImage(dir / "missing.png");
  expectErrorNaming(missing, dir / "missing.png");
  EXPECT_EQ(missing.error().code, ErrorCode::Io);

  fs::create_directories(dir / "folder.png");
  expectErrorNaming(readImage(dir / "folder.png"), dir / "folder.png");
  EXPECT_FALSE(readImageHeader(dir / "folder.png"));
  EXPECT_FALSE(readImageDescription(dir / "folder.png"));

  test::writeBytes(dir / "text.png", "hello, not an image");
  auto text = readImage(dir / "text.png");
  expectErrorNaming(text, dir / "text.png");
  EXPECT_EQ(text.error().code, ErrorCode::Format);
}

TEST(ImageIoErrors, CorruptAndTruncatedPng) {
  test::TempDir dir;
  const Image image = randomImage(64, 64, 3, 7);  // noise: it does not compress
  ASSERT_TRUE(writeImage(dir / "full.png", image));
  const std::string bytes = test::readBytes(dir / "full.png");

  test::writeBytes(dir / "half.png", bytes.substr(0, bytes.size() / 2));
  expectErrorNaming(readImage(dir / "half.png"), dir / "half.png");

  std::string garbled = bytes;
  for (std::size_t i = 100; i < garbled.size() - 20; i += 7) garbled[i] = char(garbled[i] ^ 0x5a);
  test::writeBytes(dir / "garbled.png", garbled);
  expectErrorNaming(readImage(dir / "garbled.png"), dir / "garbled.png");

  test::writeBytes(dir / "signature.png", bytes.substr(0, 8));
  expectErrorNaming(readImage(dir / "signature.png"), dir / "signature.png");

  // A header read (lfcam info) skips the image data: it still finds the file cut short, but
  // leaves damage inside the data to the read of the pixels.
  expectErrorNaming(readImageHeader(dir / "half.png"), dir / "half.png");
  expectErrorNaming(readImageHeader(dir / "signature.png"), dir / "signature.png");
  std::string damagedData = bytes;
  damagedData[bytes.size() / 2] = char(damagedData[bytes.size() / 2] ^ 0x5a);
  test::writeBytes(dir / "damaged.png", damagedData);
  auto header = readImageHeader(dir / "damaged.png");
  ASSERT_TRUE(header) << header.error().message;
  EXPECT_EQ(header->width, 64);
  auto pixels = readImage(dir / "damaged.png");
  expectErrorNaming(pixels, dir / "damaged.png");
  EXPECT_NE(pixels.error().message.find("fails its CRC check"), std::string::npos) << pixels.error().message;
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string bigEndian32(std::uint32_t value) {
  return {char(value >> 24), char(value >> 16), char(value >> 8), char(value)};
}

std::string pngChunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  return bigEndian32(std::uint32_t(data.size())) + body + bigEndian32(crc32(body));
}

// A grey 8-bit PNG whose IHDR says width x height and whose data holds one row of `codes`, made
// by hand (a stored deflate block), so that what the file holds does not depend on lfcam's writer.
std::string handMadeGreyPng(std::uint32_t width, std::uint32_t height, const std::string& codes) {
  const std::string ihdr = bigEndian32(width) + bigEndian32(height) + std::string("\x08\x00\x00\x00\x00", 5);
  const std::string raw = std::string(1, '\0') + codes;  // filter byte, then the pixels
  std::uint32_t a = 1, b = 0;
  for (unsigned char byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  const std::uint16_t length = std::uint16_t(raw.size());
  std::string zlib = std::string("\x78\x01\x01", 3) + char(length & 0xff) + char(length >> 8) + char(~length & 0xff) +
                     char((~length >> 8) & 0xff) + raw + bigEndian32((b << 16) | a);
  return "\x89PNG\r\n\x1a\n" + pngChunk("IHDR", ihdr) + pngChunk("IDAT", zlib) + pngChunk("IEND", "");
}

TEST(ImageIoPng, EightBitFilesHoldSrgbCodes) {
  test::TempDir dir;
  test::writeBytes(dir / "grey.png", handMadeGreyPng(2, 1, std::string("\x80\xff", 2)));
  auto read = readImage(dir / "grey.png");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_FLOAT_EQ(read->at(0, 0, 0), linearFromSrgb(128 / 255.0f));
  EXPECT_NEAR(read->at(0, 0, 0), 0.2158605f, 1e-6);
  EXPECT_EQ(read->at(1, 0, 0), 1.0f);
}

TEST(ImageIoErrors, PngWithAbsurdDimensionsIsRefusedBeforeAllocating) {
  test::TempDir dir;
  // Valid chunks claiming 900000 x 900000 pixels, with one byte of data.
  test::writeBytes(dir / "huge.png", handMadeGreyPng(900000, 900000, "a"));
  auto read = readImage(dir / "huge.png");
  expectErrorNaming(read, dir / "huge.png");
  EXPECT_NE(read.error().message.find("900000x900000"), std::string::npos) << read.error().message;
}

TEST(ImageIoWrite, RefusesWhatTheFormatCannotHold) {
  test::TempDir dir;
  const Image image = randomImage(4, 4, 3, 8);
  auto expectUsage = [](const Status& status) {
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().code, ErrorCode::Usage);
  };
  expectUsage(writeImage(dir / "a.png", image, {.sampleType = SampleType::Float32}));
  expectUsage(writeImage(dir / "a.exr", image, {.sampleType = SampleType::UInt8}));
  expectUsage(writeImage(dir / "a.png", Image(4, 4, 5)));
  expectUsage(writeImage(dir / "a.jpg", Image(4, 4, 2)));
  expectUsage(writeImage(dir / "a.xyz", image));
  expectUsage(writeImage(dir / "a.png", Image()));
  EXPECT_EQ(entriesIn(dir.path()), 0u);
}

TEST(ImageIoWrite, FailureLeavesNothingBehindAndNamesTheFile) {
  test::TempDir dir;
  const Image image = randomImage(4, 4, 3, 9);
  Status status = writeImage(dir / "no" / "such" / "folder.png", image);
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("folder.png"), std::string::npos) << status.error().message;
  status = writeImage(dir / "no" / "such" / "folder.pfm", image);
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("folder.pfm"), std::string::npos) << status.error().message;
  // A folder where the file should go.
  fs::create_directories(dir / "taken.png");
  EXPECT_FALSE(writeImage(dir / "taken.png", image));
  EXPECT_EQ(entriesIn(dir.path()), 1u);
}

}  // namespace
}  // namespace lfcam
