// How the native file stores samples: in the precision they came in, chosen by exactness. A light
// field read from 8-bit sRGB PNGs holds only the 256 values of the sRGB table, so it is stored as
// those 8-bit codes; 16-bit linear images hold code / 65535, stored as 16-bit codes with that
// scale; anything float16 holds exactly is float16; the rest float32. The writer takes the first
// encoding that gives every sample back bit for bit, so a file always reads back exactly what was
// written, and an 8-bit source costs a quarter of float32 on disk and in decompression.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace lfcam::io {

enum class SampleEncodingKind {
  Srgb8,     // uint8 sRGB codes: value = the sRGB transfer of code / 255 (lfcam's table)
  Linear8,   // uint8: value = code * scale
  Linear16,  // uint16: value = code * scale
  Float16,   // IEEE binary16
  Float32,   // IEEE binary32
};

struct SampleEncoding {
  SampleEncodingKind kind = SampleEncodingKind::Float32;
  double scale = 1.0;  // Linear8 and Linear16 only
  bool operator==(const SampleEncoding&) const = default;
};

std::size_t bytesPerSample(SampleEncodingKind kind);

// Encodes `values` into `out` (values.size() * bytesPerSample, little-endian); false, with `out`
// partly written, as soon as one value would not decode back to the same bits.
bool encodeExactly(const SampleEncoding& encoding, std::span<const float> values, unsigned char* out);

// The inverse: `count` samples from little-endian codes.
void decodeSamples(const SampleEncoding& encoding, const unsigned char* codes, std::size_t count, float* out);

// The first of `candidates` that holds every value exactly, else Float32; checked one view
// (`viewValues` samples) at a time in parallel.
SampleEncoding exactEncodingOf(std::span<const float> values, std::size_t viewValues,
                               std::span<const SampleEncoding> candidates);

// The candidates, most compact first: colour samples as 8-bit sRGB, 16-bit linear or float16;
// weights (linear by nature) as 8-bit or 16-bit linear or float16.
extern const SampleEncoding kColorEncodings[3];
extern const SampleEncoding kWeightEncodings[3];

}  // namespace lfcam::io
