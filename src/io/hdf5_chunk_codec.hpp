// The two HDF5 built-in filters lfcam writes, applied outside libhdf5: byte shuffle (H5Z_FILTER_SHUFFLE)
// and deflate (H5Z_FILTER_DEFLATE, a zlib stream). Run by lfcam's own threads on raw chunks
// (H5Dwrite_chunk / H5Dread_chunk), one chunk per thread, where libhdf5 would filter them one at a
// time under its lock. The bytes are exactly those libhdf5's filters make, so any HDF5 reader
// (h5py, MATLAB) decodes the file with no plugin.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace lfcam::io {

struct ChunkFilters {
  bool shuffle = false;
  bool deflate = false;
};

// `bytes` of elements `elementSize` bytes wide, filtered as `filters` says.
std::vector<unsigned char> filterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                                       const ChunkFilters& filters, int deflateLevel);

// The inverse, into exactly `outBytes` bytes at `out`; an empty string on success, else what is wrong
// with the chunk (corrupt stream, or not the expected size).
std::string unfilterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                          const ChunkFilters& filters, unsigned char* out, std::size_t outBytes);

}  // namespace lfcam::io
