// The PSF cache (psf.hpp): one HDF5 file, written and read under the library's one HDF5 lock.
#include <hdf5.h>

#include <cstdio>
#include <mutex>
#include <string>

#include "core/atomic_file.hpp"
#include "core/hdf5_handle.hpp"
#include "core/hdf5_lock.hpp"
#include "lfcam/lfm/psf.hpp"
#include "lfm/psf_stages.hpp"

namespace lfcam {

namespace {

using hdf5::Handle;

constexpr const char* kFormatTag = "lfcam-lfm-psf";
constexpr int kFormatVersion = 1;

// Every number the cache is keyed by, with the name a refusal shows.
struct Key {
  const char* attribute;
  const char* name;
  double value;
};

std::vector<Key> keysOf(const LfmOptics& o, PupilModel pupil) {
  return {{"magnification", "magnification", o.magnification},
          {"numerical_aperture", "NA", o.numericalAperture},
          {"immersion_index", "immersion index", o.immersionIndex},
          {"wavelength_nm", "wavelength (nm)", o.wavelengthNm},
          {"tube_focal_length_mm", "tube lens focal length (mm)", o.tubeFocalLengthMm},
          {"microlens_pitch_um", "microlens pitch (um)", o.microlensPitchUm},
          {"microlens_focal_length_um", "microlens focal length (um)", o.microlensFocalLengthUm},
          {"microlens_fill_factor", "microlens fill factor", o.microlensFillFactor},
          {"pixel_size_um", "pixel size (um)", o.pixelSizeUm},
          {"supersample", "supersample", double(o.supersample)},
          {"pupil", "pupil (0 Abbe sine, 1 paraxial)", double(int(pupil))}};
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", x);
  return text;
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

// Writes to `file`, naming `path` (the destination) in errors.
Status writeCacheFile(const LfmPsfSet& set, const std::string& fileName, const std::string& path) {
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
  for (const Key& key : keysOf(set.optics, set.pupil)) ok = ok && writeDouble(file.get(), key.attribute, key.value);
  ok = ok && writeDouble(file.get(), "lenslets_across", set.lensletsAcross) &&
       writeDouble(file.get(), "phases_across", set.phasesAcross);
  ok = ok && writeDataset(file.get(), "depths_um", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {hsize_t(set.depthsUm.size())},
                          set.depthsUm.data());
  const hsize_t p = set.phasesAcross, n = set.pixelsAcross;
  ok = ok && writeDataset(file.get(), "psf", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT,
                          {hsize_t(set.depthsUm.size()), p, p, n, n}, set.values.data());
  if (!ok) return makeError(ErrorCode::Io, path + ": cannot write the PSF cache");
  // The file's last metadata is written as it closes: its failure is the write's.
  if (!file.close()) return makeError(ErrorCode::Io, path + ": cannot write the PSF cache");
  return {};
}

}  // namespace

Status writePsfCache(const LfmPsfSet& set, const std::string& path) {
  // Whole or not at all: a cache cut short by a failure or a kill would be refused as not one, but
  // it would also have replaced a good one.
  return writeFileAtomically(
      path, [&](const std::filesystem::path& temporary) { return writeCacheFile(set, temporary.string(), path); });
}

Result<LfmPsfSet> readPsfCache(const std::string& path, const LfmOptics& optics, PupilModel pupil) {
  LFCAM_TRY(validateLfmOptics(optics));
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
  if (!readDouble(file.get(), "format_version", version) || version != kFormatVersion) return notCache;
  // The optics it was made for, exactly: a PSF of other optics is another PSF.
  for (const Key& key : keysOf(optics, pupil)) {
    double made = 0;
    if (!readDouble(file.get(), key.attribute, made)) return notCache;
    if (made != key.value)
      return makeError(ErrorCode::Usage, path + ": made for " + key.name + " " + number(made) + ", not " +
                                             number(key.value) + ": compute the PSFs again for these optics");
  }
  double lenslets = 0, phases = 0;
  if (!readDouble(file.get(), "lenslets_across", lenslets) || !readDouble(file.get(), "phases_across", phases))
    return notCache;
  if (lenslets < 1 || lenslets > 201 || lenslets != int(lenslets) || phases < 1 || phases > 1000 ||
      phases != int(phases))
    return notCache;
  LfmPsfSet set{.optics = optics,
                .pupil = pupil,
                .lensletsAcross = int(lenslets),
                .phasesAcross = int(phases),
                .pixelsAcross = lfm::windowPixels(optics, int(lenslets))};
  {
    if (H5Lexists(file.get(), "depths_um", H5P_DEFAULT) <= 0) return notCache;
    Handle dataset(H5Dopen2(file.get(), "depths_um", H5P_DEFAULT), H5Dclose);
    Handle space(H5Dget_space(dataset.get()), H5Sclose);
    const hssize_t count = H5Sget_simple_extent_npoints(space.get());
    if (count < 1 || count > 100000) return notCache;
    set.depthsUm.resize(count);
  }
  if (!readDataset(file.get(), "depths_um", H5T_NATIVE_DOUBLE, {hsize_t(set.depthsUm.size())}, set.depthsUm.data()))
    return notCache;
  const hsize_t p = set.phasesAcross, n = set.pixelsAcross;
  set.values.resize(set.depthsUm.size() * p * p * n * n);
  if (!readDataset(file.get(), "psf", H5T_NATIVE_FLOAT, {hsize_t(set.depthsUm.size()), p, p, n, n}, set.values.data()))
    return notCache;
  return set;
}

}  // namespace lfcam
