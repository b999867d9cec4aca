#include "io/view_folder.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>

#include "core/parallel.hpp"
#include "io/io_support.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

struct Listing {
  std::vector<std::pair<int, fs::path>> hci;
  std::vector<std::pair<RowColumn, fs::path>> rowColumn;
};

Result<Listing> listViews(const fs::path& folder, ViewNumberOrder order = ViewNumberOrder::RowFirst) {
  Listing listing;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string name = it->path().filename().string();
    if (auto index = hciViewIndex(name))
      listing.hci.emplace_back(*index, it->path());
    else if (auto place = rowColumnOf(name, order))
      listing.rowColumn.emplace_back(*place, it->path());
  }
  if (ec) return fileError(ErrorCode::Io, folder, "cannot list folder: " + ec.message());
  return listing;
}

// All views share the first one's size and channel count.
Status checkViewMatches(const ViewGrid& grid, std::size_t index, int width, int height, int channels,
                        const LightFieldShape& shape) {
  const fs::path& file = grid.files[index];
  const std::string firstName = grid.files.front().filename().string();
  if (width != shape.ns || height != shape.nt)
    return fileError(ErrorCode::Format, file,
                     std::to_string(width) + "x" + std::to_string(height) + " pixels, but " + firstName + " has " +
                         std::to_string(shape.ns) + "x" + std::to_string(shape.nt));
  if (channels != shape.channels)
    return fileError(
        ErrorCode::Format, file,
        std::to_string(channels) + " channels, but " + firstName + " has " + std::to_string(shape.channels));
  return {};
}

// The shape from the first view; with checkAll, every view's header must agree with it (cheap:
// no pixels are decoded, but a damaged or mismatched view is found without reading samples).
Result<LightFieldInfo> shapeFromHeaders(const ViewGrid& grid, bool checkAll) {
  LFCAM_ASSIGN_OR_RETURN(auto first, readImageHeader(grid.files.front()));
  LightFieldInfo info;
  info.format = grid.format;
  info.shape = {.nu = grid.nu, .nv = grid.nv, .ns = first.width, .nt = first.height, .channels = first.channels};
  info.metadata = grid.metadata;
  for (std::size_t i = 1; checkAll && i < grid.files.size(); ++i) {
    LFCAM_ASSIGN_OR_RETURN(auto header, readImageHeader(grid.files[i]));
    LFCAM_TRY(checkViewMatches(grid, i, header.width, header.height, header.channels, info.shape));
  }
  return info;
}

// Runs work(i) for i in [0, count) a batch at a time, in parallel within a batch, and reports
// progress between batches (from the calling thread, as ProgressCallback promises). Returns the
// first error in view order.
Status forEachViewInBatches(std::size_t count, const std::function<Status(std::size_t)>& work,
                            const ProgressCallback& progress) {
  constexpr std::size_t kBatch = 8;
  std::vector<Status> results(count);
  for (std::size_t first = 0; first < count; first += kBatch) {
    const std::size_t last = std::min(count, first + kBatch);
    parallelFor(first, last, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) results[i] = work(i);
    });
    for (std::size_t i = first; i < last; ++i)
      if (!results[i]) return results[i];
    if (progress) progress(double(last) / double(count));
  }
  return {};
}

}  // namespace

Result<ViewGrid> findViewGrid(const fs::path& path, ViewNumberOrder order) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return fileError(ErrorCode::Io, path, "no such file or folder");
  // The views in the folder itself, else in its 'views' subfolder (as exported by some toolboxes).
  for (const fs::path& folder : {path, path / "views"}) {
    if (!fs::is_directory(folder, ec)) continue;
    LFCAM_ASSIGN_OR_RETURN(auto listing, listViews(folder, order));
    if (!listing.hci.empty() && !listing.rowColumn.empty())
      return fileError(ErrorCode::Format, folder,
                       "holds both HCI views (input_CamNNN.png) and row/column views (*_RR_CC.png); keep one layout");
    if (!listing.hci.empty()) return placeHciViews(folder, path, std::move(listing.hci));
    if (!listing.rowColumn.empty()) return placeRowColumnViews(folder, std::move(listing.rowColumn), order);
  }
  return fileError(ErrorCode::Format, path,
                   "no light-field views found (expected input_CamNNN.png or NAME_RR_CC.png files, here or in views/)");
}

Result<LightFieldInfo> probeViewGrid(const ViewGrid& grid) { return shapeFromHeaders(grid, true); }

Result<LightField> readViewGrid(const ViewGrid& grid, const ProgressCallback& progress) {
  // Every view is checked as it is read.
  LFCAM_ASSIGN_OR_RETURN(auto info, shapeFromHeaders(grid, false));
  const LightFieldShape& shape = info.shape;
  LFCAM_TRY(
      checkSampleCount(grid.folder, {std::uint64_t(shape.views()), shape.viewPixels(), std::uint64_t(shape.channels)}));
  LightField lightField(shape);
  lightField.metadata = grid.metadata;
  LFCAM_TRY(forEachViewInBatches(
      shape.views(),
      [&](std::size_t index) -> Status {
        const fs::path& file = grid.files[index];
        LFCAM_ASSIGN_OR_RETURN(auto view, readImage(file));
        LFCAM_TRY(checkViewMatches(grid, index, view.width(), view.height(), view.channels(), shape));
        lightField.setSubApertureImage(int(index % std::size_t(grid.nu)), int(index / std::size_t(grid.nu)), view);
        return {};
      },
      progress));
  return lightField;
}

bool isViewFileExtension(const std::string& extension) {
  return extension == ".png" || extension == ".tif" || extension == ".tiff" || extension == ".exr";
}

Result<std::vector<std::string>> writeViewFolder(const fs::path& folder, const LightField& lightField,
                                                 LightFieldFormat format, const LightFieldWriteOptions& options,
                                                 const ProgressCallback& progress, const fs::path& reportAs) {
  const ImageWriteOptions imageOptions{.sampleType = options.sampleType};
  const std::string& extension = options.viewExtension;
  const int nu = lightField.nu(), nv = lightField.nv();
  const std::size_t views = lightField.shape().views();
  std::vector<std::string> written(views);
  for (std::size_t index = 0; index < views; ++index) {
    const int u = int(index % std::size_t(nu)), v = int(index / std::size_t(nu));
    written[index] = format == LightFieldFormat::HciFolder ? hciViewName(int(index), int(views), extension)
                                                           : rowColumnViewName(v + 1, u + 1, nv, nu, extension);
  }
  LFCAM_TRY(forEachViewInBatches(
      views,
      [&](std::size_t index) -> Status {
        const int u = int(index % std::size_t(nu)), v = int(index / std::size_t(nu));
        const fs::path file = folder / written[index];
        Status status = writeImage(file, lightField.subApertureImage(u, v), imageOptions);
        // Name the destination the caller gave, not the hidden temporary folder.
        if (!status) return renamedInMessage(status.error(), file, reportAs / written[index]);
        return {};
      },
      progress));
  if (format == LightFieldFormat::HciFolder) {
    std::ofstream config(folder / "parameters.cfg");
    config << hciParameters(lightField);
    config.close();
    if (!config) return fileError(ErrorCode::Io, reportAs / "parameters.cfg", "cannot write");
    written.push_back("parameters.cfg");
  }
  return written;
}

std::optional<std::string> otherLayoutIn(const fs::path& folder, LightFieldFormat format) {
  auto listing = listViews(folder);
  if (!listing) return std::nullopt;
  if (format == LightFieldFormat::HciFolder && !listing->rowColumn.empty())
    return listing->rowColumn.front().second.filename().string();
  if (format == LightFieldFormat::RowColumnFolder && !listing->hci.empty())
    return listing->hci.front().second.filename().string();
  return std::nullopt;
}

void removeStaleViews(const fs::path& folder, LightFieldFormat format, const std::vector<std::string>& written) {
  auto listing = listViews(folder);
  if (!listing) return;
  std::vector<fs::path> candidates;
  if (format == LightFieldFormat::HciFolder)
    for (const auto& [index, path] : listing->hci) candidates.push_back(path);
  else
    for (const auto& [place, path] : listing->rowColumn) candidates.push_back(path);
  std::error_code ec;
  for (const fs::path& path : candidates)
    if (std::find(written.begin(), written.end(), path.filename().string()) == written.end()) fs::remove(path, ec);
}

}  // namespace lfcam::io
