// TIFF files through libtiff itself, without OpenImageIO (docs/design.md, "Start-up"): 8 and 16-bit
// codes stay codes; every other sample format becomes float; any number of channels. Images are
// one page; stacks (a volume's z-slices) are every page of the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

#include "io/interleaved_codes.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::io {

// Reads a TIFF's first image (strips or tiles, interleaved or separate planes). Unsigned 8 and
// 16-bit samples stay codes; 32-bit unsigned, signed integers (scaled to [0, 1] and [-1, 1]) and
// 16, 32 and 64-bit floats become Float32. Palette, YCbCr, CMYK and samples below 8 bits become
// 8-bit RGB (RGBA with an alpha sample) through libtiff's RGBA interface. With `pixels` false only
// the directory is read. `checkHeader` may refuse the header before the samples are allocated.
Result<InterleavedCodes> readTiff(const std::filesystem::path& path, bool pixels,
                                  const std::function<Status(const InterleavedCodes&)>& checkHeader);

// Writes `image` (8/16-bit codes or Float32, any number of channels; with 2 or 4 the last is
// unassociated alpha) deflate-compressed to `temporary`; errors name `path`.
Status writeTiff(const std::filesystem::path& temporary, const std::filesystem::path& path,
                 const InterleavedCodes& image);

// The resolution tags: pixels per unit across and down, in libtiff's RESUNIT_NONE, RESUNIT_INCH or
// RESUNIT_CENTIMETER.
struct TiffResolution {
  double x = 1, y = 1;
  std::uint16_t unit = 1;
};

// Pages of one layout, as a z-stack is stored: the first page's header (samples empty) and
// description, the number of pages, and the first page's resolution tags when it has them.
struct TiffStack {
  InterleavedCodes header;
  int pages = 0;
  std::optional<TiffResolution> resolution;
};

// Reads every page of a TIFF in turn, each as readTiff reads the first. `start` sees the stack before
// any samples are read and may refuse it; `page(z, codes)` then receives page z. A page whose size,
// channels or sample type differ from the first's, or a chain of pages ending in damage (a truncated
// file), is a Format error.
Status readTiffStack(const std::filesystem::path& path, const std::function<Status(const TiffStack&)>& start,
                     const std::function<Status(int z, const InterleavedCodes& codes)>& page);

// Writes `stack.pages` pages of stack.header's layout as writeTiff writes one, page z's interleaved
// samples read from samples(z); the description on the first page, the resolution (when given) on
// every page.
Status writeTiffStack(const std::filesystem::path& temporary, const std::filesystem::path& path, const TiffStack& stack,
                      const std::function<const unsigned char*(int z)>& samples);

// The DNG BlackLevel and WhiteLevel tags of a TIFF's first image, which machine-vision and microscope
// software writes into plain TIFFs too.
struct TiffLevels {
  std::optional<double> black, white;  // DN; several values (a per-channel or repeat pattern): their mean
};
// A file without them (or no TIFF at all) leaves the levels unset.
TiffLevels readTiffLevels(const std::filesystem::path& path);

}  // namespace lfcam::io
