// OpenEXR files through the OpenEXR library itself, without OpenImageIO (docs/design.md,
// "Start-up"). Channels are read as float whatever they hold (half, float, uint), straight into
// lfcam's planes, in the order R, G, B (or Y), A, then the rest by name with numbers in numeric
// order (channel2 before channel10); written as float, zip-compressed.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::io {

struct ExrHeader {
  int width = 0, height = 0, channels = 0;
  std::string description;  // the standard string attribute "comments"
};

Result<ExrHeader> readExrHeader(const std::filesystem::path& path);

// `checkHeader` may refuse the header before the samples are allocated.
Result<Image> readExr(const std::filesystem::path& path, const std::function<Status(const ExrHeader&)>& checkHeader);

// Channel names Y, YA, RGB, RGBA, else channel0, channel1, ...; errors name `path`.
Status writeExr(const std::filesystem::path& temporary, const std::filesystem::path& path, const Image& image,
                const std::string& description);

}  // namespace lfcam::io
