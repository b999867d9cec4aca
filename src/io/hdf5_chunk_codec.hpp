// The HDF5 built-in filters lfcam writes, applied outside libhdf5: byte shuffle (H5Z_FILTER_SHUFFLE),
// deflate (H5Z_FILTER_DEFLATE, a zlib stream) and szip (H5Z_FILTER_SZIP, CCSDS adaptive Rice coding
// through libaec, which Debian's libhdf5 itself uses). Run by lfcam's own threads on raw chunks
// (H5Dwrite_chunk / H5Dread_chunk), one chunk per thread, where libhdf5 would filter them one at a
// time under its lock. The bytes are exactly those libhdf5's filters make, so any HDF5 reader
// (h5py, MATLAB) decodes the file with no plugin.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace lfcam::io {

// The four parameters libhdf5 stores for the szip filter (its cd_values, in that order).
struct SzipParameters {
  unsigned optionsMask = 0;  // H5_SZIP_NN_OPTION_MASK: code each sample's difference from the previous one
  unsigned pixelsPerBlock = 0;
  unsigned bitsPerPixel = 0;
  unsigned pixelsPerScanline = 0;
  bool operator==(const SzipParameters&) const = default;
};

// Parameters lfcam can hand to libaec for samples `elementSize` bytes wide: what libhdf5 makes
// (blocks of 8, 16 or 32 pixels, at most 128 blocks a scanline, the samples' own width), never a
// value that would make libaec divide by zero.
bool szipParametersValid(const SzipParameters& szip, std::size_t elementSize);

struct ChunkFilters {
  bool shuffle = false;
  bool deflate = false;
  std::optional<SzipParameters> szip;  // alone: szip is never combined with the others
};

// `bytes` of elements `elementSize` bytes wide, filtered as `filters` says. With szip, an empty
// result means the chunk would not shrink: it is then stored unfiltered, its filter mask saying so,
// as libhdf5 does with this optional filter.
std::vector<unsigned char> filterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                                       const ChunkFilters& filters, int deflateLevel);

// The inverse, into exactly `outBytes` bytes at `out`; an empty string on success, else what is wrong
// with the chunk (corrupt stream, or not the expected size).
std::string unfilterChunk(const unsigned char* data, std::size_t bytes, std::size_t elementSize,
                          const ChunkFilters& filters, unsigned char* out, std::size_t outBytes);

}  // namespace lfcam::io
