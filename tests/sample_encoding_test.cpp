// The native file's sample encodings and chunk filters, against scalar references.
#include "io/sample_encoding.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "io/hdf5_chunk_codec.hpp"
#include "io/srgb.hpp"

namespace lfcam::io {
namespace {

std::vector<float> roundTrip(const SampleEncoding& encoding, const std::vector<float>& values, bool& exact) {
  std::vector<unsigned char> codes(values.size() * bytesPerSample(encoding.kind));
  exact = encodeExactly(encoding, values, codes.data());
  std::vector<float> back(values.size());
  if (exact) decodeSamples(encoding, codes.data(), values.size(), back.data());
  return back;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](float x, float y) {
           return std::bit_cast<std::uint32_t>(x) == std::bit_cast<std::uint32_t>(y);
         });
}

TEST(SampleEncoding, Srgb8TakesExactlyTheTablesValuesAndAgreesWithTheNearestCode) {
  for (int code = 0; code < 256; ++code) {
    const float value = linearFromSrgb8(std::uint8_t(code));
    std::uint8_t found = 0;
    ASSERT_TRUE(srgb8CodesOf(std::span<const float>(&value, 1), &found)) << code;
    EXPECT_EQ(found, code);
    EXPECT_EQ(found, srgb8FromLinear(value));  // the scalar reference
    for (const float near : {std::nextafter(value, -1.0f), std::nextafter(value, 2.0f)})
      EXPECT_FALSE(srgb8CodesOf(std::span<const float>(&near, 1), &found)) << code;
  }
  const float outside[] = {-0.0f, 1.5f, -0.25f, NAN, INFINITY};
  std::uint8_t found = 0;
  for (float value : outside) EXPECT_FALSE(srgb8CodesOf(std::span<const float>(&value, 1), &found)) << value;
}

TEST(SampleEncoding, EveryKindRoundTripsBitForBitOrRefuses) {
  std::vector<float> srgb, linear16, linear8, halves;
  for (int code = 0; code < 256; ++code) srgb.push_back(linearFromSrgb8(std::uint8_t(code)));
  for (int code = 0; code < 65536; ++code) linear16.push_back(float(code / 65535.0));  // as 16-bit PNGs decode
  for (int code = 0; code < 256; ++code) linear8.push_back(code / 255.0f);             // as 8-bit alpha decodes
  for (float value : {0.0f, -0.0f, 1.0f, -2.5f, 65504.0f, 0.000061035156f, 0.333251953125f}) halves.push_back(value);
  bool exact = false;
  EXPECT_TRUE(sameBits(roundTrip({SampleEncodingKind::Srgb8}, srgb, exact), srgb) && exact);
  EXPECT_TRUE(sameBits(roundTrip({SampleEncodingKind::Linear16, 1.0 / 65535.0}, linear16, exact), linear16) && exact);
  EXPECT_TRUE(sameBits(roundTrip({SampleEncodingKind::Linear8, 1.0 / 255.0}, linear8, exact), linear8) && exact);
  EXPECT_TRUE(sameBits(roundTrip({SampleEncodingKind::Float16}, halves, exact), halves) && exact);
  const std::vector<float> floats = {0.1f, -3.0f, 1e30f, -0.0f};
  EXPECT_TRUE(sameBits(roundTrip({SampleEncodingKind::Float32}, floats, exact), floats) && exact);

  for (SampleEncoding encoding :
       {SampleEncoding{SampleEncodingKind::Srgb8}, SampleEncoding{SampleEncodingKind::Linear16, 1.0 / 65535.0},
        SampleEncoding{SampleEncodingKind::Float16}}) {
    roundTrip(encoding, {0.5f, 0.1f}, exact);
    EXPECT_FALSE(exact) << int(encoding.kind);  // 0.1 is none of them
  }
  roundTrip({SampleEncodingKind::Linear16, 1.0 / 65535.0}, {-1.0f / 65535.0f}, exact);
  EXPECT_FALSE(exact);
}

TEST(SampleEncoding, TheMostCompactExactEncodingIsChosen) {
  const std::size_t viewValues = 16;
  std::vector<float> values(viewValues * 5);
  std::mt19937 random(1);
  std::uniform_int_distribution<int> code(0, 255);
  for (float& value : values) value = linearFromSrgb8(std::uint8_t(code(random)));
  EXPECT_EQ(exactEncodingOf(values, viewValues, kColorEncodings).kind, SampleEncodingKind::Srgb8);
  std::fill(values.begin(), values.end(), float(1000 / 65535.0));
  EXPECT_EQ(exactEncodingOf(values, viewValues, kColorEncodings).kind, SampleEncodingKind::Linear16);
  std::fill(values.begin(), values.end(), 0.25f);  // 16383.75 / 65535
  values.back() = 3.5f;
  EXPECT_EQ(exactEncodingOf(values, viewValues, kColorEncodings).kind, SampleEncodingKind::Float16);
  values.back() = 0.1f;
  EXPECT_EQ(exactEncodingOf(values, viewValues, kColorEncodings).kind, SampleEncodingKind::Float32);
  const std::vector<float> weights(viewValues * 2, 1.0f);
  EXPECT_EQ(exactEncodingOf(weights, viewValues, kWeightEncodings).kind, SampleEncodingKind::Linear8);
}

TEST(Hdf5ChunkCodec, FiltersRoundTripAndBadChunksAreDescribed) {
  std::vector<unsigned char> data(4000);
  std::iota(data.begin(), data.end(), 0);
  for (const ChunkFilters filters : {ChunkFilters{}, ChunkFilters{.shuffle = true}, ChunkFilters{.deflate = true},
                                     ChunkFilters{.shuffle = true, .deflate = true}}) {
    const std::vector<unsigned char> stored = filterChunk(data.data(), data.size(), 4, filters, 1);
    if (filters.deflate) {
      EXPECT_LT(stored.size(), data.size() / 4);
    }
    std::vector<unsigned char> back(data.size());
    EXPECT_EQ(unfilterChunk(stored.data(), stored.size(), 4, filters, back.data(), back.size()), "");
    EXPECT_EQ(back, data);
    // Too small or too large a destination: the chunk is not the size its dataset says.
    std::vector<unsigned char> small(data.size() - 4), large(data.size() + 4);
    EXPECT_NE(unfilterChunk(stored.data(), stored.size(), 4, filters, small.data(), small.size()), "");
    EXPECT_NE(unfilterChunk(stored.data(), stored.size(), 4, filters, large.data(), large.size()), "");
  }
  // HDF5's shuffle: the first bytes of all elements, then the second bytes, ...
  const unsigned char pairs[] = {1, 2, 3, 4, 5, 6};
  const std::vector<unsigned char> shuffled = filterChunk(pairs, 6, 2, {.shuffle = true}, 1);
  EXPECT_EQ(shuffled, (std::vector<unsigned char>{1, 3, 5, 2, 4, 6}));
  std::vector<unsigned char> garbage(100, 0xAB), out(4000);
  EXPECT_NE(unfilterChunk(garbage.data(), garbage.size(), 1, {.deflate = true}, out.data(), out.size()), "");
}

// szip with libhdf5's parameters for a 64 x 50 uint16 view (little-endian, difference coding).
constexpr SzipParameters kSzip16{
    .optionsMask = 32 | 8 | 128 | 1, .pixelsPerBlock = 32, .bitsPerPixel = 16, .pixelsPerScanline = 64};

TEST(Hdf5ChunkCodec, SzipRoundTripsSmoothCodesSmallAndRefusesWhatIsWrong) {
  std::vector<std::uint16_t> codes(64 * 50);
  for (std::size_t i = 0; i < codes.size(); ++i) codes[i] = std::uint16_t(1000 + (i % 64) * 3 + (i / 64) * 5);
  const auto* data = reinterpret_cast<const unsigned char*>(codes.data());
  const std::size_t bytes = codes.size() * 2;
  const ChunkFilters szip{.szip = kSzip16};
  const std::vector<unsigned char> stored = filterChunk(data, bytes, 2, szip, 1);
  ASSERT_FALSE(stored.empty());
  EXPECT_LT(stored.size(), bytes / 3);  // differences of 3 take a few bits each, not 16
  EXPECT_EQ(stored[0] | stored[1] << 8 | stored[2] << 16 | stored[3] << 24, int(bytes));  // libhdf5's header
  std::vector<unsigned char> back(bytes);
  EXPECT_EQ(unfilterChunk(stored.data(), stored.size(), 2, szip, back.data(), back.size()), "");
  EXPECT_EQ(std::memcmp(back.data(), data, bytes), 0);
  std::vector<unsigned char> small(bytes - 2), cut(stored.begin(), stored.begin() + 3);
  EXPECT_NE(unfilterChunk(stored.data(), stored.size(), 2, szip, small.data(), small.size()), "");
  EXPECT_NE(unfilterChunk(cut.data(), cut.size(), 2, szip, back.data(), back.size()), "");
  std::vector<unsigned char> corrupt = stored;
  corrupt.resize(corrupt.size() / 2);
  EXPECT_NE(unfilterChunk(corrupt.data(), corrupt.size(), 2, szip, back.data(), back.size()), "");

  // Noise does not shrink: the writer stores such a chunk unfiltered.
  std::mt19937 random(7);
  std::vector<unsigned char> noise(4096);
  for (unsigned char& byte : noise) byte = static_cast<unsigned char>(random());
  SzipParameters bytes8 = kSzip16;
  bytes8.bitsPerPixel = 8;
  EXPECT_TRUE(filterChunk(noise.data(), noise.size(), 1, {.szip = bytes8}, 1).empty());

  // Parameters libaec could not take (a zero block size divides by zero in it) are refused.
  EXPECT_TRUE(szipParametersValid(kSzip16, 2));
  EXPECT_FALSE(szipParametersValid(kSzip16, 1));
  for (const unsigned block : {0u, 7u, 64u}) {
    SzipParameters bad = kSzip16;
    bad.pixelsPerBlock = block;
    EXPECT_FALSE(szipParametersValid(bad, 2)) << block;
  }
  SzipParameters wide = kSzip16;
  wide.pixelsPerScanline = 0;
  EXPECT_FALSE(szipParametersValid(wide, 2));
  wide.pixelsPerScanline = 32 * 128 + 1;
  EXPECT_FALSE(szipParametersValid(wide, 2));
}

}  // namespace
}  // namespace lfcam::io
