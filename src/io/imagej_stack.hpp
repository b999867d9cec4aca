// A Volume as a TIFF z-stack (volume_io.hpp): written as Fiji/ImageJ writes one, read from any
// stack of one-channel pages, with ImageJ's calibration and TIFF's resolution tags.
#pragma once

#include <filesystem>

#include "lfcam/core/result.hpp"
#include "lfcam/core/volume.hpp"

namespace lfcam::io {

// Writes `volume` to `temporary` (callers make it atomic); errors name `path`.
Status writeImageJStack(const std::filesystem::path& temporary, const std::filesystem::path& path,
                        const Volume& volume);

Result<Volume> readTiffVolume(const std::filesystem::path& path);

}  // namespace lfcam::io
