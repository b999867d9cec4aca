// The HCI 4D light field benchmark's layout: input_CamNNN.png numbered row-major from the top-left
// view (NNN = v * nu + u), and parameters.cfg, an INI file of which lfcam uses num_cams_x,
// num_cams_y (the grid) and disp_min, disp_max (the scene's disparity range).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include "io/io_support.hpp"
#include "io/view_folder.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = "input_Cam";

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

// key -> value of an INI file, keys lower case, sections ignored (HCI keys are unique).
Result<std::map<std::string, std::string>> readConfig(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return fileError(ErrorCode::Io, path, "cannot open");
  std::map<std::string, std::string> values;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = trim(line);
    if (line.empty() || line[0] == '#' || line[0] == ';' || line[0] == '[') continue;
    const auto separator = line.find_first_of("=:");
    if (separator == std::string::npos)
      return fileError(ErrorCode::Format, path, "line " + std::to_string(number) + ": expected 'key = value'");
    std::string key = trim(line.substr(0, separator));
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    values[key] = trim(line.substr(separator + 1));
  }
  return values;
}

Result<std::optional<double>> numberFrom(const fs::path& path, const std::map<std::string, std::string>& config,
                                         const std::string& key) {
  const auto found = config.find(key);
  if (found == config.end()) return std::optional<double>();
  const std::string& text = found->second;
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return fileError(ErrorCode::Format, path, key + " = '" + text + "' is not a number");
  return std::optional<double>(value);
}

std::string shortest(double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

}  // namespace

std::optional<int> hciViewIndex(const std::string& filename) {
  if (filename.size() <= kPrefix.size() + 4 || filename.compare(0, kPrefix.size(), kPrefix) != 0) return std::nullopt;
  if (lowerExtension(filename) != ".png") return std::nullopt;
  const std::string digits = filename.substr(kPrefix.size(), filename.size() - kPrefix.size() - 4);
  if (digits.empty() || digits.size() > 6 || !std::all_of(digits.begin(), digits.end(), [](unsigned char ch) { return std::isdigit(ch); })) return std::nullopt;
  return std::stoi(digits);
}

std::string hciViewName(int index, int views) {
  std::string digits = std::to_string(index);
  const std::size_t width = std::max<std::size_t>(3, std::to_string(std::max(views - 1, 0)).size());
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return std::string(kPrefix) + digits + ".png";
}

Result<ViewGrid> placeHciViews(const fs::path& folder, const fs::path& configFolder,
                               std::vector<std::pair<int, fs::path>> files) {
  std::sort(files.begin(), files.end());
  for (std::size_t i = 1; i < files.size(); ++i)
    if (files[i].first == files[i - 1].first)
      return fileError(ErrorCode::Format, files[i].second,
                       "view " + std::to_string(files[i].first) + " is also " + files[i - 1].second.filename().string());

  ViewGrid grid;
  grid.format = LightFieldFormat::HciFolder;
  grid.folder = folder;
  grid.metadata.source = folder.string();

  // The grid from parameters.cfg (beside the views, or beside their 'views' folder).
  std::error_code ec;
  bool gridFromConfig = false;
  fs::path configPath = folder / "parameters.cfg";
  if (!fs::is_regular_file(configPath, ec)) configPath = configFolder / "parameters.cfg";
  if (fs::is_regular_file(configPath, ec)) {
    auto config = readConfig(configPath);
    if (!config) return config.error();
    auto columns = numberFrom(configPath, *config, "num_cams_x");
    if (!columns) return columns.error();
    auto rows = numberFrom(configPath, *config, "num_cams_y");
    if (!rows) return rows.error();
    const auto validCount = [](const std::optional<double>& n) {
      return n && *n >= 1 && *n <= 100000 && *n == std::floor(*n);
    };
    if (*columns || *rows) {
      if (!validCount(*columns) || !validCount(*rows))
        return fileError(ErrorCode::Format, configPath, "num_cams_x and num_cams_y must both be positive integers");
      grid.nu = int(**columns);
      grid.nv = int(**rows);
      gridFromConfig = true;
    }
    for (auto [key, target] : {std::pair{"disp_min", &grid.metadata.disparityMin},
                               std::pair{"disp_max", &grid.metadata.disparityMax}}) {
      auto value = numberFrom(configPath, *config, key);
      if (!value) return value.error();
      *target = *value;
    }
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

  const int views = grid.nu * grid.nv;
  const std::string gridText = std::to_string(grid.nu) + "x" + std::to_string(grid.nv);
  grid.files.resize(std::size_t(views));
  for (const auto& [index, path] : files) {
    if (index >= views)
      return fileError(ErrorCode::Format, path, "view " + std::to_string(index) + " lies outside the " + gridText +
                                                    " grid (from " + (gridFromConfig ? "parameters.cfg" : "the file count") + ")");
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
  std::ostringstream text;
  text << "# Written by lfcam, in the layout of the HCI 4D light field benchmark.\n"
       << "[intrinsics]\n"
       << "image_resolution_x_px = " << lightField.ns() << "\n"
       << "image_resolution_y_px = " << lightField.nt() << "\n\n"
       << "[extrinsics]\n"
       << "num_cams_x = " << lightField.nu() << "\n"
       << "num_cams_y = " << lightField.nv() << "\n";
  const LightFieldMetadata& metadata = lightField.metadata;
  if (metadata.disparityMin || metadata.disparityMax) {
    text << "\n[meta]\n";
    if (metadata.disparityMin) text << "disp_min = " << shortest(*metadata.disparityMin) << "\n";
    if (metadata.disparityMax) text << "disp_max = " << shortest(*metadata.disparityMax) << "\n";
  }
  return text.str();
}

}  // namespace lfcam::io
