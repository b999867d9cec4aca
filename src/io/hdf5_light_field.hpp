// The native light-field file, `.lf.h5`, through the HDF5 C API. Layout (docs/formats.md):
//   /lightfield  float32 [nv, nu, channels, nt, ns], one chunk per view, shuffle + deflate
//   /weight      float32 [nv, nu, nt, ns], when the light field has a weight
//   root attributes: lfcam_format = "lfcam-lightfield", lfcam_version = 1, axes = "v,u,c,t,s",
//   lens_step_mm, spatial_step_mm, lens_to_microlens_mm, focal_length_mm (optics, when known),
//   disparity_min, disparity_max (when known), source.
// The dataset's dimensions are the memory layout of LightField, so each view is one read.
// HDF5 (serial build) is not thread-safe: every call here holds one process-wide lock.
#pragma once

#include <filesystem>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam::io {

Result<LightFieldInfo> probeHdf5(const std::filesystem::path& path);
Result<LightField> readHdf5(const std::filesystem::path& path, const ProgressCallback& progress);
// Writes `file` directly (callers make it atomic); errors name `reportAs`.
Status writeHdf5(const std::filesystem::path& file, const LightField& lightField, const ProgressCallback& progress,
                 const std::filesystem::path& reportAs);

}  // namespace lfcam::io
