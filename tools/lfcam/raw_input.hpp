// A raw lenslet image decoded on the way: what `lfcam decode` and every command's --white take.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/decode/decode_files.hpp"
#include "lfcam/simulate/camera_model.hpp"

namespace lfcam::cli {

// --demosaic and --sampling, the decoder's method choices, on `command` (lfcam decode and every
// command that decodes a raw on the way).
void addDecodeMethodOptions(CLI::App& command, DecodeOptions& decode);
// --black-level N, the camera's offset in DN of the raw file (decode, calibrate and every command
// that decodes a raw on the way).
void addBlackLevelOption(CLI::App& command, std::optional<double>& blackLevel);

// --whites FILE and --any-camera (decode, and every command that decodes a raw on the way).
void addWhitesOptions(CLI::App& command, std::string& whites, bool& anyCamera);

// "RGGB", "mono", ... (any case); Usage error naming the option otherwise.
Result<ColorFilter> parseBayerOption(const std::string& text);
// decodeRawFiles (decode_files.hpp) with a progress bar on a terminal, saying on stderr which white
// a database gave.
Result<LightField> decodeRawInput(RawFiles files);

}  // namespace lfcam::cli
