// Volume files: the light-field microscope's reconstructions (lfcam/core/volume.hpp), by name:
//   .tif, .tiff  a z-stack, one 32-bit float page per slice, as Fiji/ImageJ saves one: its
//                description ("ImageJ=...", slices, unit=micron, spacing = the slice spacing, min
//                and max) and XResolution/YResolution = 1 / voxel width (ResolutionUnit none), so
//                Fiji opens it with its voxel size. lfcam's own lines in the description keep what
//                ImageJ has no place for or rounds: the depth of slice 0, the exact voxel width.
//   .h5, .hdf5   dataset "volume", float32 [z][y][x], one deflated chunk per slice, with attributes
//                voxel_size_um = [dz, dy, dx] and first_slice_um (h5py: f["volume"][...]).
// Reading recognises the kind by content. Any TIFF whose pages share size and one channel reads as a
// stack (napari-LF's, Fiji's, ...): 8 and 16-bit codes scaled to [0, 1] (linearly: a volume holds
// intensities, not sRGB), other samples as floats; the voxel size from ImageJ's spacing and unit
// and from the resolution tags when present, else 1 um. An HDF5 "volume" may hold any float type,
// or 8/16-bit unsigned codes scaled as a TIFF's.
//
// Writing goes through writeFileAtomically: no partial file on failure.
#pragma once

#include <filesystem>

#include "lfcam/core/result.hpp"
#include "lfcam/core/volume.hpp"

namespace lfcam {

// Writes `volume` as its extension says; another extension, an empty volume or a voxel size that
// is not positive and finite is a Usage error.
Status writeVolume(const std::filesystem::path& path, const Volume& volume);

Result<Volume> readVolume(const std::filesystem::path& path);

// writeVolume's refusal of an unknown extension, for a command to give before its work.
Status checkVolumePath(const std::filesystem::path& path);

}  // namespace lfcam
