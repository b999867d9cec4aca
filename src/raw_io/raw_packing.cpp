// Lytro raw packings (raw_packing.hpp). A trailing partial group (pixel counts that are not a
// multiple of 2 or 4) is packed as if padded with zeros, so every size round-trips.
#include "raw_io/raw_packing.hpp"

#include <limits>

namespace lfcam {

int rawPackingBits(RawPacking packing) {
  switch (packing) {
    case RawPacking::Bits12BigEndian: return 12;
    case RawPacking::Bits10LittleEndian: return 10;
    case RawPacking::Bits16LittleEndian: return 16;
  }
  return 16;
}

std::optional<std::size_t> packedByteCount(RawPacking packing, std::size_t pixels) {
  const std::size_t bits = std::size_t(rawPackingBits(packing));
  if (pixels > std::numeric_limits<std::size_t>::max() / 16) return std::nullopt;
  switch (packing) {
    case RawPacking::Bits12BigEndian: return (pixels + 1) / 2 * 3;
    case RawPacking::Bits10LittleEndian: return (pixels + 3) / 4 * 5;
    case RawPacking::Bits16LittleEndian: return pixels * bits / 8;
  }
  return std::nullopt;
}

void unpackRaw(RawPacking packing, std::span<const std::uint8_t> bytes, std::span<std::uint16_t> out) {
  const std::size_t n = out.size();
  switch (packing) {
    case RawPacking::Bits12BigEndian:
      for (std::size_t k = 0, b = 0; k < n; k += 2, b += 3) {
        out[k] = std::uint16_t(bytes[b] << 4 | bytes[b + 1] >> 4);
        if (k + 1 < n) out[k + 1] = std::uint16_t((bytes[b + 1] & 0x0f) << 8 | bytes[b + 2]);
      }
      break;
    case RawPacking::Bits10LittleEndian:
      for (std::size_t k = 0, b = 0; k < n; k += 4, b += 5) {
        const unsigned low = bytes[b + 4];
        for (std::size_t i = 0; i < 4 && k + i < n; ++i)
          out[k + i] = std::uint16_t(bytes[b + i] << 2 | ((low >> (2 * i)) & 3u));
      }
      break;
    case RawPacking::Bits16LittleEndian:
      for (std::size_t k = 0; k < n; ++k) out[k] = std::uint16_t(bytes[2 * k] | bytes[2 * k + 1] << 8);
      break;
  }
}

std::vector<std::uint8_t> packRaw(RawPacking packing, std::span<const std::uint16_t> samples) {
  const std::size_t n = samples.size();
  std::vector<std::uint8_t> bytes(*packedByteCount(packing, n), 0);
  auto at = [&](std::size_t k) -> unsigned { return k < n ? samples[k] : 0u; };
  switch (packing) {
    case RawPacking::Bits12BigEndian:
      for (std::size_t k = 0, b = 0; k < n; k += 2, b += 3) {
        const unsigned p0 = at(k) & 0xfffu, p1 = at(k + 1) & 0xfffu;
        bytes[b] = std::uint8_t(p0 >> 4);
        bytes[b + 1] = std::uint8_t((p0 & 0x0fu) << 4 | p1 >> 8);
        bytes[b + 2] = std::uint8_t(p1 & 0xffu);
      }
      break;
    case RawPacking::Bits10LittleEndian:
      for (std::size_t k = 0, b = 0; k < n; k += 4, b += 5) {
        unsigned low = 0;
        for (std::size_t i = 0; i < 4; ++i) {
          const unsigned p = at(k + i) & 0x3ffu;
          bytes[b + i] = std::uint8_t(p >> 2);
          low |= (p & 3u) << (2 * i);
        }
        bytes[b + 4] = std::uint8_t(low);
      }
      break;
    case RawPacking::Bits16LittleEndian:
      for (std::size_t k = 0; k < n; ++k) {
        bytes[2 * k] = std::uint8_t(samples[k] & 0xffu);
        bytes[2 * k + 1] = std::uint8_t(samples[k] >> 8);
      }
      break;
  }
  return bytes;
}

}  // namespace lfcam
