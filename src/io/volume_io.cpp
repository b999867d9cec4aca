// Volume files: TIFF z-stacks through io/imagej_stack, HDF5 through io/hdf5_volume. Which reader
// runs is decided by the file's first bytes; which writer runs, by the name's extension.
#include "lfcam/io/volume_io.hpp"

#include <cmath>
#include <string>

#include "core/atomic_file.hpp"
#include "io/hdf5_support.hpp"
#include "io/hdf5_volume.hpp"
#include "io/imagej_stack.hpp"
#include "io/io_support.hpp"

namespace lfcam {

namespace fs = std::filesystem;
using io::fileError;

Status checkVolumePath(const fs::path& path) {
  const std::string extension = io::lowerExtension(path);
  if (extension != ".tif" && extension != ".tiff" && extension != ".h5" && extension != ".hdf5")
    return fileError(ErrorCode::Usage, path,
                     "unknown volume extension '" + path.extension().string() + "' (use .tif, .tiff, .h5 or .hdf5)");
  return {};
}

Status writeVolume(const fs::path& path, const Volume& volume) {
  LFCAM_TRY(checkVolumePath(path));
  const std::string extension = io::lowerExtension(path);
  const bool tiff = extension == ".tif" || extension == ".tiff";
  if (volume.empty()) return fileError(ErrorCode::Usage, path, "nothing to write: the volume is empty");
  const auto positive = [](double size) { return std::isfinite(size) && size > 0; };
  if (!positive(volume.voxelWidthUm) || !positive(volume.voxelHeightUm) || !positive(volume.voxelDepthUm) ||
      !std::isfinite(volume.firstSliceUm))
    return fileError(ErrorCode::Usage, path,
                     "voxel sizes must be positive and finite and the first slice's depth finite, not " +
                         io::shortestNumber(volume.voxelWidthUm) + ", " + io::shortestNumber(volume.voxelHeightUm) +
                         ", " + io::shortestNumber(volume.voxelDepthUm) + " and " +
                         io::shortestNumber(volume.firstSliceUm) + " um");
  return writeFileAtomically(path, [&](const fs::path& temporary) {
    return tiff ? io::writeImageJStack(temporary, path, volume) : io::writeHdf5Volume(temporary, volume, path);
  });
}

Result<Volume> readVolume(const fs::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  return io::startsLikeHdf5(path) ? io::readHdf5Volume(path) : io::readTiffVolume(path);
}

}  // namespace lfcam
