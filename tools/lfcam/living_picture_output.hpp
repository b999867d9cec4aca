// The living picture as `lfcam export-html` writes it: one self-contained page, written atomically.
#pragma once

#include <filesystem>
#include <string>

#include "lfcam/light_field.hpp"
#include "lfcam/living_picture.hpp"
#include "lfcam/result.hpp"

namespace lfcam::cli {

// With a progress bar on a terminal while the page is made.
Status writeLivingPictureFile(const std::filesystem::path& output, const LightField& lightField,
                              const LivingPictureOptions& options);

}  // namespace lfcam::cli
