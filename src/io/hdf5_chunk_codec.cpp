#include "io/hdf5_chunk_codec.hpp"

#include <libdeflate.h>

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

}  // namespace

std::vector<unsigned char> filterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                                       const ChunkFilters& filters, int deflateLevel) {
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
