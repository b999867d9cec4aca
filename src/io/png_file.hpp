// PNG files through libpng itself: the format of view folders and of most outputs, read and written
// without OpenImageIO, whose Debian build maps some 250 shared libraries at start-up (docs/design.md,
// "Start-up"). Samples stay interleaved codes here; image_io converts them to linear planes.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "io/interleaved_codes.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::io {

// Reads a PNG (checked with checkPngStructure first). Palettes, transparency chunks and bit depths
// below 8 are expanded to 8-bit grey, grey+alpha, RGB or RGBA; 16-bit stays 16-bit. With
// `pixels` false only the header and the text chunks before the image data are read.
// `checkHeader` sees the header (no samples yet) and may refuse it before the samples are allocated.
Result<InterleavedCodes> readPng(const std::filesystem::path& path, bool pixels,
                                 const std::function<Status(const InterleavedCodes&)>& checkHeader);

// Writes `image` (channels 1-4: grey, grey+alpha, RGB, RGBA) to `temporary`; errors name `path`.
// zlib level 1 (a third of the time of level 6 for files about 13% larger) and the Up filter on every
// row (libpng's trial of all five per row costs more than it saves at this level).
Status writePng(const std::filesystem::path& temporary, const std::filesystem::path& path,
                const InterleavedCodes& image);

// The same file's bytes in memory (the viewer's answers).
Result<std::string> encodePng(const InterleavedCodes& image);

}  // namespace lfcam::io
