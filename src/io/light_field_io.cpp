// Light-field inputs and outputs: which kind a path is, and the dispatch to each kind's reader
// and writer (hdf5_light_field, view_folder, lenslet_image).
#include "lfcam/io/light_field_io.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>

#include "core/atomic_file.hpp"
#include "io/hdf5_light_field.hpp"
#include "io/hdf5_support.hpp"
#include "io/io_support.hpp"
#include "io/lenslet_image.hpp"
#include "io/view_folder.hpp"
#include "io/view_order.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {

namespace fs = std::filesystem;
using io::fileError;

namespace {

// What a path holds, with the folder listing when it is a folder (so it is listed once).
struct Source {
  LightFieldFormat format = LightFieldFormat::Hdf5;
  std::optional<io::ViewGrid> grid;
};

Result<Source> identify(const fs::path& path, const LightFieldReadOptions& options = {}) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) return fileError(ErrorCode::Io, path, "no such file or folder");
  if (fs::is_directory(status)) {
    const bool decide = options.viewNumberOrder == ViewNumberOrder::Auto;
    auto grid = io::findViewGrid(path, decide ? ViewNumberOrder::RowFirst : options.viewNumberOrder);
    LFCAM_TRY(grid);
    if (decide && grid->format == LightFieldFormat::RowColumnFolder) {
      LFCAM_ASSIGN_OR_RETURN(auto order, io::detectViewNumberOrder(*grid));
      if (order == ViewNumberOrder::ColumnFirst) {
        grid = io::findViewGrid(path, ViewNumberOrder::ColumnFirst);
        LFCAM_TRY(grid);
      }
    }
    const LightFieldFormat format = grid->format;
    return Source{format, std::move(*grid)};
  }
  if (!fs::is_regular_file(status)) return fileError(ErrorCode::Usage, path, "not a regular file or folder");
  if (io::startsLikeHdf5(path)) return Source{LightFieldFormat::Hdf5, std::nullopt};
  if (looksLikeImageFile(path)) return Source{LightFieldFormat::LensletImage, std::nullopt};
  return fileError(ErrorCode::Format, path, "not a light field: neither an HDF5 file, an image, nor a folder of views");
}

bool isImageExtension(const std::string& extension) {
  for (const char* known : {".png", ".tif", ".tiff", ".exr", ".jpg", ".jpeg", ".pfm"})
    if (extension == known) return true;
  return false;
}

LightFieldFormat formatFromName(const fs::path& path) {
  const std::string extension = io::lowerExtension(path);
  if (extension == ".h5" || extension == ".hdf5") return LightFieldFormat::Hdf5;
  if (isImageExtension(extension)) return LightFieldFormat::LensletImage;
  return LightFieldFormat::HciFolder;
}

Status writeFolder(const fs::path& path, const LightField& lightField, LightFieldFormat format,
                   const LightFieldWriteOptions& options, const ProgressCallback& progress) {
  if (!io::isViewFileExtension(options.viewExtension))
    return fileError(ErrorCode::Usage, path,
                     "views are written as .png, .tif, .tiff or .exr, not '" + options.viewExtension + "'");
  const fs::path someView = path / ("view" + options.viewExtension);
  if (Status usable = checkImageWriteOptions(someView, {.sampleType = options.sampleType}); !usable)
    return io::renamedInMessage(usable.error(), someView, path);
  std::error_code ec;
  if (fs::is_directory(path, ec))
    if (auto other = io::otherLayoutIn(path, format))
      return fileError(
          ErrorCode::Usage, path,
          "already holds views of the other layout (" + *other + "); write to a new folder or remove them");
  std::vector<std::string> written;
  LFCAM_TRY(writeFolderAtomically(path, [&](const fs::path& temporary) -> Status {
    LFCAM_ASSIGN_OR_RETURN(auto names, io::writeViewFolder(temporary, lightField, format, options, progress, path));
    written = std::move(names);
    return {};
  }));
  // Views left from an earlier, larger grid would make the folder read as something else.
  io::removeStaleViews(path, format, written);
  return {};
}

Status checkFiniteValues(std::span<const float> values, std::string_view where, std::string_view what) {
  bool finite = true;
  for (float value : values) finite &= std::isfinite(value);  // no early exit: vectorises
  if (finite) return {};
  const auto bad = std::find_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); });
  return makeError(ErrorCode::Format,
                   std::string(where) + ": " + std::string(what) + " " + std::to_string(bad - values.begin()) + " is " +
                       (std::isnan(*bad) ? "NaN" : "infinite") + "; only finite values are accepted");
}

}  // namespace

const char* formatName(LightFieldFormat format) {
  switch (format) {
    case LightFieldFormat::Hdf5: return "lf.h5";
    case LightFieldFormat::HciFolder: return "hci-folder";
    case LightFieldFormat::RowColumnFolder: return "rowcol-folder";
    case LightFieldFormat::LensletImage: return "lenslet-image";
  }
  return "unknown";
}

Result<LightFieldFormat> detectLightFieldFormat(const fs::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto source, identify(path));
  return source.format;
}

Result<LightFieldInfo> probeLightField(const fs::path& path, const LightFieldReadOptions& options) {
  LFCAM_ASSIGN_OR_RETURN(auto source, identify(path, options));
  switch (source.format) {
    case LightFieldFormat::Hdf5: return io::probeHdf5(path);
    case LightFieldFormat::LensletImage: return io::probeLensletImage(path, options);
    case LightFieldFormat::HciFolder:
    case LightFieldFormat::RowColumnFolder: return io::probeViewGrid(*source.grid);
  }
  return fileError(ErrorCode::Unsupported, path, "unknown light-field format");
}

Result<LightField> readLightField(const fs::path& path, const LightFieldReadOptions& options,
                                  const ProgressCallback& progress) {
  LFCAM_ASSIGN_OR_RETURN(auto source, identify(path, options));
  if (progress) progress(0.0);
  auto lightField = [&]() -> Result<LightField> {
    switch (source.format) {
      case LightFieldFormat::Hdf5: return io::readHdf5(path, progress);
      case LightFieldFormat::LensletImage: return io::readLensletImage(path, options, progress);
      case LightFieldFormat::HciFolder:
      case LightFieldFormat::RowColumnFolder: return io::readViewGrid(*source.grid, progress);
    }
    return fileError(ErrorCode::Unsupported, path, "unknown light-field format");
  }();
  if (!lightField) return lightField;
  LFCAM_TRY(checkFinite(*lightField, path.string()));
  return lightField;
}

Status writeLightField(const fs::path& path, const LightField& lightField, const LightFieldWriteOptions& options,
                       const ProgressCallback& progress) {
  if (lightField.empty()) return fileError(ErrorCode::Usage, path, "nothing to write: the light field is empty");
  const LightFieldFormat format = options.format.value_or(formatFromName(path));
  if (progress) progress(0.0);
  switch (format) {
    case LightFieldFormat::Hdf5:
      return writeFileAtomically(
          path, [&](const fs::path& temporary) { return io::writeHdf5(temporary, lightField, progress, path); });
    case LightFieldFormat::LensletImage: return io::writeLensletImage(path, lightField, options.sampleType, progress);
    case LightFieldFormat::HciFolder:
    case LightFieldFormat::RowColumnFolder: return writeFolder(path, lightField, format, options, progress);
  }
  return fileError(ErrorCode::Usage, path, "unknown light-field format");
}

Status checkFinite(const LightField& lightField, std::string_view where) {
  LFCAM_TRY(checkFiniteValues(lightField.samples(), where, "sample"));
  return checkFiniteValues(lightField.weights(), where, "weight");
}

}  // namespace lfcam
