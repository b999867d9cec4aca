// Camera raw files through LibRaw (private to src/raw_io; readRaw is the public entry).
#pragma once

#include <filesystem>

#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

Result<RawImage> readCameraRaw(const std::filesystem::path& path);

}  // namespace lfcam
