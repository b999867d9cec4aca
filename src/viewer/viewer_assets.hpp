// The page's files (src/viewer/assets/), embedded in the binary at build time by
// src/viewer/embed_assets.cmake: the viewer never reads a file from disk to answer a request.
#pragma once

#include <string_view>

namespace lfcam::viewer {

struct Asset {
  std::string_view name;  // file name under src/viewer/assets/, e.g. "viewer.js"
  std::string_view contentType;
  std::string_view bytes;
};

// The asset of that exact name, or nullptr.
const Asset* findAsset(std::string_view name);

}  // namespace lfcam::viewer
