// JPEG files through libjpeg(-turbo) itself, without OpenImageIO (docs/design.md, "Start-up"):
// 8-bit grey or RGB, the description in a COM marker.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "io/interleaved_codes.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::io {

// Reads a JPEG as 8-bit grey (one channel) or RGB (three; YCbCr, CMYK and YCCK are converted).
// With `pixels` false only the header and the markers before the scan are read. `checkHeader`
// sees the header (no samples yet) and may refuse it before the samples are allocated.
Result<InterleavedCodes> readJpeg(const std::filesystem::path& path, bool pixels,
                                  const std::function<Status(const InterleavedCodes&)>& checkHeader);

// Writes `image` (8-bit, 1 or 3 channels) at `quality` (1-100) to `temporary`; errors name `path`.
Status writeJpeg(const std::filesystem::path& temporary, const std::filesystem::path& path,
                 const InterleavedCodes& image, int quality);

// The same file's bytes in memory (the viewer's answers).
Result<std::string> encodeJpeg(const InterleavedCodes& image, int quality);

}  // namespace lfcam::io
