// A Volume as an HDF5 file (volume_io.hpp): dataset /volume, float32 [z][y][x], one chunk per
// slice through libhdf5's shuffle and deflate, attributes voxel_size_um = [dz, dy, dx] and
// first_slice_um on the dataset. libhdf5 makes the file in memory, lfcam writes its bytes
// (hdf5_support.hpp).
#pragma once

#include <filesystem>

#include "lfcam/core/result.hpp"
#include "lfcam/core/volume.hpp"

namespace lfcam::io {

// Writes `file` directly (callers make it atomic); errors name `reportAs`.
Status writeHdf5Volume(const std::filesystem::path& file, const Volume& volume, const std::filesystem::path& reportAs);

Result<Volume> readHdf5Volume(const std::filesystem::path& path);

}  // namespace lfcam::io
