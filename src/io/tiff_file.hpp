// TIFF files through libtiff itself, without OpenImageIO (docs/design.md, "Start-up"): 8 and 16-bit
// codes stay codes; every other sample format becomes float; any number of channels.
#pragma once

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

// The DNG BlackLevel and WhiteLevel tags of a TIFF's first image, which machine-vision and microscope
// software writes into plain TIFFs too.
struct TiffLevels {
  std::optional<double> black, white;  // DN; several values (a per-channel or repeat pattern): their mean
};
// A file without them (or no TIFF at all) leaves the levels unset.
TiffLevels readTiffLevels(const std::filesystem::path& path);

}  // namespace lfcam::io
