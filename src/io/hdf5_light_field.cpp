#include "io/hdf5_light_field.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "io/io_support.hpp"
#include "io/survives_in_child.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormatTag = "lfcam-lightfield";
constexpr int kFormatVersion = 1;
constexpr const char* kAxes = "v,u,c,t,s";
constexpr unsigned kDeflateLevel = 1;  // float samples gain little from higher levels, and cost time

std::mutex& hdf5Mutex() {
  static std::mutex mutex;
  return mutex;
}

// Holds the lock and keeps HDF5 from printing its error stack to stderr.
class Hdf5Session {
 public:
  Hdf5Session() : lock_(hdf5Mutex()) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    H5Eclear2(H5E_DEFAULT);
  }

 private:
  std::lock_guard<std::mutex> lock_;
};

// An HDF5 identifier closed by the matching function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now, reporting failure (a file's last metadata is written when it closes).
  bool close() {
    const bool ok = id_ < 0 || close_(id_) >= 0;
    id_ = -1;
    return ok;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// The innermost message on HDF5's error stack: the actual reason ("file signature not found").
// Walking downward goes from the API call to where the error arose, so the last entry wins.
std::string hdf5Reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        if (error->desc && *error->desc) *static_cast<std::string*>(data) = error->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "unknown HDF5 error" : reason;
}

Error hdf5Error(ErrorCode code, const fs::path& path, const std::string& what) {
  return fileError(code, path, what + ": " + hdf5Reason());
}

// File access: tolerate file systems without locking (network mounts) instead of failing.
Handle fileAccess() {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_file_locking(fapl.get(), true, true);
  return fapl;
}

// ---- attributes ----

Result<std::optional<std::string>> readStringAttribute(const fs::path& path, hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return std::optional<std::string>();
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  if (!attribute.valid() || !type.valid() || H5Tget_class(type.get()) != H5T_STRING ||
      H5Sget_simple_extent_npoints(space.get()) != 1)
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' is not a string");
  // libhdf5 1.10 copies a variable-length string's global-heap object into a buffer sized by the
  // attribute's own length field, so a file whose two disagree overflows the heap inside H5Aread
  // (fuzz/regressions/hdf5_light_field). lfcam writes fixed-length strings and refuses the others.
  if (H5Tis_variable_str(type.get()) != 0)
    return fileError(ErrorCode::Unsupported, path,
                     std::string("attribute '") + name +
                         "' is a variable-length string; lfcam reads fixed-length string attributes only");
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > (1u << 20))
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' has a bad size");
  std::vector<char> text(size + 1, '\0');
  if (H5Aread(attribute.get(), type.get(), text.data()) < 0)
    return hdf5Error(ErrorCode::Format, path, std::string("cannot read attribute '") + name + "'");
  return std::optional<std::string>(std::string(text.data()));  // up to the first NUL
}

Result<std::optional<double>> readNumberAttribute(const fs::path& path, hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return std::optional<double>();
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  const H5T_class_t typeClass = type.valid() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  if (!attribute.valid() || (typeClass != H5T_FLOAT && typeClass != H5T_INTEGER) ||
      H5Sget_simple_extent_npoints(space.get()) != 1)
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' is not a number");
  double value = 0;
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    return hdf5Error(ErrorCode::Format, path, std::string("cannot read attribute '") + name + "'");
  return std::optional<double>(value);
}

bool writeStringAttribute(hid_t object, const char* name, const std::string& value) {
  // Fixed-length UTF-8, NUL-padded (see readStringAttribute for why not variable-length): h5py
  // reads it as bytes, MATLAB's h5readatt as char.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1));
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  std::string padded = value;
  padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
  return attribute.valid() && H5Awrite(attribute.get(), type.get(), padded.data()) >= 0;
}

template <class T>
bool writeScalarAttribute(hid_t object, const char* name, hid_t fileType, hid_t memoryType, T value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return attribute.valid() && H5Awrite(attribute.get(), memoryType, &value) >= 0;
}

// ---- reading ----

struct OpenedFile {
  std::unique_ptr<Handle> file, samples, weight;
  LightFieldInfo info;
};

// A dataset of floats (any precision: HDF5 converts) of the given rank, or a Format error.
Result<std::vector<hsize_t>> floatDatasetDims(const fs::path& path, hid_t dataset, const char* name, int rank,
                                              const char* axes) {
  Handle type(H5Dget_type(dataset), H5Tclose);
  Handle space(H5Dget_space(dataset), H5Sclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_FLOAT)
    return fileError(ErrorCode::Format, path, std::string("dataset ") + name + " does not hold floating-point samples");
  const int found = H5Sget_simple_extent_ndims(space.get());
  if (found != rank)
    return fileError(ErrorCode::Format, path,
                     std::string("dataset ") + name + " has " + std::to_string(found) + " dimensions, expected " +
                         std::to_string(rank) + " (" + axes + ")");
  std::vector<hsize_t> dims(std::size_t(rank), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  for (hsize_t dim : dims)
    if (dim == 0 || dim > hsize_t(INT_MAX))
      return fileError(ErrorCode::Format, path, std::string("dataset ") + name + " has an empty or absurd dimension");
  return dims;
}

Result<OpenedFile> openLightFieldFile(const fs::path& path) {
  LFCAM_TRY(checkReadableFile(path));
  OpenedFile opened;
  Handle fapl = fileAccess();
  opened.file = std::make_unique<Handle>(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!opened.file->valid()) return hdf5Error(ErrorCode::Format, path, "not a readable HDF5 file");
  const hid_t file = opened.file->get();

  // Identity: files of other kinds are refused, files without the tag are accepted by layout.
  LFCAM_ASSIGN_OR_RETURN(auto tag, readStringAttribute(path, file, "lfcam_format"));
  if (tag && *tag != kFormatTag)
    return fileError(ErrorCode::Format, path, "an HDF5 file of another kind (lfcam_format = '" + *tag + "')");
  LFCAM_ASSIGN_OR_RETURN(auto version, readNumberAttribute(path, file, "lfcam_version"));
  if (version && *version > kFormatVersion)
    return fileError(ErrorCode::Unsupported, path,
                     "written by a newer lfcam (format version " + std::to_string(int(*version)) + ")");
  LFCAM_ASSIGN_OR_RETURN(auto axes, readStringAttribute(path, file, "axes"));
  if (axes && *axes != kAxes)
    return fileError(ErrorCode::Unsupported, path, "axes '" + *axes + "' are not supported (expected " + kAxes + ")");

  if (H5Lexists(file, "lightfield", H5P_DEFAULT) <= 0)
    return fileError(ErrorCode::Format, path,
                     "not an lfcam light field: no /lightfield dataset (an HDF5 file of another layout)");
  opened.samples = std::make_unique<Handle>(H5Dopen2(file, "lightfield", H5P_DEFAULT), H5Dclose);
  if (!opened.samples->valid()) return hdf5Error(ErrorCode::Format, path, "/lightfield is not a readable dataset");
  LFCAM_ASSIGN_OR_RETURN(auto dims, floatDatasetDims(path, opened.samples->get(), "/lightfield", 5, kAxes));
  LightFieldShape& shape = opened.info.shape;
  shape = {.nu = int(dims[1]), .nv = int(dims[0]), .ns = int(dims[4]), .nt = int(dims[3]), .channels = int(dims[2])};
  // Samples the file cannot hold mean a corrupt header (or chunks never written): deflate, the
  // only filter lfcam writes, compresses at most about 1032:1.
  {
    std::error_code ec;
    const std::uint64_t fileSize = fs::file_size(path, ec);
    const auto bytes = checkedProduct({dims[0], dims[1], dims[2], dims[3], dims[4], sizeof(float)});
    if (!ec && (!bytes || *bytes / 1100 > fileSize + 4096))
      return fileError(ErrorCode::Format, path,
                       "truncated or corrupt: /lightfield claims " + formatBytes(bytes.value_or(UINT64_MAX)) +
                           " of samples but the file has only " + std::to_string(fileSize) + " bytes");
  }
  LFCAM_TRY(checkSampleCount(path, {dims[0], dims[1], dims[2], dims[3], dims[4]}));

  if (H5Lexists(file, "weight", H5P_DEFAULT) > 0) {
    opened.weight = std::make_unique<Handle>(H5Dopen2(file, "weight", H5P_DEFAULT), H5Dclose);
    if (!opened.weight->valid()) return hdf5Error(ErrorCode::Format, path, "/weight is not a readable dataset");
    LFCAM_ASSIGN_OR_RETURN(auto weightDims, floatDatasetDims(path, opened.weight->get(), "/weight", 4, "v,u,t,s"));
    if (weightDims != std::vector<hsize_t>{dims[0], dims[1], dims[3], dims[4]})
      return fileError(ErrorCode::Format, path, "/weight does not match the dimensions of /lightfield");
    opened.info.hasWeight = true;
  }

  // Metadata.
  LightFieldMetadata& metadata = opened.info.metadata;
  std::optional<double> numbers[6];
  const char* names[6] = {"lens_step_mm",    "spatial_step_mm", "lens_to_microlens_mm",
                          "focal_length_mm", "disparity_min",   "disparity_max"};
  for (int i = 0; i < 6; ++i) {
    LFCAM_ASSIGN_OR_RETURN(auto number, readNumberAttribute(path, file, names[i]));
    numbers[i] = number;
  }
  const int opticsGiven = int(bool(numbers[0])) + int(bool(numbers[1])) + int(bool(numbers[2]));
  if (opticsGiven == 3) {
    metadata.optics = Optics{.lensStepMm = *numbers[0],
                             .spatialStepMm = *numbers[1],
                             .lensToMicrolensMm = *numbers[2],
                             .focalLengthMm = numbers[3]};
  } else if (opticsGiven > 0) {
    return fileError(ErrorCode::Format, path,
                     "incomplete optics: lens_step_mm, spatial_step_mm and lens_to_microlens_mm go together");
  }
  metadata.disparityMin = numbers[4];
  metadata.disparityMax = numbers[5];
  LFCAM_ASSIGN_OR_RETURN(auto source, readStringAttribute(path, file, "source"));
  metadata.source = source.value_or("");
  opened.info.format = LightFieldFormat::Hdf5;
  return opened;
}

// True when a per-view read touches each stored chunk once (chunks no larger than a view).
bool readsViewByView(hid_t dataset) {
  Handle dcpl(H5Dget_create_plist(dataset), H5Pclose);
  if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED) return true;
  hsize_t chunk[5] = {};
  const int rank = H5Pget_chunk(dcpl.get(), 5, chunk);
  return rank >= 2 && chunk[0] == 1 && chunk[1] == 1;
}

// Reads `dataset` (views outermost, `viewValues` floats each) into `out`, view by view when the
// chunks allow, so that progress can be reported.

// The extent of one view, (1, 1, rest of dims), and its selection in a [nv, nu, ...] dataset.
std::vector<hsize_t> oneViewCount(const std::vector<hsize_t>& dims) {
  std::vector<hsize_t> count = dims;
  count[0] = count[1] = 1;
  return count;
}

void selectView(hid_t fileSpace, const std::vector<hsize_t>& dims, std::size_t view) {
  std::vector<hsize_t> start(dims.size(), 0);
  start[0] = view / dims[1];
  start[1] = view % dims[1];
  const std::vector<hsize_t> count = oneViewCount(dims);
  H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
}

Status readViews(const fs::path& path, hid_t dataset, int rank, std::size_t views, std::size_t viewValues, float* out,
                 const std::function<void()>& viewDone) {
  if (!readsViewByView(dataset)) {
    if (H5Dread(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
      return hdf5Error(ErrorCode::Format, path, "cannot read samples");
    for (std::size_t i = 0; i < views; ++i) viewDone();
    return {};
  }
  Handle fileSpace(H5Dget_space(dataset), H5Sclose);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(fileSpace.get(), dims.data(), nullptr);
  // The memory space has the selection's shape: with a flat one, HDF5 copies element by element.
  const std::vector<hsize_t> count = oneViewCount(dims);
  Handle memorySpace(H5Screate_simple(rank, count.data(), nullptr), H5Sclose);
  for (std::size_t view = 0; view < views; ++view) {
    selectView(fileSpace.get(), dims, view);
    if (H5Dread(dataset, H5T_NATIVE_FLOAT, memorySpace.get(), fileSpace.get(), H5P_DEFAULT, out + view * viewValues) <
        0)
      return hdf5Error(ErrorCode::Format, path, "cannot read samples");
    viewDone();
  }
  return {};
}

// ---- writing ----

Status writeViews(const fs::path& path, hid_t file, const char* name, const std::vector<hsize_t>& dims,
                  const float* values, const std::function<void()>& viewDone) {
  const int rank = int(dims.size());
  const std::size_t views = std::size_t(dims[0] * dims[1]);
  std::size_t viewValues = 1;
  for (int i = 2; i < rank; ++i) viewValues *= std::size_t(dims[std::size_t(i)]);

  // One chunk per view, unless a view passes HDF5's 4 GiB chunk limit: then bands of rows.
  std::vector<hsize_t> chunk = dims;
  chunk[0] = chunk[1] = 1;
  constexpr std::size_t kMaxChunkBytes = std::size_t(1) << 31;
  if (viewValues * sizeof(float) > kMaxChunkBytes) {
    const std::size_t rowBytes = std::size_t(dims.back()) * sizeof(float);
    for (int i = 2; i < rank - 2; ++i) chunk[std::size_t(i)] = 1;
    chunk[std::size_t(rank - 2)] = std::max<hsize_t>(1, kMaxChunkBytes / rowBytes);
  }
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_chunk(dcpl.get(), rank, chunk.data());
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), kDeflateLevel);
  }
  Handle fileSpace(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose);
  Handle dataset(H5Dcreate2(file, name, H5T_IEEE_F32LE, fileSpace.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                 H5Dclose);
  if (!dataset.valid()) return hdf5Error(ErrorCode::Io, path, std::string("cannot create dataset ") + name);

  const std::vector<hsize_t> count = oneViewCount(dims);
  Handle memorySpace(H5Screate_simple(rank, count.data(), nullptr), H5Sclose);
  for (std::size_t view = 0; view < views; ++view) {
    selectView(fileSpace.get(), dims, view);
    if (H5Dwrite(dataset.get(), H5T_NATIVE_FLOAT, memorySpace.get(), fileSpace.get(), H5P_DEFAULT,
                 values + view * viewValues) < 0)
      return hdf5Error(ErrorCode::Io, path, "cannot write samples");
    viewDone();
  }
  return {};
}

Status writeMetadata(const fs::path& path, hid_t file, const LightFieldMetadata& metadata) {
  bool ok = writeStringAttribute(file, "lfcam_format", kFormatTag) &&
            writeScalarAttribute(file, "lfcam_version", H5T_STD_I32LE, H5T_NATIVE_INT, kFormatVersion) &&
            writeStringAttribute(file, "axes", kAxes) && writeStringAttribute(file, "source", metadata.source);
  const auto number = [&](const char* name, double value) {
    ok = ok && writeScalarAttribute(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value);
  };
  if (metadata.optics) {
    number("lens_step_mm", metadata.optics->lensStepMm);
    number("spatial_step_mm", metadata.optics->spatialStepMm);
    number("lens_to_microlens_mm", metadata.optics->lensToMicrolensMm);
    if (metadata.optics->focalLengthMm) number("focal_length_mm", *metadata.optics->focalLengthMm);
  }
  if (metadata.disparityMin) number("disparity_min", *metadata.disparityMin);
  if (metadata.disparityMax) number("disparity_max", *metadata.disparityMax);
  if (!ok) return hdf5Error(ErrorCode::Io, path, "cannot write attributes");
  return {};
}

}  // namespace

bool startsLikeHdf5(const fs::path& path) {
  static constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  for (std::uintmax_t offset = 0; !ec && in && offset + 8 <= size; offset = offset == 0 ? 512 : offset * 2) {
    unsigned char head[8] = {};
    in.seekg(std::streamoff(offset));
    in.read(reinterpret_cast<char*>(head), 8);
    if (in.gcount() == 8 && std::memcmp(head, kSignature, 8) == 0) return true;
  }
  return false;
}

namespace {

// The samples (and weights) of an opened file, read view by view.
Result<LightField> readOpened(const fs::path& path, const OpenedFile& opened, const ProgressCallback& progress) {
  const LightFieldShape& shape = opened.info.shape;
  LightField lightField(shape);
  lightField.metadata = opened.info.metadata;

  const std::size_t views = shape.views();
  const std::size_t steps = views * (opened.info.hasWeight ? 2 : 1);
  std::size_t done = 0;
  const auto viewDone = [&] {
    ++done;
    if (progress) progress(double(done) / double(steps));
  };
  LFCAM_TRY(readViews(path, opened.samples->get(), 5, views, shape.viewPixels() * std::size_t(shape.channels),
                      lightField.samples().data(), viewDone));
  if (opened.info.hasWeight) {
    lightField.enableWeight();
    LFCAM_TRY(
        readViews(path, opened.weight->get(), 4, views, shape.viewPixels(), lightField.weights().data(), viewDone));
  }
  return lightField;
}

// What the reader will ask of libhdf5, asked first in a throwaway process (survives_in_child.hpp):
// the metadata, every chunk's entry in the chunk index, and, when the samples are small enough to
// read twice without notice, every sample. A crash or hang there refuses the file. Larger files
// are read once, after the child has walked their metadata and chunk index; what it does not
// exercise for them is the decompression of the chunks' payloads (zlib's, which is hardened).
Status refuseWhatCrashesLibhdf5(const fs::path& path) {
  constexpr std::size_t kReadTwiceBytes = std::size_t(64) << 20;
  const ChildOutcome outcome = survivesInChild(
      [&] {
        auto opened = openLightFieldFile(path);
        if (!opened) return;  // a clean error: the parent will find and report it itself
        for (const auto* dataset : {opened->samples.get(), opened->weight.get()}) {
          hsize_t chunks = 0;
          if (!dataset || H5Dget_num_chunks(dataset->get(), H5S_ALL, &chunks) < 0) continue;
          for (hsize_t i = 0; i < std::min<hsize_t>(chunks, 4096); ++i) {
            hsize_t offset[5] = {}, size = 0;
            unsigned filterMask = 0;
            haddr_t address = 0;
            H5Dget_chunk_info(dataset->get(), H5S_ALL, i, offset, &filterMask, &address, &size);
          }
        }
        const LightFieldShape& shape = opened->info.shape;
        if (shape.samples() * sizeof(float) <= kReadTwiceBytes) (void)readOpened(path, *opened, {});
      },
      std::chrono::seconds(30));
  if (outcome == ChildOutcome::Crashed)
    return fileError(ErrorCode::Format, path,
                     "a corrupt HDF5 file: libhdf5 crashed reading it (in a throwaway process)");
  if (outcome == ChildOutcome::TimedOut)
    return fileError(ErrorCode::Format, path, "a corrupt HDF5 file: libhdf5 did not finish reading it within 30 s");
  return {};
}

}  // namespace

Result<LightFieldInfo> probeHdf5(const fs::path& path) {
  Hdf5Session session;
  LFCAM_TRY(refuseWhatCrashesLibhdf5(path));
  LFCAM_ASSIGN_OR_RETURN(auto opened, openLightFieldFile(path));
  return opened.info;
}

Result<LightField> readHdf5(const fs::path& path, const ProgressCallback& progress) {
  Hdf5Session session;
  LFCAM_TRY(refuseWhatCrashesLibhdf5(path));
  LFCAM_ASSIGN_OR_RETURN(auto opened, openLightFieldFile(path));
  return readOpened(path, opened, progress);
}

Status writeHdf5(const fs::path& file, const LightField& lightField, const ProgressCallback& progress,
                 const fs::path& path) {
  Hdf5Session session;
  const LightFieldShape& shape = lightField.shape();
  Handle fapl = fileAccess();
  Handle handle(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (!handle.valid()) return hdf5Error(ErrorCode::Io, path, "cannot create");

  const std::size_t steps = shape.views() * (lightField.hasWeight() ? 2 : 1);
  std::size_t done = 0;
  const auto viewDone = [&] {
    ++done;
    if (progress) progress(double(done) / double(steps));
  };
  LFCAM_TRY(writeMetadata(path, handle.get(), lightField.metadata));
  const auto nv = hsize_t(shape.nv), nu = hsize_t(shape.nu), nt = hsize_t(shape.nt), ns = hsize_t(shape.ns);
  LFCAM_TRY(writeViews(path, handle.get(), "lightfield", {nv, nu, hsize_t(shape.channels), nt, ns},
                       lightField.samples().data(), viewDone));
  if (lightField.hasWeight())
    LFCAM_TRY(writeViews(path, handle.get(), "weight", {nv, nu, nt, ns}, lightField.weights().data(), viewDone));
  if (!handle.close()) return hdf5Error(ErrorCode::Io, path, "cannot write");
  return {};
}

}  // namespace lfcam::io
