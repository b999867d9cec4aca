// The DNG BlackLevel (50714) and WhiteLevel (50717) tags of a TIFF's first image, which
// OpenImageIO 2.4 does not pass on: machine-vision and microscope software writes them into plain
// TIFFs as well. Private to src/raw_io.
#pragma once

#include <filesystem>
#include <optional>

namespace lfcam {

struct TiffLevels {
  std::optional<double> black, white;  // DN; several values (a per-channel or repeat pattern): their mean
};

// The tags of the first IFD of a classic TIFF (either byte order). Anything it cannot read (no
// TIFF, BigTIFF, a damaged directory, a tag of another type) leaves the level unset.
TiffLevels readTiffLevels(const std::filesystem::path& path);

}  // namespace lfcam
