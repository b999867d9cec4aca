#include "io/sample_encoding.hpp"

#include <Imath/half.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/parallel.hpp"
#include "io/srgb.hpp"

namespace lfcam::io {

namespace {

bool sameBits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

float fromLinearCode(unsigned code, double scale) { return float(double(code) * scale); }

// Little-endian stores and loads (the file's byte order on every machine).
void storeLittle16(unsigned char* out, std::uint16_t value) {
  out[0] = static_cast<unsigned char>(value & 0xff);
  out[1] = static_cast<unsigned char>(value >> 8);
}
std::uint16_t loadLittle16(const unsigned char* in) { return std::uint16_t(in[0] | (unsigned(in[1]) << 8)); }
void storeLittle32(unsigned char* out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<unsigned char>(value >> (8 * i));
}
std::uint32_t loadLittle32(const unsigned char* in) {
  return std::uint32_t(in[0]) | (std::uint32_t(in[1]) << 8) | (std::uint32_t(in[2]) << 16) |
         (std::uint32_t(in[3]) << 24);
}

}  // namespace

std::size_t bytesPerSample(SampleEncodingKind kind) {
  switch (kind) {
    case SampleEncodingKind::Srgb8:
    case SampleEncodingKind::Linear8: return 1;
    case SampleEncodingKind::Linear16:
    case SampleEncodingKind::Float16: return 2;
    case SampleEncodingKind::Float32: return 4;
  }
  return 4;
}

bool encodeExactly(const SampleEncoding& encoding, std::span<const float> values, unsigned char* out) {
  const std::size_t count = values.size();
  switch (encoding.kind) {
    case SampleEncodingKind::Srgb8: return srgb8CodesOf(values, out);
    case SampleEncodingKind::Linear8:
    case SampleEncodingKind::Linear16: {
      const double maxCode = encoding.kind == SampleEncodingKind::Linear8 ? 255.0 : 65535.0;
      for (std::size_t i = 0; i < count; ++i) {
        const double code = std::round(double(values[i]) / encoding.scale);
        if (!(code >= 0.0 && code <= maxCode) || !sameBits(fromLinearCode(unsigned(code), encoding.scale), values[i]))
          return false;
        if (encoding.kind == SampleEncodingKind::Linear8)
          out[i] = static_cast<unsigned char>(code);
        else
          storeLittle16(out + 2 * i, std::uint16_t(code));
      }
      return true;
    }
    case SampleEncodingKind::Float16:
      for (std::size_t i = 0; i < count; ++i) {
        const Imath::half half(values[i]);
        if (!sameBits(float(half), values[i])) return false;
        storeLittle16(out + 2 * i, half.bits());
      }
      return true;
    case SampleEncodingKind::Float32:
      for (std::size_t i = 0; i < count; ++i) storeLittle32(out + 4 * i, std::bit_cast<std::uint32_t>(values[i]));
      return true;
  }
  return false;
}

void decodeSamples(const SampleEncoding& encoding, const unsigned char* codes, std::size_t count, float* out) {
  switch (encoding.kind) {
    case SampleEncodingKind::Srgb8:
    case SampleEncodingKind::Linear8: {
      float table[256];
      for (unsigned code = 0; code < 256; ++code)
        table[code] = encoding.kind == SampleEncodingKind::Srgb8 ? linearFromSrgb8(std::uint8_t(code))
                                                                 : fromLinearCode(code, encoding.scale);
      for (std::size_t i = 0; i < count; ++i) out[i] = table[codes[i]];
      return;
    }
    case SampleEncodingKind::Linear16:
      for (std::size_t i = 0; i < count; ++i) out[i] = fromLinearCode(loadLittle16(codes + 2 * i), encoding.scale);
      return;
    case SampleEncodingKind::Float16:
      for (std::size_t i = 0; i < count; ++i) {
        Imath::half half;
        half.setBits(loadLittle16(codes + 2 * i));
        out[i] = float(half);
      }
      return;
    case SampleEncodingKind::Float32:
      for (std::size_t i = 0; i < count; ++i) out[i] = std::bit_cast<float>(loadLittle32(codes + 4 * i));
      return;
  }
}

const SampleEncoding kColorEncodings[3] = {
    {SampleEncodingKind::Srgb8}, {SampleEncodingKind::Linear16, 1.0 / 65535.0}, {SampleEncodingKind::Float16}};
const SampleEncoding kWeightEncodings[3] = {{SampleEncodingKind::Linear8, 1.0 / 255.0},
                                            {SampleEncodingKind::Linear16, 1.0 / 65535.0},
                                            {SampleEncodingKind::Float16}};

SampleEncoding exactEncodingOf(std::span<const float> values, std::size_t viewValues,
                               std::span<const SampleEncoding> candidates) {
  const std::size_t views = viewValues == 0 ? 0 : values.size() / viewValues;
  for (const SampleEncoding& candidate : candidates) {
    std::atomic<bool> exact = true;
    parallelFor(0, views, 1, [&](std::size_t begin, std::size_t end) {
      std::vector<unsigned char> scratch(viewValues * bytesPerSample(candidate.kind));
      for (std::size_t view = begin; view < end && exact.load(std::memory_order_relaxed); ++view)
        if (!encodeExactly(candidate, values.subspan(view * viewValues, viewValues), scratch.data())) exact = false;
    });
    if (exact) return candidate;
  }
  return {SampleEncodingKind::Float32};
}

}  // namespace lfcam::io
