// Lytro raw packings: known byte patterns (the layouts of docs/formats.md) and round trips.
#include <gtest/gtest.h>

#include <random>

#include "raw_io/raw_packing.hpp"

namespace lfcam {
namespace {

TEST(RawPacking, TwelveBitBigEndianKnownBytes) {
  const std::vector<std::uint16_t> pixels{0xABC, 0x123};
  const auto bytes = packRaw(RawPacking::Bits12BigEndian, pixels);
  EXPECT_EQ(bytes, (std::vector<std::uint8_t>{0xAB, 0xC1, 0x23}));
  std::vector<std::uint16_t> back(2);
  unpackRaw(RawPacking::Bits12BigEndian, bytes, back);
  EXPECT_EQ(back, pixels);
}

TEST(RawPacking, TenBitLittleEndianKnownBytes) {
  // Bytes 0-3: the high 8 bits of pixels 0-3; byte 4: their low 2 bits, pixel k at bits 2k.
  const std::vector<std::uint16_t> pixels{0x3FF, 0x000, 0x155, 0x2AA};
  const auto bytes = packRaw(RawPacking::Bits10LittleEndian, pixels);
  EXPECT_EQ(bytes, (std::vector<std::uint8_t>{0xFF, 0x00, 0x55, 0xAA, 0x93}));
  std::vector<std::uint16_t> back(4);
  unpackRaw(RawPacking::Bits10LittleEndian, std::vector<std::uint8_t>{0x01, 0x80, 0x00, 0x00, 0xE4}, back);
  EXPECT_EQ(back, (std::vector<std::uint16_t>{0x004, 0x201, 0x002, 0x003}));
}

TEST(RawPacking, SixteenBitLittleEndianKnownBytes) {
  const auto bytes = packRaw(RawPacking::Bits16LittleEndian, std::vector<std::uint16_t>{0x1234, 0xFFEE});
  EXPECT_EQ(bytes, (std::vector<std::uint8_t>{0x34, 0x12, 0xEE, 0xFF}));
}

TEST(RawPacking, ByteCounts) {
  EXPECT_EQ(*packedByteCount(RawPacking::Bits12BigEndian, 3280 * 3280), 3280u * 3280u * 3 / 2);
  EXPECT_EQ(*packedByteCount(RawPacking::Bits10LittleEndian, 7728 * 5368), 7728u * 5368u * 5 / 4);
  EXPECT_EQ(*packedByteCount(RawPacking::Bits12BigEndian, 3), 6u);      // a partial pair is padded
  EXPECT_EQ(*packedByteCount(RawPacking::Bits10LittleEndian, 5), 10u);  // a partial group too
  EXPECT_FALSE(packedByteCount(RawPacking::Bits16LittleEndian, std::size_t(-1)));
}

TEST(RawPacking, RandomRoundTripsAtEveryLength) {
  std::mt19937 rng(7);
  for (RawPacking packing :
       {RawPacking::Bits12BigEndian, RawPacking::Bits10LittleEndian, RawPacking::Bits16LittleEndian}) {
    const unsigned mask = (1u << rawPackingBits(packing)) - 1;
    for (std::size_t n : {1, 2, 3, 4, 5, 7, 8, 1001}) {
      std::vector<std::uint16_t> pixels(n);
      for (auto& p : pixels) p = std::uint16_t(rng() & mask);
      const auto bytes = packRaw(packing, pixels);
      ASSERT_EQ(bytes.size(), *packedByteCount(packing, n));
      std::vector<std::uint16_t> back(n);
      unpackRaw(packing, bytes, back);
      EXPECT_EQ(back, pixels) << rawPackingBits(packing) << " bits, " << n << " pixels";
    }
  }
}

}  // namespace
}  // namespace lfcam
