// The PSF cache (sparse_psf.hpp): one HDF5 file, written and read under the library's one HDF5 lock.
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

#include "core/atomic_file.hpp"
#include "core/hdf5_handle.hpp"
#include "core/hdf5_lock.hpp"
#include "lfcam/lfm/sparse_psf.hpp"

#include "lfm/message_text.hpp"

namespace lfcam {

using lfm::number;
using lfm::usage;

namespace {

using hdf5::Handle;

constexpr const char* kFormatTag = "lfcam-lfm-psf";
constexpr int kFormatVersion = 3;  // 1 held dense PSFs on field-sample phases; 2 had square arrays only

// Every number the cache is keyed by, with the name a refusal shows.
struct Key {
  const char* attribute;
  const char* name;
  double value;
};

std::vector<Key> keysOf(const LfmOptics& o, PupilModel pupil, const LfmGrid& grid, double keep) {
  return {{"magnification", "magnification", o.magnification},
          {"numerical_aperture", "NA", o.numericalAperture},
          {"immersion_index", "immersion index", o.immersionIndex},
          {"wavelength_nm", "wavelength (nm)", o.wavelengthNm},
          {"tube_focal_length_mm", "tube lens focal length (mm)", o.tubeFocalLengthMm},
          {"microlens_pitch_um", "microlens pitch (um)", o.microlensPitchUm},
          {"microlens_focal_length_um", "microlens focal length (um)", o.microlensFocalLengthUm},
          {"microlens_fill_factor", "microlens fill factor", o.microlensFillFactor},
          {"microlens_array", "microlens array (0 square, 1 hexagonal)", double(int(o.array))},
          {"pixel_size_um", "pixel size (um)", o.pixelSizeUm},
          {"pixel_aspect", "pixel aspect", o.pixelAspect},
          {"field_samples_per_pixel", "field samples per pixel", double(o.supersample)},
          {"pupil", "pupil (0 Abbe sine, 1 paraxial)", double(int(pupil))},
          {"pixels_per_lenslet", "pixels per lenslet", double(grid.pixelsPerLenslet)},
          {"voxels_per_lenslet", "voxels per lenslet", double(grid.voxelsPerLenslet)},
          {"kept_energy", "kept PSF energy", keep}};
}

bool writeDouble(hid_t object, const char* name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return attribute.valid() && H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value) >= 0;
}

bool readDouble(hid_t object, const char* name, double& value) {
  if (H5Aexists(object, name) <= 0) return false;
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  return attribute.valid() && H5Sget_simple_extent_npoints(space.get()) == 1 &&
         H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) >= 0;
}

bool writeDataset(hid_t file, const char* name, hid_t fileType, hid_t memoryType, const std::vector<hsize_t>& dims,
                  const void* data) {
  Handle space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose);
  Handle dataset(H5Dcreate2(file, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  return dataset.valid() && H5Dwrite(dataset.get(), memoryType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0;
}

// Reads dataset `name` of exactly `dims` into `out`.
bool readDataset(hid_t file, const char* name, hid_t memoryType, const std::vector<hsize_t>& dims, void* out) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return false;
  Handle dataset(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!dataset.valid() || H5Sget_simple_extent_ndims(space.get()) != int(dims.size())) return false;
  std::vector<hsize_t> found(dims.size());
  H5Sget_simple_extent_dims(space.get(), found.data(), nullptr);
  if (found != dims) return false;
  return H5Dread(dataset.get(), memoryType, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) >= 0;
}

}  // namespace

namespace {

// The splats' fields, one dataset each.
struct SplatColumns {
  std::vector<std::uint16_t> pixels;
  std::vector<std::int8_t> dx, dy;
  std::vector<float> weights;
};

// Writes to `file`, naming `path` (the destination) in errors.
Status writeCacheFile(const LfmSparsePsf& psf, const std::string& fileName, const std::string& path) {
  std::lock_guard lock(hdf5::libraryMutex());
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Handle file(H5Fcreate(fileName.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) return makeError(ErrorCode::Io, path + ": cannot create the PSF cache");
  bool ok = true;
  {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type.get(), std::char_traits<char>::length(kFormatTag));
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(H5Acreate2(file.get(), "format", type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    ok = attribute.valid() && H5Awrite(attribute.get(), type.get(), kFormatTag) >= 0;
  }
  ok = ok && writeDouble(file.get(), "format_version", kFormatVersion);
  for (const Key& key : keysOf(psf.optics, psf.pupil, psf.grid, psf.keptEnergy))
    ok = ok && writeDouble(file.get(), key.attribute, key.value);
  ok = ok && writeDouble(file.get(), "reach", psf.reach);
  ok = ok && writeDataset(file.get(), "depths_um", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                          {hsize_t(psf.grid.depthsUm.size())}, psf.grid.depthsUm.data());
  const std::vector<std::uint64_t> begins(psf.begins.begin(), psf.begins.end());
  ok = ok &&
       writeDataset(file.get(), "begins", H5T_STD_U64LE, H5T_NATIVE_UINT64, {hsize_t(begins.size())}, begins.data());
  SplatColumns columns;
  for (const LfmSplat& splat : psf.splats) {
    columns.pixels.push_back(splat.pixel);
    columns.dx.push_back(splat.dx);
    columns.dy.push_back(splat.dy);
    columns.weights.push_back(splat.weight);
  }
  const std::vector<hsize_t> count{hsize_t(psf.splats.size())};
  ok = ok && writeDataset(file.get(), "pixels", H5T_STD_U16LE, H5T_NATIVE_UINT16, count, columns.pixels.data()) &&
       writeDataset(file.get(), "lenslet_dx", H5T_STD_I8LE, H5T_NATIVE_INT8, count, columns.dx.data()) &&
       writeDataset(file.get(), "lenslet_dy", H5T_STD_I8LE, H5T_NATIVE_INT8, count, columns.dy.data()) &&
       writeDataset(file.get(), "weights", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, count, columns.weights.data());
  if (!ok) return makeError(ErrorCode::Io, path + ": cannot write the PSF cache");
  // The file's last metadata is written as it closes: its failure is the write's.
  if (!file.close()) return makeError(ErrorCode::Io, path + ": cannot write the PSF cache");
  return {};
}

hssize_t datasetLength(hid_t file, const char* name) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return -1;
  Handle dataset(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!dataset.valid() || H5Sget_simple_extent_ndims(space.get()) != 1) return -1;
  return H5Sget_simple_extent_npoints(space.get());
}

}  // namespace

Status writePsfCache(const LfmSparsePsf& psf, const std::string& path) {
  // Whole or not at all: a cache cut short by a failure or a kill would be refused as not one, but
  // it would also have replaced a good one.
  return writeFileAtomically(
      path, [&](const std::filesystem::path& temporary) { return writeCacheFile(psf, temporary.string(), path); });
}

Result<LfmSparsePsf> readPsfCache(const std::string& path, const LfmOptics& microscope, const LfmGrid& grid,
                                  double keep, PupilModel pupil) {
  LFCAM_TRY(validateLfmOptics(microscope));
  LFCAM_TRY(validateLfmGrid(grid));
  const LfmOptics optics = frameOptics(microscope, grid.pixelsPerLenslet);
  std::lock_guard lock(hdf5::libraryMutex());
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) return makeError(ErrorCode::Io, path + ": cannot open as HDF5");
  const Error notCache = makeError(ErrorCode::Format, path + ": not an lfcam PSF cache");
  {
    if (H5Aexists(file.get(), "format") <= 0) return notCache;
    Handle attribute(H5Aopen(file.get(), "format", H5P_DEFAULT), H5Aclose);
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    const std::size_t length = H5Tget_size(type.get());
    if (H5Tget_class(type.get()) != H5T_STRING || length != std::char_traits<char>::length(kFormatTag)) return notCache;
    Handle memoryType(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memoryType.get(), length);
    std::string tag(length, '\0');
    if (H5Aread(attribute.get(), memoryType.get(), tag.data()) < 0 || tag != kFormatTag) return notCache;
  }
  double version = 0;
  if (!readDouble(file.get(), "format_version", version)) return notCache;
  if (version != kFormatVersion)
    return makeError(ErrorCode::Usage, path + ": a PSF cache of an earlier lfcam (format " + number(version, "%.10g") +
                                           "): compute the PSFs again");
  // What it was made for, exactly: a PSF of other optics is another PSF.
  for (const Key& key : keysOf(optics, pupil, grid, keep)) {
    double made = 0;
    if (!readDouble(file.get(), key.attribute, made)) return notCache;
    if (made != key.value)
      return makeError(ErrorCode::Usage, path + ": made for " + key.name + " " + number(made, "%.10g") + ", not " +
                                             number(key.value, "%.10g") +
                                             ": compute the PSFs again for these settings");
  }
  LfmSparsePsf psf{.optics = optics, .pupil = pupil, .grid = grid, .keptEnergy = keep};
  double reach = 0;
  if (!readDouble(file.get(), "reach", reach) || reach < 0 || reach > 127 || reach != int(reach)) return notCache;
  psf.reach = int(reach);
  std::vector<double> depths(grid.depthsUm.size());
  if (datasetLength(file.get(), "depths_um") != hssize_t(depths.size()))
    return makeError(ErrorCode::Usage, path + ": made for " + std::to_string(datasetLength(file.get(), "depths_um")) +
                                           " slices, not " + std::to_string(depths.size()) +
                                           ": compute the PSFs again for these settings");
  if (!readDataset(file.get(), "depths_um", H5T_NATIVE_DOUBLE, {hsize_t(depths.size())}, depths.data()))
    return notCache;
  for (std::size_t d = 0; d < depths.size(); ++d)
    if (depths[d] != grid.depthsUm[d])
      return makeError(ErrorCode::Usage, path + ": made for a slice at " + number(depths[d], "%.10g") + " um, not " +
                                             number(grid.depthsUm[d], "%.10g") +
                                             ": compute the PSFs again for these settings");
  const std::size_t phases = depths.size() * grid.voxelsPerLenslet * grid.voxelsPerLenslet * optics.rowsPerPeriod();
  std::vector<std::uint64_t> begins(phases + 1);
  if (datasetLength(file.get(), "begins") != hssize_t(begins.size()) ||
      !readDataset(file.get(), "begins", H5T_NATIVE_UINT64, {hsize_t(begins.size())}, begins.data()))
    return notCache;
  const hssize_t count = datasetLength(file.get(), "weights");
  if (count < 0 || begins.front() != 0 || begins.back() != std::uint64_t(count) ||
      !std::is_sorted(begins.begin(), begins.end()))
    return notCache;
  SplatColumns columns{std::vector<std::uint16_t>(count), std::vector<std::int8_t>(count),
                       std::vector<std::int8_t>(count), std::vector<float>(count)};
  const std::vector<hsize_t> dims{hsize_t(count)};
  if (!readDataset(file.get(), "pixels", H5T_NATIVE_UINT16, dims, columns.pixels.data()) ||
      !readDataset(file.get(), "lenslet_dx", H5T_NATIVE_INT8, dims, columns.dx.data()) ||
      !readDataset(file.get(), "lenslet_dy", H5T_NATIVE_INT8, dims, columns.dy.data()) ||
      !readDataset(file.get(), "weights", H5T_NATIVE_FLOAT, dims, columns.weights.data()))
    return notCache;
  const int pixels = grid.pixelsPerLenslet * grid.pixelsPerLenslet * optics.rowsPerPeriod();
  psf.begins.assign(begins.begin(), begins.end());
  psf.splats.resize(count);
  for (hssize_t k = 0; k < count; ++k) {
    // The projectors index with these: a damaged file must not reach them.
    if (columns.pixels[k] >= pixels || std::abs(columns.dx[k]) > psf.reach || std::abs(columns.dy[k]) > psf.reach ||
        !std::isfinite(columns.weights[k]))
      return notCache;
    psf.splats[k] = {columns.pixels[k], columns.dx[k], columns.dy[k], columns.weights[k]};
  }
  return psf;
}

}  // namespace lfcam
