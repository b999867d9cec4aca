#include "io/srgb.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <vector>

#include "lfcam/io/image_io.hpp"

namespace lfcam {

namespace {

double linearFromSrgbExact(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

double srgbFromLinearExact(double linear) {
  return linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

}  // namespace

float linearFromSrgb(float encoded) { return float(linearFromSrgbExact(encoded)); }
float srgbFromLinear(float linear) { return float(srgbFromLinearExact(linear)); }

namespace io {

namespace {

// Buckets of [0, 1] for srgb8FromLinear (a power of two, so that bucket edges are exact floats):
// sRGB's steepest slope, 12.92 x 255 codes per unit at 0, puts at most one code boundary in each.
constexpr int kBuckets = 4096;

// For srgb8CodesOf, a float's top 16 bits: sign, exponent and 7 bits of mantissa, a bucket 1/128 of
// its value wide. Adjacent sRGB codes lie at least 0.89 % apart above code 10 and 3e-4 apart below
// it, so a bucket holds at most two codes.
std::uint32_t bucketOf(float value) { return std::bit_cast<std::uint32_t>(value) >> 16; }

struct Tables {
  std::array<float, 256> linear;                 // code -> linear
  std::array<float, 255> thresholds;             // linear value halfway (in code space) between k and k+1
  std::array<std::uint8_t, kBuckets> firstCode;  // the code of each bucket's lower edge
  std::vector<std::uint8_t> firstCodeIn;         // bucketOf -> the lowest code at or above its start
  Tables() : firstCodeIn(std::size_t(1) << 16, 255) {
    // The same float as linearFromSrgb(k / 255.0f), so callers computing it themselves agree.
    for (int k = 0; k < 256; ++k) linear[k] = linearFromSrgb(float(k) / 255.0f);
    for (int k = 0; k < 255; ++k) thresholds[k] = float(linearFromSrgbExact((k + 0.5) / 255.0));
    for (int b = 0; b < kBuckets; ++b) firstCode[b] = codeByBinarySearch(float(b) / kBuckets);
    for (int k = 255; k >= 0; --k) firstCodeIn[bucketOf(linear[k])] = std::uint8_t(k);
  }
  // The code is the number of thresholds at or below the value: rounding in code space.
  std::uint8_t codeByBinarySearch(float value) const {
    return std::uint8_t(std::upper_bound(thresholds.begin(), thresholds.end(), value) - thresholds.begin());
  }
};

const Tables& tables() {
  static const Tables instance;
  return instance;
}

}  // namespace

float linearFromSrgb8(std::uint8_t code) { return tables().linear[code]; }
const std::array<float, 256>& linearOfSrgb8Codes() { return tables().linear; }

std::uint8_t srgb8FromLinear(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  const Tables& t = tables();
  int code = t.firstCode[int(linear * kBuckets)];
  while (code < 255 && t.thresholds[code] <= linear) ++code;
  return std::uint8_t(code);
}

std::uint8_t srgb8FromLinearReference(float linear) {
  if (!(linear > 0.0f)) return 0;
  return tables().codeByBinarySearch(linear);
}

bool srgb8CodesOf(std::span<const float> linear, std::uint8_t* codes) {
  const Tables& t = tables();
  const std::uint8_t* firstCodeIn = t.firstCodeIn.data();
  const auto bitsOf = [&](int code) { return std::bit_cast<std::uint32_t>(t.linear[std::size_t(code)]); };
  for (std::size_t i = 0; i < linear.size(); ++i) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(linear[i]);
    int code = firstCodeIn[bits >> 16];
    if (bitsOf(code) != bits && !(code < 255 && bitsOf(++code) == bits)) return false;
    codes[i] = std::uint8_t(code);
  }
  return true;
}

std::uint8_t unorm8FromLinear(float value) {
  if (!(value > 0.0f)) return 0;
  return std::uint8_t(std::lround(std::min(value, 1.0f) * 255.0f));
}

std::uint16_t unorm16FromLinear(float value) {
  if (!(value > 0.0f)) return 0;
  return std::uint16_t(std::lround(double(std::min(value, 1.0f)) * 65535.0));
}

}  // namespace io
}  // namespace lfcam
