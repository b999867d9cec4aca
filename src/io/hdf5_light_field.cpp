#include "io/hdf5_light_field.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/hdf5_handle.hpp"
#include "core/parallel.hpp"
#include "io/hdf5_chunk_codec.hpp"
#include "io/hdf5_support.hpp"
#include "io/io_support.hpp"
#include "io/sample_encoding.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

using hdf5::Handle;

constexpr const char* kFormatTag = "lfcam-lightfield";
constexpr int kFormatVersion = 2;  // 2: samples in their own precision (sample_encoding.hpp)
constexpr const char* kAxes = "v,u,c,t,s";
constexpr int kDeflateLevel = 1;              // higher levels gain little on samples (docs/design.md), and cost time
constexpr unsigned kSzipPixelsPerBlock = 32;  // szip's largest block: the fastest, as small as 16 here

// ---- reading ----

// Views and values per view of a [nv, nu, ...] dataset.
std::size_t viewsOf(const std::vector<hsize_t>& dims) { return std::size_t(dims[0] * dims[1]); }
std::size_t viewValuesOf(const std::vector<hsize_t>& dims) {
  std::size_t values = 1;
  for (std::size_t i = 2; i < dims.size(); ++i) values *= std::size_t(dims[i]);
  return values;
}

// One stored array, /lightfield or /weight, and how its samples are encoded.
struct StoredSamples {
  std::unique_ptr<Handle> dataset;
  std::vector<hsize_t> dims;
  SampleEncoding encoding;
  // Set when lfcam reads the chunks raw and unfilters them itself: one chunk per view, stored in
  // the encoding's own little-endian type, filtered by shuffle and deflate only, in that order, or
  // by szip alone (with `szip` its parameters).
  std::optional<std::vector<H5Z_filter_t>> rawFilters;
  std::optional<SzipParameters> szip;

  std::size_t views() const { return viewsOf(dims); }
  std::size_t viewValues() const { return viewValuesOf(dims); }
};

struct OpenedFile {
  std::unique_ptr<Handle> file;
  StoredSamples samples;
  std::optional<StoredSamples> weight;
  LightFieldInfo info;
};

// IEEE binary16, little-endian, as h5py writes numpy's float16.
Handle float16Type() {
  Handle type(H5Tcopy(H5T_IEEE_F32LE), H5Tclose);
  H5Tset_fields(type.get(), 15, 10, 5, 0, 10);
  H5Tset_size(type.get(), 2);
  H5Tset_ebias(type.get(), 15);
  return type;
}

Handle fileTypeOf(SampleEncodingKind kind) {
  switch (kind) {
    case SampleEncodingKind::Srgb8:
    case SampleEncodingKind::Linear8: return Handle(H5Tcopy(H5T_STD_U8LE), H5Tclose);
    case SampleEncodingKind::Linear16: return Handle(H5Tcopy(H5T_STD_U16LE), H5Tclose);
    case SampleEncodingKind::Float16: return float16Type();
    case SampleEncodingKind::Float32: break;
  }
  return Handle(H5Tcopy(H5T_IEEE_F32LE), H5Tclose);
}

const char* encodingName(SampleEncodingKind kind) {
  switch (kind) {
    case SampleEncodingKind::Srgb8: return "srgb8";
    case SampleEncodingKind::Linear8:
    case SampleEncodingKind::Linear16: return "linear";
    case SampleEncodingKind::Float16:
    case SampleEncodingKind::Float32: break;
  }
  return "float";
}

// The encoding of `dataset` from its type and its `encoding` (and `scale`) attributes.
Result<SampleEncoding> encodingOf(const fs::path& path, hid_t dataset, hid_t type, const std::string& name) {
  LFCAM_ASSIGN_OR_RETURN(auto encoding, readStringAttribute(path, dataset, "encoding"));
  const H5T_class_t typeClass = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  if (typeClass == H5T_FLOAT) {
    if (encoding && *encoding != "float")
      return fileError(ErrorCode::Format, path,
                       "dataset " + name + " holds floats but says encoding '" + *encoding + "'");
    return SampleEncoding{size == 2 ? SampleEncodingKind::Float16 : SampleEncodingKind::Float32};
  }
  if (typeClass != H5T_INTEGER)
    return fileError(ErrorCode::Format, path, "dataset " + name + " does not hold samples (floats or integer codes)");
  if (!encoding)
    return fileError(
        ErrorCode::Format, path,
        "dataset " + name + " holds integers without an 'encoding' attribute (srgb8, or linear with a scale)");
  const bool isUnsigned = H5Tget_sign(type) == H5T_SGN_NONE;
  if (*encoding == "srgb8") {
    if (!isUnsigned || size != 1)
      return fileError(ErrorCode::Format, path,
                       "dataset " + name + " says srgb8 but does not hold 8-bit unsigned codes");
    return SampleEncoding{SampleEncodingKind::Srgb8};
  }
  if (*encoding != "linear")
    return fileError(ErrorCode::Unsupported, path, "dataset " + name + " has an unknown encoding '" + *encoding + "'");
  if (!isUnsigned || (size != 1 && size != 2))
    return fileError(ErrorCode::Format, path,
                     "dataset " + name + " says linear but does not hold 8- or 16-bit unsigned codes");
  LFCAM_ASSIGN_OR_RETURN(auto scale, readNumberAttribute(path, dataset, "scale"));
  if (!scale || !std::isfinite(*scale) || *scale <= 0 || *scale > 1e30)
    return fileError(ErrorCode::Format, path, "dataset " + name + " needs a positive finite 'scale' attribute");
  return SampleEncoding{size == 1 ? SampleEncodingKind::Linear8 : SampleEncodingKind::Linear16, *scale};
}

// The filters lfcam undoes itself when the chunks are laid out as it writes them (into
// `stored.rawFilters` and `stored.szip`); left unset when libhdf5 must read the dataset (and then
// every filter must be one libhdf5 can load).
Status findRawFilters(const fs::path& path, StoredSamples& stored, hid_t type, const std::string& name) {
  Handle dcpl(H5Dget_create_plist(stored.dataset->get()), H5Pclose);
  std::vector<H5Z_filter_t> filters;
  bool ownFilters = true;
  for (int i = 0, count = H5Pget_nfilters(dcpl.get()); i < count; ++i) {
    char filterName[64] = {};
    unsigned flags = 0, values[4] = {};
    std::size_t valueCount = 4;
    const H5Z_filter_t filter =
        H5Pget_filter2(dcpl.get(), unsigned(i), &flags, &valueCount, values, sizeof filterName, filterName, nullptr);
    const bool szip = filter == H5Z_FILTER_SZIP && count == 1;
    const bool own = filter == (filters.empty() ? H5Z_FILTER_SHUFFLE : -1) || filter == H5Z_FILTER_DEFLATE || szip;
    if (!own && H5Zfilter_avail(filter) <= 0)
      return fileError(ErrorCode::Unsupported, path,
                       "dataset " + name + " is compressed with HDF5 filter " + std::to_string(filter) + " (" +
                           filterName + "), which is not installed: install its plugin and set HDF5_PLUGIN_PATH");
    if (szip) {
      // libaec divides by some of these: they are checked before anything decodes with them.
      stored.szip = SzipParameters{values[0], values[1], values[2], values[3]};
      if (valueCount != 4 || !szipParametersValid(*stored.szip, H5Tget_size(type)))
        return fileError(ErrorCode::Format, path, "dataset " + name + " has szip parameters out of range");
    }
    ownFilters = ownFilters && own && (filters.empty() || filters.back() != H5Z_FILTER_DEFLATE);
    filters.push_back(filter);
  }
  hsize_t chunk[5] = {};
  const int rank = int(stored.dims.size());
  const bool oneViewChunks = H5Pget_layout(dcpl.get()) == H5D_CHUNKED &&
                             H5Pget_chunk(dcpl.get(), rank, chunk) == rank && chunk[0] == 1 && chunk[1] == 1 &&
                             std::equal(chunk + 2, chunk + rank, stored.dims.begin() + 2);
  Handle ownType = fileTypeOf(stored.encoding.kind);
  if (ownFilters && oneViewChunks && H5Tequal(type, ownType.get()) > 0) stored.rawFilters = filters;
  return {};
}

Result<StoredSamples> openSamples(const fs::path& path, hid_t file, const char* name, int rank, const char* axes) {
  StoredSamples stored;
  const std::string slashName = std::string("/") + name;
  stored.dataset = std::make_unique<Handle>(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  if (!stored.dataset->valid()) return hdf5Error(ErrorCode::Format, path, slashName + " is not a readable dataset");
  Handle type(H5Dget_type(stored.dataset->get()), H5Tclose);
  Handle space(H5Dget_space(stored.dataset->get()), H5Sclose);
  if (!type.valid() || !space.valid())
    return hdf5Error(ErrorCode::Format, path, slashName + " has no readable type or shape");
  LFCAM_ASSIGN_OR_RETURN(stored.encoding, encodingOf(path, stored.dataset->get(), type.get(), slashName));
  const int found = H5Sget_simple_extent_ndims(space.get());
  if (found != rank)
    return fileError(ErrorCode::Format, path,
                     "dataset " + slashName + " has " + std::to_string(found) + " dimensions, expected " +
                         std::to_string(rank) + " (" + axes + ")");
  stored.dims.assign(std::size_t(rank), 0);
  H5Sget_simple_extent_dims(space.get(), stored.dims.data(), nullptr);
  for (hsize_t dim : stored.dims)
    if (dim == 0 || dim > hsize_t(INT_MAX))
      return fileError(ErrorCode::Format, path, "dataset " + slashName + " has an empty or absurd dimension");
  LFCAM_TRY(findRawFilters(path, stored, type.get(), slashName));
  // Samples the file cannot hold mean a corrupt header (or chunks never written): deflate shrinks
  // at most about 1032:1, szip to at least 2 bytes a scanline (a constant image).
  const std::size_t elementSize = H5Tget_size(type.get());
  const std::uint64_t maxRatio =
      std::max<std::uint64_t>(1100, stored.szip ? stored.szip->pixelsPerScanline * elementSize : 0);
  std::error_code ec;
  const std::uint64_t fileSize = fs::file_size(path, ec);
  std::uint64_t bytes = elementSize;
  for (hsize_t dim : stored.dims) bytes = checkedProduct({bytes, dim}).value_or(UINT64_MAX);
  if (!ec && bytes / maxRatio > fileSize + 4096)
    return fileError(ErrorCode::Format, path,
                     "truncated or corrupt: " + slashName + " claims " + formatBytes(bytes) +
                         " of samples but the file has only " + std::to_string(fileSize) + " bytes");
  return stored;
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
  LFCAM_ASSIGN_OR_RETURN(opened.samples, openSamples(path, file, "lightfield", 5, kAxes));
  const std::vector<hsize_t>& dims = opened.samples.dims;
  LightFieldShape& shape = opened.info.shape;
  shape = {.nu = int(dims[1]), .nv = int(dims[0]), .ns = int(dims[4]), .nt = int(dims[3]), .channels = int(dims[2])};
  LFCAM_TRY(checkSampleCount(path, {dims[0], dims[1], dims[2], dims[3], dims[4]}));

  if (H5Lexists(file, "weight", H5P_DEFAULT) > 0) {
    LFCAM_ASSIGN_OR_RETURN(opened.weight, openSamples(path, file, "weight", 4, "v,u,t,s"));
    if (opened.weight->dims != std::vector<hsize_t>{dims[0], dims[1], dims[3], dims[4]})
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

// The start of view `view` in a [nv, nu, ...] dataset.
std::vector<hsize_t> viewOffset(const std::vector<hsize_t>& dims, std::size_t view) {
  std::vector<hsize_t> offset(dims.size(), 0);
  offset[0] = view / dims[1];
  offset[1] = view % dims[1];
  return offset;
}

// The extent of one view, (1, 1, rest of dims).
std::vector<hsize_t> oneViewCount(const std::vector<hsize_t>& dims) {
  std::vector<hsize_t> count = dims;
  count[0] = count[1] = 1;
  return count;
}

void selectView(hid_t fileSpace, const std::vector<hsize_t>& dims, std::size_t view) {
  const std::vector<hsize_t> start = viewOffset(dims, view), count = oneViewCount(dims);
  H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
}

// One chunk as stored, and which of the dataset's filters were applied to it.
struct RawChunk {
  std::vector<unsigned char> bytes;
  ChunkFilters filters;
};

// The stored bytes of views [first, last), read through libhdf5 without its filters.
Result<std::vector<RawChunk>> readRawChunks(const fs::path& path, const StoredSamples& stored, std::size_t first,
                                            std::size_t last) {
  std::error_code ec;
  const std::uint64_t fileSize = fs::file_size(path, ec);
  std::vector<RawChunk> chunks(last - first);
  for (std::size_t view = first; view < last; ++view) {
    const std::vector<hsize_t> offset = viewOffset(stored.dims, view);
    const std::string which = "the chunk of view " + std::to_string(view);
    hsize_t size = 0;
    if (H5Dget_chunk_storage_size(stored.dataset->get(), offset.data(), &size) < 0 || size == 0)
      return fileError(ErrorCode::Format, path, "truncated or corrupt: " + which + " is missing");
    if (ec || size > fileSize)
      return fileError(ErrorCode::Format, path,
                       "truncated or corrupt: " + which + " claims more bytes than the file has");
    RawChunk& chunk = chunks[view - first];
    chunk.bytes.resize(std::size_t(size));
    std::uint32_t skipped = 0;
    if (H5Dread_chunk(stored.dataset->get(), H5P_DEFAULT, offset.data(), &skipped, chunk.bytes.data()) < 0)
      return hdf5Error(ErrorCode::Format, path, "cannot read " + which);
    const std::vector<H5Z_filter_t>& filters = *stored.rawFilters;
    for (std::size_t i = 0; i < filters.size(); ++i) {
      const bool applied = (skipped & (1u << i)) == 0;
      if (filters[i] == H5Z_FILTER_SZIP) {
        if (applied) chunk.filters.szip = stored.szip;
      } else {
        (filters[i] == H5Z_FILTER_SHUFFLE ? chunk.filters.shuffle : chunk.filters.deflate) = applied;
      }
    }
  }
  return chunks;
}

// Views [first, last) of `stored` into `out` (viewValues floats each) by libhdf5, converted by it
// to float or to native integer codes, which decodeSamples reads as little-endian.
static_assert(std::endian::native == std::endian::little);
Status readViewsThroughLibhdf5(const fs::path& path, const StoredSamples& stored, std::size_t first, std::size_t last,
                               float* out) {
  const hid_t dataset = stored.dataset->get();
  const SampleEncodingKind kind = stored.encoding.kind;
  const bool codes = bytesPerSample(kind) < 4 && kind != SampleEncodingKind::Float16;
  const hid_t memoryType = !codes                                 ? H5T_NATIVE_FLOAT
                           : kind == SampleEncodingKind::Linear16 ? H5T_NATIVE_UINT16
                                                                  : H5T_NATIVE_UINT8;
  Handle fileSpace(H5Dget_space(dataset), H5Sclose);
  const std::vector<hsize_t> count = oneViewCount(stored.dims);
  Handle memorySpace(H5Screate_simple(int(count.size()), count.data(), nullptr), H5Sclose);
  const std::size_t viewValues = stored.viewValues();
  std::vector<unsigned char> scratch(codes ? viewValues * bytesPerSample(kind) : 0);
  for (std::size_t view = first; view < last; ++view) {
    selectView(fileSpace.get(), stored.dims, view);
    float* target = out + view * viewValues;
    void* buffer = codes ? static_cast<void*>(scratch.data()) : static_cast<void*>(target);
    if (H5Dread(dataset, memoryType, memorySpace.get(), fileSpace.get(), H5P_DEFAULT, buffer) < 0)
      return hdf5Error(ErrorCode::Format, path, "cannot read samples");
    if (codes) decodeSamples(stored.encoding, scratch.data(), viewValues, target);
  }
  return {};
}

// Views are read a batch at a time: libhdf5 reads a batch's chunks under its lock, then lfcam's
// threads unfilter and decode them without it, so memory holds one batch of stored bytes.
constexpr std::size_t kViewsPerBatch = 16;

Status decodeRawChunks(const fs::path& path, const StoredSamples& stored, std::size_t first,
                       const std::vector<RawChunk>& chunks, float* out) {
  const std::size_t viewValues = stored.viewValues();
  const std::size_t elementSize = bytesPerSample(stored.encoding.kind);
  std::vector<std::string> problems(chunks.size());
  parallelFor(0, chunks.size(), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<unsigned char> codes(viewValues * elementSize);
    for (std::size_t i = begin; i < end; ++i) {
      problems[i] = unfilterChunk(chunks[i].bytes.data(), chunks[i].bytes.size(), elementSize, chunks[i].filters,
                                  codes.data(), codes.size());
      if (problems[i].empty()) decodeSamples(stored.encoding, codes.data(), viewValues, out + (first + i) * viewValues);
    }
  });
  for (std::size_t i = 0; i < problems.size(); ++i)
    if (!problems[i].empty())
      return fileError(ErrorCode::Format, path, "view " + std::to_string(first + i) + ": " + problems[i]);
  return {};
}

// Every view of `stored` into `out`, reporting each view done; `session` is unlocked while
// lfcam's threads decode.
Status readSamples(const fs::path& path, Hdf5Session& session, const StoredSamples& stored, float* out,
                   const std::function<void()>& viewDone) {
  for (std::size_t first = 0; first < stored.views(); first += kViewsPerBatch) {
    const std::size_t last = std::min(stored.views(), first + kViewsPerBatch);
    if (stored.rawFilters) {
      LFCAM_ASSIGN_OR_RETURN(auto chunks, readRawChunks(path, stored, first, last));
      LFCAM_TRY(session.unlockedWhile([&] { return decodeRawChunks(path, stored, first, chunks, out); }));
    } else {
      LFCAM_TRY(readViewsThroughLibhdf5(path, stored, first, last, out));
    }
    for (std::size_t view = first; view < last; ++view) viewDone();
  }
  return {};
}

// ---- writing ----

// Writes `values` (views outermost, `dims` = [nv, nu, ...]) as one dataset of the most compact
// exact encoding, one deflated chunk per view, encoded and deflated by lfcam's threads a batch at a
// time with `session` unlocked.
Status writeSamples(const fs::path& path, Hdf5Session& session, hid_t file, const char* name,
                    const std::vector<hsize_t>& dims, std::span<const float> values,
                    std::span<const SampleEncoding> candidates, const std::function<void()>& viewDone) {
  const int rank = int(dims.size());
  const std::size_t views = viewsOf(dims), viewValues = viewValuesOf(dims);
  const SampleEncoding encoding =
      session.unlockedWhile([&] { return exactEncodingOf(values, viewValues, candidates); });
  const std::size_t elementSize = bytesPerSample(encoding.kind);
  // A chunk holds at most 4 GiB; a view that large would not be a light field this tool can hold.
  if (viewValues * elementSize > (std::size_t(1) << 31))
    return fileError(ErrorCode::Unsupported, path, "a view larger than 2 GiB does not fit one HDF5 chunk");
  // Integer codes go through szip, which codes each sample's difference from the previous one in
  // its row, as PNG's filters do (smaller than the PNGs they came from, docs/design.md); floats
  // through shuffle and deflate. szip needs a view of at least one block of pixels.
  const bool szip = encoding.kind != SampleEncodingKind::Float16 && encoding.kind != SampleEncodingKind::Float32 &&
                    viewValues >= kSzipPixelsPerBlock;
  ChunkFilters filters{.shuffle = !szip && elementSize > 1, .deflate = !szip};

  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  const std::vector<hsize_t> chunk = oneViewCount(dims);
  H5Pset_chunk(dcpl.get(), rank, chunk.data());
  if (filters.shuffle) H5Pset_shuffle(dcpl.get());
  if (filters.deflate) H5Pset_deflate(dcpl.get(), kDeflateLevel);
  if (szip) H5Pset_szip(dcpl.get(), H5_SZIP_NN_OPTION_MASK, kSzipPixelsPerBlock);
  Handle fileSpace(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose);
  Handle type = fileTypeOf(encoding.kind);
  Handle dataset(H5Dcreate2(file, name, type.get(), fileSpace.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) return hdf5Error(ErrorCode::Io, path, std::string("cannot create dataset ") + name);
  if (szip) {
    // The parameters libhdf5 completed for this dataset (sample width, scanline, byte order).
    Handle created(H5Dget_create_plist(dataset.get()), H5Pclose);
    unsigned flags = 0, cd[4] = {};  // the filter's client data, HDF5's cd_values
    std::size_t valueCount = 4;
    if (H5Pget_filter_by_id2(created.get(), H5Z_FILTER_SZIP, &flags, &valueCount, cd, 0, nullptr, nullptr) < 0 ||
        valueCount != 4)
      return hdf5Error(ErrorCode::Io, path, std::string("cannot set up szip for ") + name);
    filters.szip = SzipParameters{cd[0], cd[1], cd[2], cd[3]};
  }
  bool ok = writeStringAttribute(dataset.get(), "encoding", encodingName(encoding.kind));
  if (encoding.kind == SampleEncodingKind::Linear8 || encoding.kind == SampleEncodingKind::Linear16)
    ok = ok && writeScalarAttribute(dataset.get(), "scale", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, encoding.scale);
  if (!ok) return hdf5Error(ErrorCode::Io, path, std::string("cannot write the encoding of ") + name);

  for (std::size_t first = 0; first < views; first += kViewsPerBatch) {
    const std::size_t last = std::min(views, first + kViewsPerBatch);
    std::vector<std::vector<unsigned char>> chunks(last - first);
    std::vector<std::uint32_t> skipped(last - first, 0);  // filter masks: bit 0 for an unfiltered szip chunk
    session.unlockedWhile([&] {
      parallelFor(first, last, 1, [&](std::size_t begin, std::size_t end) {
        std::vector<unsigned char> codes(viewValues * elementSize);
        for (std::size_t view = begin; view < end; ++view) {
          encodeExactly(encoding, values.subspan(view * viewValues, viewValues), codes.data());
          std::vector<unsigned char>& stored = chunks[view - first];
          stored = filterChunk(codes.data(), codes.size(), elementSize, filters, kDeflateLevel);
          if (stored.empty()) {  // szip would not shrink it
            stored = codes;
            skipped[view - first] = 1;
          }
        }
      });
    });
    for (std::size_t view = first; view < last; ++view) {
      const std::vector<unsigned char>& bytes = chunks[view - first];
      const std::vector<hsize_t> offset = viewOffset(dims, view);
      if (H5Dwrite_chunk(dataset.get(), H5P_DEFAULT, skipped[view - first], offset.data(), bytes.size(), bytes.data()) <
          0)
        return hdf5Error(ErrorCode::Io, path, "cannot write samples");
      viewDone();
    }
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

namespace {

// The samples (and weights) of an opened file.
Result<LightField> readOpened(const fs::path& path, Hdf5Session& session, const OpenedFile& opened,
                              const ProgressCallback& progress) {
  const LightFieldShape& shape = opened.info.shape;
  LightField lightField(shape);
  lightField.metadata = opened.info.metadata;

  const std::size_t steps = shape.views() * (opened.weight ? 2 : 1);
  std::size_t done = 0;
  const auto viewDone = [&] {
    ++done;
    if (progress) progress(double(done) / double(steps));
  };
  LFCAM_TRY(readSamples(path, session, opened.samples, lightField.samples().data(), viewDone));
  if (opened.weight) {
    lightField.enableWeight();
    LFCAM_TRY(readSamples(path, session, *opened.weight, lightField.weights().data(), viewDone));
  }
  return lightField;
}

// What the reader will ask of libhdf5, asked first in a throwaway process (survives_in_child.hpp).
// For a file laid out as lfcam writes it, that is everything: the metadata, and the raw bytes of
// every chunk, which libhdf5 only copies; their decompression is lfcam's own (zlib, bounded to the
// chunk's size) and happens once, in the parent. For other files, libhdf5 runs the filters
// itself, so the child also reads every sample when they are small enough to read twice without
// notice; larger ones are read once, after the child has walked their metadata and chunk index.
// A probe reads no samples, and its child opens the file only.
Status refuseLightFieldsThatCrashLibhdf5(const fs::path& path, bool readsSamples) {
  constexpr std::size_t kReadTwiceBytes = std::size_t(64) << 20;
  return io::refuseWhatCrashesLibhdf5(path, [&] {
    auto opened = openLightFieldFile(path);
    if (!opened || !readsSamples) return;  // a clean error is the parent's to find and report
    for (StoredSamples* stored : {&opened->samples, opened->weight ? &*opened->weight : nullptr}) {
      if (!stored) continue;
      if (stored->rawFilters) {
        for (std::size_t first = 0; first < stored->views(); first += kViewsPerBatch)
          if (!readRawChunks(path, *stored, first, std::min(stored->views(), first + kViewsPerBatch))) return;
        continue;
      }
      hsize_t chunks = 0;
      if (H5Dget_num_chunks(stored->dataset->get(), H5S_ALL, &chunks) < 0) continue;
      for (hsize_t i = 0; i < std::min<hsize_t>(chunks, 4096); ++i) {
        hsize_t offset[5] = {}, size = 0;
        unsigned filterMask = 0;
        haddr_t address = 0;
        H5Dget_chunk_info(stored->dataset->get(), H5S_ALL, i, offset, &filterMask, &address, &size);
      }
      if (stored->views() * stored->viewValues() * sizeof(float) <= kReadTwiceBytes) {
        std::vector<float> scratch(stored->views() * stored->viewValues());
        (void)readViewsThroughLibhdf5(path, *stored, 0, stored->views(), scratch.data());
      }
    }
  });
}

}  // namespace

Result<LightFieldInfo> probeHdf5(const fs::path& path) {
  Hdf5Session session;
  LFCAM_TRY(refuseLightFieldsThatCrashLibhdf5(path, false));
  LFCAM_ASSIGN_OR_RETURN(auto opened, openLightFieldFile(path));
  return opened.info;
}

Result<LightField> readHdf5(const fs::path& path, const ProgressCallback& progress) {
  Hdf5Session session;
  LFCAM_TRY(refuseLightFieldsThatCrashLibhdf5(path, true));
  LFCAM_ASSIGN_OR_RETURN(auto opened, openLightFieldFile(path));
  return readOpened(path, session, opened, progress);
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
  LFCAM_TRY(writeSamples(path, session, handle.get(), "lightfield", {nv, nu, hsize_t(shape.channels), nt, ns},
                         lightField.samples(), kColorEncodings, viewDone));
  if (lightField.hasWeight())
    LFCAM_TRY(writeSamples(path, session, handle.get(), "weight", {nv, nu, nt, ns}, lightField.weights(),
                           kWeightEncodings, viewDone));
  if (!handle.close()) return hdf5Error(ErrorCode::Io, path, "cannot write");
  return {};
}

}  // namespace lfcam::io
