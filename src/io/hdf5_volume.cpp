#include "io/hdf5_volume.hpp"

#include <hdf5.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/hdf5_handle.hpp"
#include "io/hdf5_support.hpp"
#include "io/io_support.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;
using hdf5::Handle;

namespace {

constexpr const char* kDataset = "volume";
constexpr int kDeflateLevel = 1;  // as the light field's: higher levels gain little on floats, and cost time

// An opened /volume: its dimensions (z, y, x), the scale of its codes (1 for floats), the voxel size.
struct OpenedVolume {
  Handle file, dataset;
  hsize_t dims[3] = {};
  double codeScale = 1;
  double voxelWidthUm = 1, voxelHeightUm = 1, voxelDepthUm = 1, firstSliceUm = 0;
};

Result<OpenedVolume> openVolume(const fs::path& path) {
  LFCAM_TRY(checkReadableFile(path));
  Handle fapl = fileAccess();
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file.valid()) return hdf5Error(ErrorCode::Format, path, "not a readable HDF5 file");
  if (H5Lexists(file.get(), kDataset, H5P_DEFAULT) <= 0)
    return fileError(ErrorCode::Format, path,
                     "not an lfcam volume: no /volume dataset (an HDF5 file of another layout)");
  Handle datasetHandle(H5Dopen2(file.get(), kDataset, H5P_DEFAULT), H5Dclose);
  if (!datasetHandle.valid()) return hdf5Error(ErrorCode::Format, path, "/volume is not a readable dataset");
  OpenedVolume opened{std::move(file), std::move(datasetHandle)};
  const hid_t dataset = opened.dataset.get();
  Handle type(H5Dget_type(dataset), H5Tclose);
  Handle space(H5Dget_space(dataset), H5Sclose);
  if (!type.valid() || !space.valid())
    return hdf5Error(ErrorCode::Format, path, "/volume has no readable type or shape");

  const H5T_class_t typeClass = H5Tget_class(type.get());
  const std::size_t size = H5Tget_size(type.get());
  if (typeClass == H5T_INTEGER && H5Tget_sign(type.get()) == H5T_SGN_NONE && (size == 1 || size == 2))
    opened.codeScale = size == 1 ? 255 : 65535;
  else if (typeClass != H5T_FLOAT)
    return fileError(ErrorCode::Format, path, "/volume holds neither floats nor 8 or 16-bit unsigned codes");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != 3)
    return fileError(ErrorCode::Format, path,
                     "/volume has " + std::to_string(rank) + " dimensions, expected 3 (z, y, x)");
  H5Sget_simple_extent_dims(space.get(), opened.dims, nullptr);
  for (hsize_t dim : opened.dims)
    if (dim == 0 || dim > hsize_t(INT_MAX))
      return fileError(ErrorCode::Format, path, "/volume has an empty or absurd dimension");
  LFCAM_TRY(checkSampleCount(path, {opened.dims[0], opened.dims[1], opened.dims[2]}));

  LFCAM_ASSIGN_OR_RETURN(auto voxelSize, readNumbersAttribute(path, dataset, "voxel_size_um"));
  if (voxelSize) {
    const std::vector<double>& sizes = *voxelSize;
    for (double value : sizes)
      if (!std::isfinite(value) || value <= 0 || sizes.size() != 3)
        return fileError(ErrorCode::Format, path, "attribute 'voxel_size_um' is not three positive sizes [dz, dy, dx]");
    opened.voxelDepthUm = sizes[0];
    opened.voxelHeightUm = sizes[1];
    opened.voxelWidthUm = sizes[2];
  }
  LFCAM_ASSIGN_OR_RETURN(auto firstSlice, readNumberAttribute(path, dataset, "first_slice_um"));
  if (firstSlice && !std::isfinite(*firstSlice))
    return fileError(ErrorCode::Format, path, "attribute 'first_slice_um' is not finite");
  opened.firstSliceUm = firstSlice.value_or(0);
  return opened;
}

// Every voxel, converted by libhdf5 to float, codes then scaled to [0, 1].
Status readVoxels(const fs::path& path, const OpenedVolume& opened, float* out) {
  if (H5Dread(opened.dataset.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
    return hdf5Error(ErrorCode::Format, path, "cannot read voxels");
  if (opened.codeScale != 1) {
    const std::size_t count = std::size_t(opened.dims[0] * opened.dims[1] * opened.dims[2]);
    for (std::size_t i = 0; i < count; ++i) out[i] = float(out[i] / opened.codeScale);
  }
  return {};
}

}  // namespace

Status writeHdf5Volume(const fs::path& file, const Volume& volume, const fs::path& path) {
  return writeHdf5ThroughMemory(file, path, [&](hid_t handle) -> Status {
    const hsize_t dims[3] = {hsize_t(volume.depth()), hsize_t(volume.height()), hsize_t(volume.width())};
    const hsize_t chunk[3] = {1, dims[1], dims[2]};
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_chunk(dcpl.get(), 3, chunk);
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), kDeflateLevel);
    Handle space(H5Screate_simple(3, dims, nullptr), H5Sclose);
    Handle dataset(H5Dcreate2(handle, kDataset, H5T_IEEE_F32LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                   H5Dclose);
    if (!dataset.valid()) return hdf5Error(ErrorCode::Io, path, "cannot create dataset volume");
    if (H5Dwrite(dataset.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, volume.voxels().data()) < 0)
      return hdf5Error(ErrorCode::Io, path, "cannot write voxels");
    const bool attributes =
        writeNumbersAttribute(dataset.get(), "voxel_size_um",
                              {volume.voxelDepthUm, volume.voxelHeightUm, volume.voxelWidthUm}) &&
        writeScalarAttribute(dataset.get(), "first_slice_um", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, volume.firstSliceUm);
    if (!attributes) return hdf5Error(ErrorCode::Io, path, "cannot write attributes");
    if (!dataset.close()) return hdf5Error(ErrorCode::Io, path, "cannot write voxels");
    return {};
  });
}

Result<Volume> readHdf5Volume(const fs::path& path) {
  Hdf5Session session;
  // The child reads the voxels too when they are small enough to read twice without notice.
  constexpr std::uint64_t kReadTwiceBytes = std::uint64_t(64) << 20;
  LFCAM_TRY(refuseWhatCrashesLibhdf5(path, [&] {
    auto opened = openVolume(path);
    if (!opened) return;  // a clean error is the parent's to find and report
    const std::uint64_t count = opened->dims[0] * opened->dims[1] * opened->dims[2];
    if (count * sizeof(float) > kReadTwiceBytes) return;
    std::vector<float> scratch(count);
    (void)readVoxels(path, *opened, scratch.data());
  }));
  LFCAM_ASSIGN_OR_RETURN(auto opened, openVolume(path));
  Volume volume(int(opened.dims[2]), int(opened.dims[1]), int(opened.dims[0]));
  volume.voxelWidthUm = opened.voxelWidthUm;
  volume.voxelHeightUm = opened.voxelHeightUm;
  volume.voxelDepthUm = opened.voxelDepthUm;
  volume.firstSliceUm = opened.firstSliceUm;
  LFCAM_TRY(readVoxels(path, opened, volume.voxels().data()));
  return volume;
}

}  // namespace lfcam::io
