// Every setting of DepthOptions (depth.hpp), stage by stage, under the name `lfcam depth` gives it:
// its flag (--NAME) and its key in an options file (--options FILE.json, an object of NAME:
// number, unknown keys refused). One table, so that the command line, the file and --help cannot
// drift apart.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <variant>

#include "lfcam/core/result.hpp"
#include "lfcam/edof/depth.hpp"

namespace lfcam {

struct DepthKnob {
  const char* stage;  // range, cost, aggregation, regularisation, refinement, cleanup
  const char* name;   // "defocus-weight"
  const char* help;
  std::variant<std::optional<double> DepthOptions::*, int DepthOptions::*, double DepthOptions::*> member;
  double min, max;  // the accepted values, inclusive
};
std::span<const DepthKnob> depthKnobs();

// Sets the options an options file names, leaving the others. Errors name the file and the key
// (an unknown key, a value out of range, not JSON); the range is not checked against itself here
// (estimateDepth refuses min >= max).
Status readDepthOptions(const std::filesystem::path& file, DepthOptions& options);

}  // namespace lfcam
