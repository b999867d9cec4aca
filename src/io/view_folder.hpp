// Folders of sub-aperture views, one image file per view (u, v), in two layouts:
//   HCI         input_CamNNN.png, NNN = v * nu + u, plus parameters.cfg (hci_folder.cpp)
//   row/column  PREFIX_RR_CC.png, RR = v + 1 and CC = u + 1 (row_column_folder.cpp)
// The views may lie in the folder itself or in its 'views' subfolder, and be PNG, TIFF or OpenEXR
// files (16-bit and float views keep what 8-bit PNGs round away).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam::io {

// A folder's views placed on their grid, before any pixel is read.
struct ViewGrid {
  LightFieldFormat format = LightFieldFormat::HciFolder;
  std::filesystem::path folder;  // where the view files are
  int nu = 0, nv = 0;
  std::vector<std::filesystem::path> files;  // view (u, v) at v * nu + u
  LightFieldMetadata metadata;
};

// Lists `path` (or path/views) and places its views; errors name the missing or extra file.
Result<ViewGrid> findViewGrid(const std::filesystem::path& path, ViewNumberOrder order = ViewNumberOrder::RowFirst);
Result<LightFieldInfo> probeViewGrid(const ViewGrid& grid);
Result<LightField> readViewGrid(const ViewGrid& grid, const ProgressCallback& progress);

// The extensions a view file may have (lower case, with the dot): .png, .tif, .tiff, .exr.
bool isViewFileExtension(const std::string& extension);

// Writes the views of `lightField` into `folder` (already created), named by the layout with the
// options' view extension, in their sample type (image_io.hpp). Returns the names written.
Result<std::vector<std::string>> writeViewFolder(const std::filesystem::path& folder, const LightField& lightField,
                                                 LightFieldFormat format, const LightFieldWriteOptions& options,
                                                 const ProgressCallback& progress,
                                                 const std::filesystem::path& reportAs);
// The views of the other layout already in `folder`, which would make it ambiguous.
std::optional<std::string> otherLayoutIn(const std::filesystem::path& folder, LightFieldFormat format);
// Removes views of `format` in `folder` that are not among `written` (left by a larger grid).
void removeStaleViews(const std::filesystem::path& folder, LightFieldFormat format,
                      const std::vector<std::string>& written);

// ---- per layout ----

// input_CamNNN.png (or another view extension) -> NNN.
std::optional<int> hciViewIndex(const std::string& filename);
std::string hciViewName(int index, int views, const std::string& extension = ".png");
// Places HCI files (index, path) using parameters.cfg in `folder` or `configFolder`.
Result<ViewGrid> placeHciViews(const std::filesystem::path& folder, const std::filesystem::path& configFolder,
                               std::vector<std::pair<int, std::filesystem::path>> files);
// parameters.cfg for a light field: the keys placeHciViews reads.
std::string hciParameters(const LightField& lightField);

struct RowColumn {
  int row = 0, column = 0;  // 1-based
};
// ANYTHING_AA_BB.png (or another view extension) -> (AA, BB) as (row, column), or (BB, AA) when
// the order is ColumnFirst.
std::optional<RowColumn> rowColumnOf(const std::string& filename, ViewNumberOrder order = ViewNumberOrder::RowFirst);
std::string rowColumnViewName(int row, int column, int rows, int columns, const std::string& extension = ".png");
Result<ViewGrid> placeRowColumnViews(const std::filesystem::path& folder,
                                     std::vector<std::pair<RowColumn, std::filesystem::path>> files,
                                     ViewNumberOrder order);

}  // namespace lfcam::io
