// `lfcam info` for Lytro containers (tools/lfcam/lytro_info.cpp).
#pragma once

#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam::cli {

// Prints the sections of the container at `path`, what each is, and the frame's key facts.
Status printLytroInfo(const std::string& path, bool json);

}  // namespace lfcam::cli
