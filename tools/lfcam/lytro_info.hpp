// `lfcam info` for Lytro containers (tools/lfcam/lytro_info.cpp).
#pragma once

#include <optional>
#include <string>

#include "lfcam/core/result.hpp"
#include "white_note.hpp"

namespace lfcam::cli {

// Prints the sections of the container at `path`, what each is, the frame's key facts, and which
// white decoding it would take.
Status printLytroInfo(const std::string& path, bool json, const std::optional<WhiteNote>& white);

}  // namespace lfcam::cli
