// A focal stack as `lfcam stack` writes it: slice_000.EXT, slice_001.EXT, ... and stack.json
// naming the slope (and alpha, with optics) of each, all into `folder` atomically.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/photo/photo_request.hpp"

namespace lfcam {

// "slice_007.png" for index 7 and extension "png".
std::string stackSliceName(int index, const std::string& extension);

// progress(fraction) after each slice written.
Status writeFocalStack(const std::filesystem::path& folder, const LightField& lightField, const ResolvedPhoto& camera,
                       const std::vector<double>& slopes, const std::string& extension,
                       const ImageWriteOptions& writeOptions, const std::function<void(double)>& progress);

}  // namespace lfcam
