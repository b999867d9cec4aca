// Packed raw sensor samples, as Lytro cameras store them (docs/formats.md, "Lytro containers"):
//   12-bit big-endian (first-generation F01): 2 pixels in 3 bytes,
//     p0 = b0 << 4 | b1 >> 4,  p1 = (b1 & 0x0f) << 8 | b2;
//   10-bit little-endian (Illum): 4 pixels in 5 bytes, bytes 0-3 the high 8 bits of pixels 0-3,
//     byte 4 their low 2 bits, pixel k in bits 2k..2k+1;
//   16-bit little-endian (Lytro's simulator and third-party tools): 2 bytes per pixel.
// Pixels run row-major from the top-left. Scalar code: unpacking a full Illum frame takes a
// fraction of a second, far below the decode that follows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace lfcam {

enum class RawPacking { Bits12BigEndian, Bits10LittleEndian, Bits16LittleEndian };

int rawPackingBits(RawPacking packing);
// Bytes holding `pixels` samples (rounded up to whole bytes); nullopt on overflow.
std::optional<std::size_t> packedByteCount(RawPacking packing, std::size_t pixels);

// Unpacks exactly out.size() samples; `bytes` must hold packedByteCount of them (checked by the
// caller: these functions assume it).
void unpackRaw(RawPacking packing, std::span<const std::uint8_t> bytes, std::span<std::uint16_t> out);
// The inverse; values are masked to the packing's bit depth.
std::vector<std::uint8_t> packRaw(RawPacking packing, std::span<const std::uint16_t> samples);

}  // namespace lfcam
