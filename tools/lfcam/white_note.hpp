// For `lfcam info`: which white decoding the input would take (or took): the one a --whites database
// chooses and why, the --white given, none given for a raw frame, or none needed for a light field.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.hpp"

namespace lfcam::cli {

struct WhiteNote {
  std::string text;     // one line
  nlohmann::json json;  // {"choice": "database" | "given" | "none-given" | "none-needed", ...}
};

// Nothing to say (nullopt) about a light field when no white was asked about: its metadata's
// source already names the white it was decoded with. `container`: the input is a Lytro container.
Result<std::optional<WhiteNote>> whiteNote(const InputOptions& input, bool container);

}  // namespace lfcam::cli
