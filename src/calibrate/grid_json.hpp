// The JSON documents of calibration (not public; readGrid, writeGrid and readLensletHint are the
// file-level entry points): grid.json and the lenslet hint of a metadata file.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

// grid.json (docs/formats.md).
nlohmann::json gridToJson(const LensletGrid& grid);
Result<LensletGrid> gridFromJson(const nlohmann::json& json, const std::string& where);

// The simulator's camera.json (its "lattice_px") or a Lytro frame metadata document.
Result<LensletHint> lensletHintFromJson(const nlohmann::json& json, const std::string& where);

}  // namespace lfcam
