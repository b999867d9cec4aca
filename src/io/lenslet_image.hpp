// A light field stored as one "macro-pixel" image of (ns * nu) x (nt * nv) pixels: the nu x nv
// pixels behind each microlens hold the views, so pixel (s * nu + u, t * nv + v) = L(u, v, s, t).
// lfcam writes the image description "lfcam lenslet nu=N nv=M" so that it can read the grid back;
// other files need the number of views per lens, given or estimated (macro_pixel_period.hpp).
#pragma once

#include <filesystem>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam::io {

Result<LightFieldInfo> probeLensletImage(const std::filesystem::path& path, const LightFieldReadOptions& options);
Result<LightField> readLensletImage(const std::filesystem::path& path, const LightFieldReadOptions& options,
                                    const ProgressCallback& progress);
// Atomic, through writeImage, in `sampleType` (default: the format's natural one).
Status writeLensletImage(const std::filesystem::path& path, const LightField& lightField,
                         std::optional<SampleType> sampleType, const ProgressCallback& progress);

}  // namespace lfcam::io
