// Folders of views named PREFIX_RR_CC.png (or .tif, .tiff, .exr), RR the view's row (v + 1) and CC its column (u + 1).
// Anything before the last two fields is ignored (the Lytro export in the shared data puts a
// serpentine frame counter there, IMG_0001_NNN_SS_TT.png, and numbers the column first: its
// script loops over s, "the horizontal angular coordinate", and saves LF(t, s, :, :, :)).
#include <algorithm>
#include <cctype>
#include <set>
#include <string>

#include "io/io_support.hpp"
#include "io/view_folder.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

std::optional<int> number(const std::string& digits) {
  if (digits.empty() || digits.size() > 4 ||
      !std::all_of(digits.begin(), digits.end(), [](unsigned char ch) { return std::isdigit(ch); }))
    return std::nullopt;
  return std::stoi(digits);
}

std::string padded(int value, int largest) {
  std::string digits = std::to_string(value);
  const std::size_t width = std::max<std::size_t>(2, std::to_string(largest).size());
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return digits;
}

}  // namespace

std::optional<RowColumn> rowColumnOf(const std::string& filename, ViewNumberOrder order) {
  const std::string extension = lowerExtension(filename);
  if (!isViewFileExtension(extension)) return std::nullopt;
  const std::string stem = filename.substr(0, filename.size() - extension.size());
  const auto last = stem.rfind('_');
  if (last == std::string::npos || last == 0) return std::nullopt;
  const auto before = stem.rfind('_', last - 1);
  if (before == std::string::npos || before == 0) return std::nullopt;  // a prefix is required
  const auto row = number(stem.substr(before + 1, last - before - 1));
  const auto column = number(stem.substr(last + 1));
  if (!row || !column || *row < 1 || *column < 1) return std::nullopt;
  if (order == ViewNumberOrder::ColumnFirst) return RowColumn{*column, *row};
  return RowColumn{*row, *column};
}

std::string rowColumnViewName(int row, int column, int rows, int columns, const std::string& extension) {
  return "view_" + padded(row, rows) + "_" + padded(column, columns) + extension;
}

Result<ViewGrid> placeRowColumnViews(const fs::path& folder, std::vector<std::pair<RowColumn, fs::path>> files,
                                     ViewNumberOrder order) {
  ViewGrid grid;
  grid.format = LightFieldFormat::RowColumnFolder;
  grid.folder = folder;
  grid.metadata.source = folder.string();
  for (const auto& [place, path] : files) {
    grid.nv = std::max(grid.nv, place.row);
    grid.nu = std::max(grid.nu, place.column);
  }
  const std::size_t views = std::size_t(grid.nu) * std::size_t(grid.nv);
  if (views > files.size()) {
    // Some view is missing (or a stray file claims a far row or column): name the first gap,
    // which scanning in order meets within files.size() + 1 places.
    std::set<std::pair<int, int>> present;
    for (const auto& [place, path] : files) present.emplace(place.row, place.column);
    for (int row = 1; row <= grid.nv; ++row)
      for (int column = 1; column <= grid.nu; ++column)
        if (!present.count({row, column})) {
          const std::string rowText = padded(row, grid.nv), columnText = padded(column, grid.nu);
          const std::string expected =
              order != ViewNumberOrder::ColumnFirst ? rowText + "_" + columnText : columnText + "_" + rowText;
          return fileError(ErrorCode::Format, folder,
                           "missing view at row " + std::to_string(row) + ", column " + std::to_string(column) +
                               " (no *_" + expected + files.front().second.extension().string() + ") in a " +
                               std::to_string(grid.nu) + "x" + std::to_string(grid.nv) + " grid");
        }
  }
  grid.files.resize(views);
  for (const auto& [place, path] : files) {
    fs::path& slot = grid.files[std::size_t(place.row - 1) * grid.nu + (place.column - 1)];
    if (!slot.empty())
      return fileError(ErrorCode::Format, path,
                       "same view (row " + std::to_string(place.row) + ", column " + std::to_string(place.column) +
                           ") as " + slot.filename().string());
    slot = path;
  }
  return grid;
}

}  // namespace lfcam::io
