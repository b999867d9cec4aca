// How every image-writing command (refocus, stack, views, edof, observer, animate --stills,
// convert) chooses what its image files hold: the format from the file's extension (or a folder's
// --format), the sample depth from --bit-depth:
//   8      sRGB-encoded codes, for quick looks (PNG, TIFF, JPEG)
//   16     linear radiance, code 65535 = 1.0 (the white image's level), clamped to [0, 1] (PNG, TIFF)
//   float  linear radiance as computed, unclamped (TIFF, OpenEXR, PFM)
// Default: the format's own (8 for PNG and JPEG, 16 for TIFF, float for OpenEXR and PFM). A depth
// the format cannot hold is a usage error, found before any work.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>

#include "lfcam/core/result.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::cli {

// --bit-depth 8|16|float on `command`; `depth` stays empty when not given.
CLI::Option* addBitDepthOption(CLI::App& command, std::string& depth);

// The sample type `depth` names (empty: the format's own); for the light-field writers.
std::optional<SampleType> sampleTypeOfDepth(const std::string& depth);

// The options writing `file` at `depth` takes, or a Usage error naming the file (an unknown
// extension, a depth its format cannot hold).
Result<ImageWriteOptions> imageWriteOptionsFor(const std::filesystem::path& file, const std::string& depth);

}  // namespace lfcam::cli
