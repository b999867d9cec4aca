#include "io/hdf5_chunk_codec.hpp"

#include <libdeflate.h>
extern "C" {  // szlib.h declares C functions without saying so to C++
#include <szlib.h>
}

#include <cstring>
#include <memory>

namespace lfcam::io {

namespace {

// HDF5's shuffle: byte j of element i goes to j * count + i, so like bytes of all elements sit
// together (the high bytes of floats or 16-bit codes compress far better on their own).
void shuffleBytes(const unsigned char* in, std::size_t count, std::size_t elementSize, unsigned char* out) {
  for (std::size_t j = 0; j < elementSize; ++j)
    for (std::size_t i = 0; i < count; ++i) out[j * count + i] = in[i * elementSize + j];
}

void unshuffleBytes(const unsigned char* in, std::size_t count, std::size_t elementSize, unsigned char* out) {
  for (std::size_t j = 0; j < elementSize; ++j)
    for (std::size_t i = 0; i < count; ++i) out[i * elementSize + j] = in[j * count + i];
}

SZ_com_t szipOptions(const SzipParameters& szip) {
  return {.options_mask = int(szip.optionsMask),
          .bits_per_pixel = int(szip.bitsPerPixel),
          .pixels_per_block = int(szip.pixelsPerBlock),
          .pixels_per_scanline = int(szip.pixelsPerScanline)};
}

// libhdf5's szip chunk: the unfiltered size (32-bit little-endian), then libaec's stream.
constexpr std::size_t kSzipHeader = 4;

std::vector<unsigned char> szipChunk(const unsigned char* data, std::size_t bytes, const SzipParameters& szip) {
  std::vector<unsigned char> out(kSzipHeader + bytes);
  for (std::size_t i = 0; i < kSzipHeader; ++i) out[i] = static_cast<unsigned char>(bytes >> (8 * i));
  std::size_t size = bytes;
  SZ_com_t options = szipOptions(szip);
  if (SZ_BufftoBuffCompress(out.data() + kSzipHeader, &size, data, bytes, &options) != SZ_OK) return {};
  out.resize(kSzipHeader + size);
  return out;
}

std::string unszipChunk(const unsigned char* data, std::size_t bytes, const SzipParameters& szip, unsigned char* out,
                        std::size_t outBytes) {
  if (bytes < kSzipHeader) return "a truncated szip chunk";
  std::size_t claimed = 0;
  for (std::size_t i = 0; i < kSzipHeader; ++i) claimed |= std::size_t(data[i]) << (8 * i);
  if (claimed != outBytes) return "a chunk says it holds another number of bytes than a view";
  std::size_t size = outBytes;
  SZ_com_t options = szipOptions(szip);
  if (SZ_BufftoBuffDecompress(out, &size, data + kSzipHeader, bytes - kSzipHeader, &options) != SZ_OK)
    return "a corrupt szip stream in a chunk";
  if (size != outBytes) return "a chunk decompresses to fewer bytes than it should hold";
  return {};
}

}  // namespace

bool szipParametersValid(const SzipParameters& szip, std::size_t elementSize) {
  const unsigned block = szip.pixelsPerBlock;
  return (block == 8 || block == 16 || block == 32) && szip.bitsPerPixel == 8 * elementSize &&
         szip.pixelsPerScanline > 0 && szip.pixelsPerScanline <= block * 128;
}

std::vector<unsigned char> filterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                                       const ChunkFilters& filters, int deflateLevel) {
  if (filters.szip) return szipChunk(data, bytes, *filters.szip);
  std::vector<unsigned char> shuffled;
  if (filters.shuffle && elementSize > 1) {
    shuffled.resize(bytes);
    shuffleBytes(data, bytes / elementSize, elementSize, shuffled.data());
    data = shuffled.data();
  }
  if (!filters.deflate) return shuffled.empty() ? std::vector<unsigned char>(data, data + bytes) : shuffled;
  // libdeflate: the same zlib stream as zlib's, made and read about twice as fast (docs/design.md).
  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(deflateLevel), libdeflate_free_compressor);
  std::vector<unsigned char> out(libdeflate_zlib_compress_bound(compressor.get(), bytes));
  out.resize(libdeflate_zlib_compress(compressor.get(), data, bytes, out.data(), out.size()));
  return out;
}

std::string unfilterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                          const ChunkFilters& filters, unsigned char* out, std::size_t outBytes) {
  if (filters.szip) return unszipChunk(data, bytes, *filters.szip, out, outBytes);
  const bool unshuffle = filters.shuffle && elementSize > 1;
  std::vector<unsigned char> shuffled(unshuffle ? outBytes : 0);
  unsigned char* target = unshuffle ? shuffled.data() : out;
  if (filters.deflate) {
    const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> decompressor(
        libdeflate_alloc_decompressor(), libdeflate_free_decompressor);
    std::size_t produced = 0;
    switch (libdeflate_zlib_decompress(decompressor.get(), data, bytes, target, outBytes, &produced)) {
      case LIBDEFLATE_SUCCESS:
        if (produced != outBytes) return "a chunk decompresses to fewer bytes than it should hold";
        break;
      case LIBDEFLATE_INSUFFICIENT_SPACE: return "a chunk decompresses to more bytes than it should hold";
      default: return "a corrupt deflate stream in a chunk";
    }
  } else {
    if (bytes != outBytes) return "a chunk of the wrong size";
    std::memcpy(target, data, bytes);
  }
  if (unshuffle) unshuffleBytes(shuffled.data(), outBytes / elementSize, elementSize, out);
  return {};
}

}  // namespace lfcam::io
