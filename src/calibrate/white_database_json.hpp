// whites.json (docs/formats.md, "White-image database") <-> WhiteDatabase. Paths in the file are
// relative to the index's folder where they lie under it, so the index and its cache move together.
#pragma once

#include <filesystem>

#include "lfcam/calibrate/white_database.hpp"

namespace lfcam {

Status writeWhiteDatabase(const WhiteDatabase& database);

}  // namespace lfcam
