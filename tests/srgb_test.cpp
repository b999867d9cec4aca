// The fast sRGB encoder (bucket table and a step or two) against its binary-search reference, at
// every code boundary, bucket edge and their neighbouring floats, and on a dense sweep; the SIMD
// encoder of many values against the one of a value.
#include "io/srgb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "lfcam/io/image_io.hpp"

namespace lfcam::io {
namespace {

TEST(Srgb8FromLinear, MatchesTheReferenceEverywhere) {
  std::vector<float> values = {0.0f,
                               -1.0f,
                               1.0f,
                               2.0f,
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::denorm_min()};
  for (int k = 0; k < 255; ++k) values.push_back(linearFromSrgb((k + 0.5f) / 255.0f));  // near each boundary
  for (int b = 0; b <= 4096; ++b) values.push_back(float(b) / 4096.0f);                 // bucket edges
  const std::size_t edges = values.size();
  for (std::size_t i = 0; i < edges; ++i) {
    values.push_back(std::nextafter(values[i], 0.0f));
    values.push_back(std::nextafter(values[i], 2.0f));
  }
  for (int i = 0; i <= 1 << 22; ++i) values.push_back(float(i) / float(1 << 22));
  for (const float value : values) ASSERT_EQ(srgb8FromLinear(value), srgb8FromLinearReference(value)) << value;
  // And the reference is the round trip of every code.
  for (int code = 0; code < 256; ++code) EXPECT_EQ(srgb8FromLinearReference(linearFromSrgb8(std::uint8_t(code))), code);
}

// Random values over the range a light field holds and far beyond, the toe's edge and the values
// that are not numbers, at every length of a last partial vector.
TEST(SrgbFromLinearInPlace, MatchesTheOneValueEncoderButForRareRoundings) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), exponent(-40.0f, 38.0f);
  std::vector<float> values = {0.0f,
                               -0.5f,
                               0.0031308f,
                               std::nextafter(0.0031308f, 1.0f),
                               1.0f,
                               1e38f,
                               std::numeric_limits<float>::denorm_min(),
                               std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN()};
  for (int i = 0; i < 1 << 20; ++i) values.push_back(unit(random));
  for (int i = 0; i < 1 << 16; ++i) values.push_back(std::pow(10.0f, exponent(random)));
  std::size_t differing = 0;
  for (std::size_t length = values.size() - 17; length <= values.size(); ++length) {
    std::vector<float> encoded(values.begin(), values.begin() + std::ptrdiff_t(length));
    srgbFromLinear(std::span<float>(encoded));
    for (std::size_t i = 0; i < length; ++i) {
      const float expected = srgbFromLinear(values[i]);
      if (std::isnan(expected)) {
        ASSERT_TRUE(std::isnan(encoded[i])) << values[i];
      } else if (encoded[i] != expected) {
        ++differing;
        ASSERT_TRUE(encoded[i] == std::nextafter(expected, 0.0f) || encoded[i] == std::nextafter(expected, 2.0f))
            << values[i] << ": " << encoded[i] << " against " << expected;
      }
    }
  }
  EXPECT_LE(differing, 18u);  // of 18 x 1.1 million; none when this test was written
}

}  // namespace
}  // namespace lfcam::io
