// 8-bit sRGB codes to linear values and back, through tables: exact round trips and no pow()
// per sample.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace lfcam::io {

// Linear value of an 8-bit sRGB code; the table of all 256, for loops over many samples.
float linearFromSrgb8(std::uint8_t code);
const std::array<float, 256>& linearOfSrgb8Codes();
// The nearest 8-bit sRGB code to a linear value (clamped to [0, 1]; NaN gives 0): a table lookup
// by the value's bucket and a step or two, the same code as the reference's binary search.
std::uint8_t srgb8FromLinear(float linear);
std::uint8_t srgb8FromLinearReference(float linear);
// The codes whose linearFromSrgb8 are exactly `linear` (same bits), into `codes`; false as soon
// as a value is none of the 256. One table look-up per value, for millions of samples.
bool srgb8CodesOf(std::span<const float> linear, std::uint8_t* codes);

// Integer codes of linear files: value = code / max, code = round(clamp(value) * max).
std::uint8_t unorm8FromLinear(float value);
std::uint16_t unorm16FromLinear(float value);

}  // namespace lfcam::io
