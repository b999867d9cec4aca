// PFM, the Portable Float Map (the HCI benchmark's disparity maps): a text header
//   "PF" (3 channels) or "Pf" (1 channel), width height, scale
// then float32 pixels, interleaved, rows from the bottom of the image to the top. The sign of the
// scale gives the byte order: negative little-endian, positive big-endian. Its magnitude is
// ignored, as most readers do.
#pragma once

#include <filesystem>
#include <span>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::io {

bool startsLikePfm(std::span<const unsigned char> head);
Result<ImageHeader> readPfmHeader(const std::filesystem::path& path);
Result<Image> readPfm(const std::filesystem::path& path);
// Writes `file` directly (callers make it atomic); errors name `reportAs`, the file the user
// asked for. Little-endian; 1 or 3 channels.
Status writePfm(const std::filesystem::path& file, const Image& image, const std::filesystem::path& reportAs);

}  // namespace lfcam::io
