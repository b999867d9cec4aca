// A structural check of PNG files before libpng decodes them (io/png_file): checking the chunk
// lengths and CRCs first turns truncated and corrupted files into errors that say what is wrong.
// (A file crafted with valid CRCs around a broken deflate stream still gets through to libpng,
// whose message then names the problem.)
#pragma once

#include <filesystem>

#include "lfcam/core/result.hpp"

namespace lfcam::io {

// Walks the chunks: IHDR first, every chunk whole with a matching CRC, IDAT present, IEND last.
// Without `imageData`, the image data (IDAT) is only checked to be in the file, not read: what a
// header read needs, which then costs a few small reads instead of the whole file.
Status checkPngStructure(const std::filesystem::path& path, bool imageData);

}  // namespace lfcam::io
