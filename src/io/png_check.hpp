// A structural check of PNG files before OpenImageIO decodes them. OpenImageIO 2.4 leaves
// libpng's default error handler in place, which prints to stderr; checking the chunk lengths
// and CRCs first turns truncated and corrupted files into clean errors without reaching it.
// (A file crafted with valid CRCs around a broken deflate stream still gets through to libpng.)
#pragma once

#include <filesystem>

#include "lfcam/result.hpp"

namespace lfcam::io {

// Walks the chunks: IHDR first, every chunk whole with a matching CRC, IDAT present, IEND last.
Status checkPngStructure(const std::filesystem::path& path);

}  // namespace lfcam::io
