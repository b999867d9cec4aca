// Small text documents (calibration and settings files) read whole and written atomically, with
// errors that name the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam {

// The file's bytes; `expected` says what it should be, for the error when it is a folder
// ("a calibration file (.xml or .json)"). Files over `maxBytes` are refused as not that kind.
Result<std::string> readTextFile(const std::filesystem::path& path, const char* expected,
                                 std::uintmax_t maxBytes = 64u << 20);
// Writes `text` to `path` through a temporary renamed into place (atomic_file.hpp).
Status writeTextFileAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace lfcam
