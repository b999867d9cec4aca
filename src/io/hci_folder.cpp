// The HCI 4D light field benchmark's layout: input_CamNNN.png numbered row-major from the top-left
// view (NNN = v * nu + u), and parameters.cfg (hci_parameters.hpp), of which lfcam uses num_cams_x,
// num_cams_y (the grid), disp_min, disp_max (the scene's disparity range) and the virtual camera
// (optics, for metric distances).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <system_error>

#include "io/hci_parameters.hpp"
#include "io/io_support.hpp"
#include "io/view_folder.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = "input_Cam";

}  // namespace

std::optional<int> hciViewIndex(const std::string& filename) {
  const std::string extension = lowerExtension(filename);
  if (filename.size() <= kPrefix.size() + extension.size() || filename.compare(0, kPrefix.size(), kPrefix) != 0)
    return std::nullopt;
  if (!isViewFileExtension(extension)) return std::nullopt;
  const std::string digits = filename.substr(kPrefix.size(), filename.size() - kPrefix.size() - extension.size());
  if (digits.empty() || digits.size() > 6 ||
      !std::all_of(digits.begin(), digits.end(), [](unsigned char ch) { return std::isdigit(ch); }))
    return std::nullopt;
  return std::stoi(digits);
}

std::string hciViewName(int index, int views, const std::string& extension) {
  std::string digits = std::to_string(index);
  const std::size_t width = std::max<std::size_t>(3, std::to_string(std::max(views - 1, 0)).size());
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return std::string(kPrefix) + digits + extension;
}

Result<ViewGrid> placeHciViews(const fs::path& folder, const fs::path& configFolder,
                               std::vector<std::pair<int, fs::path>> files) {
  std::sort(files.begin(), files.end());
  for (std::size_t i = 1; i < files.size(); ++i)
    if (files[i].first == files[i - 1].first)
      return fileError(
          ErrorCode::Format, files[i].second,
          "view " + std::to_string(files[i].first) + " is also " + files[i - 1].second.filename().string());

  ViewGrid grid;
  grid.format = LightFieldFormat::HciFolder;
  grid.folder = folder;
  grid.metadata.source = folder.string();

  // The grid from parameters.cfg (beside the views, or beside their 'views' folder).
  std::error_code ec;
  bool gridFromConfig = false;
  fs::path configPath = folder / "parameters.cfg";
  if (!fs::exists(configPath, ec)) configPath = configFolder / "parameters.cfg";
  if (fs::exists(configPath, ec)) {  // a folder of that name is refused by the reader
    LFCAM_ASSIGN_OR_RETURN(auto parameters, readHciParameters(configPath));
    if (parameters.camerasX || parameters.camerasY) {
      if (!parameters.camerasX || !parameters.camerasY)
        return fileError(ErrorCode::Format, configPath, "num_cams_x and num_cams_y must both be positive integers");
      grid.nu = *parameters.camerasX;
      grid.nv = *parameters.camerasY;
      gridFromConfig = true;
    }
    grid.metadata.disparityMin = parameters.disparityMin;
    grid.metadata.disparityMax = parameters.disparityMax;
    // The virtual camera, for metric distances (hci_parameters.hpp).
    if (auto optics = hciOptics(parameters)) grid.metadata.optics = optics;
  }
  if (grid.nu == 0) {
    // No parameters.cfg: a square grid.
    const int side = int(std::lround(std::sqrt(double(files.size()))));
    if (std::size_t(side) * std::size_t(side) != files.size())
      return fileError(ErrorCode::Format, folder,
                       std::to_string(files.size()) +
                           " HCI views do not make a square grid; add parameters.cfg with num_cams_x and num_cams_y");
    grid.nu = grid.nv = side;
  }

  const std::string gridText = std::to_string(grid.nu) + "x" + std::to_string(grid.nv);
  // More views than files: a view is missing. Said before allocating, and without int overflow:
  // parameters.cfg may ask for up to 100000 x 100000 views.
  const std::uint64_t viewCount = std::uint64_t(grid.nu) * std::uint64_t(grid.nv);
  if (viewCount > files.size()) {
    int missing = 0;  // the first gap in the sorted indices
    for (const auto& file : files) {
      if (file.first != missing) break;
      ++missing;
    }
    return fileError(ErrorCode::Format, folder / hciViewName(missing, int(std::min<std::uint64_t>(viewCount, INT_MAX))),
                     "missing view: a " + gridText + " grid needs " + std::to_string(viewCount) + " views, found " +
                         std::to_string(files.size()));
  }
  const int views = int(viewCount);
  grid.files.resize(std::size_t(views));
  for (const auto& [index, path] : files) {
    if (index >= views)
      return fileError(ErrorCode::Format, path,
                       "view " + std::to_string(index) + " lies outside the " + gridText + " grid (from " +
                           (gridFromConfig ? "parameters.cfg" : "the file count") + ")");
    grid.files[std::size_t(index)] = path;
  }
  for (int index = 0; index < views; ++index)
    if (grid.files[std::size_t(index)].empty())
      return fileError(ErrorCode::Format, folder / hciViewName(index, views),
                       "missing view: a " + gridText + " grid needs " + hciViewName(0, views) + " to " +
                           hciViewName(views - 1, views));
  return grid;
}

std::string hciParameters(const LightField& lightField) {
  const LightFieldMetadata& metadata = lightField.metadata;
  // The virtual camera, inverting hciOptics, when the optics focus at a finite distance.
  std::string intrinsics, extrinsics;
  if (const auto& optics = metadata.optics; optics && optics->focalLengthMm && optics->lensToMicrolensMm > 0) {
    const double inverseFocus = 1.0 / *optics->focalLengthMm - 1.0 / optics->lensToMicrolensMm;
    if (inverseFocus > 0 && optics->lensStepMm > 0 && optics->spatialStepMm > 0) {
      intrinsics = "focal_length_mm = " + shortestNumber(optics->lensToMicrolensMm) + "\nsensor_size_mm = " +
                   shortestNumber(optics->spatialStepMm * std::max(lightField.ns(), lightField.nt())) + "\n";
      extrinsics = "baseline_mm = " + shortestNumber(optics->lensStepMm) +
                   "\nfocus_distance_m = " + shortestNumber(1.0 / inverseFocus / 1000.0) + "\n";
    }
  }
  std::ostringstream text;
  text << "# Written by lfcam, in the layout of the HCI 4D light field benchmark.\n"
       << "[intrinsics]\n"
       << "image_resolution_x_px = " << lightField.ns() << "\n"
       << "image_resolution_y_px = " << lightField.nt() << "\n"
       << intrinsics << "\n"
       << "[extrinsics]\n"
       << "num_cams_x = " << lightField.nu() << "\n"
       << "num_cams_y = " << lightField.nv() << "\n"
       << extrinsics;
  if (metadata.disparityMin || metadata.disparityMax) {
    text << "\n[meta]\n";
    if (metadata.disparityMin) text << "disp_min = " << shortestNumber(*metadata.disparityMin) << "\n";
    if (metadata.disparityMax) text << "disp_max = " << shortestNumber(*metadata.disparityMax) << "\n";
  }
  return text.str();
}

}  // namespace lfcam::io
