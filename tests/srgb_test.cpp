// The fast sRGB encoder (bucket table and a step or two) against its binary-search reference, at
// every code boundary, bucket edge and their neighbouring floats, and on a dense sweep.
#include "io/srgb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "lfcam/image_io.hpp"

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

}  // namespace
}  // namespace lfcam::io
