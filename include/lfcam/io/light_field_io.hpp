// Light-field files and folders, each read and written:
//   Hdf5            native `.lf.h5` (layout in docs/formats.md): float32 samples, weight, metadata
//   HciFolder       `input_CamNNN.png`, row-major views, plus `parameters.cfg` (HCI benchmark)
//   RowColumnFolder `*_RR_CC.png`, RR the view's row and CC its column, 1-based (some exporters
//                   put the column first: see ViewNumberOrder)
//   LensletImage    one image of (ns * nu) x (nt * nv) pixels: pixel (s * nu + u, t * nv + v) holds
//                   L(u, v, s, t), the "macro-pixel" image of microscopes and other toolboxes
// Reading recognises the kind by content (HDF5 signature, folder listing, image signature), not
// by name. Writing picks it from the name: `.h5` -> Hdf5; an image extension -> LensletImage;
// otherwise a folder (HCI layout unless options say RowColumn).
// Folder and lenslet outputs hold what their image type holds (8-bit sRGB PNG by default; 16-bit
// and float files linear radiance, image_io.hpp) and no weight; only Hdf5 keeps everything.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {

enum class LightFieldFormat { Hdf5, HciFolder, RowColumnFolder, LensletImage };
const char* formatName(LightFieldFormat format);

// How the two numbers in the names of a row/column folder, NAME_AA_BB.png, are read.
enum class ViewNumberOrder {
  Auto,         // decided by the parallax between views (RowFirst when it cannot tell)
  RowFirst,     // AA = row (v + 1), BB = column (u + 1): the usual order, and what lfcam writes
  ColumnFirst,  // AA = column (u + 1), BB = row (v + 1): e.g. the LF Toolbox export of the Lytro
                // set lytro-f01-flower (IMG_0001_NNN_SS_TT.png, SS the horizontal position)
};

struct LightFieldReadOptions {
  // Views across (and down) a lenslet image that carries no lfcam description. When absent
  // too, the reader estimates the period of the macro-pixels from the image itself.
  std::optional<int> lensletViews;
  ViewNumberOrder viewNumberOrder = ViewNumberOrder::Auto;  // row/column folders only
};

struct LightFieldWriteOptions {
  std::optional<LightFieldFormat> format;  // overrides the choice by name
  // Folders and lenslet images: the image files' sample type (default: their format's natural
  // one, image_io.hpp); a type the format cannot hold is a Usage error. Ignored by Hdf5.
  std::optional<SampleType> sampleType;
  std::string viewExtension = ".png";  // folders: the views' .png, .tif, .tiff or .exr
};

// What a light-field input is, without reading its samples where the format allows.
struct LightFieldInfo {
  LightFieldFormat format = LightFieldFormat::Hdf5;
  LightFieldShape shape;
  bool hasWeight = false;
  LightFieldMetadata metadata;
};

Result<LightFieldFormat> detectLightFieldFormat(const std::filesystem::path& path);
Result<LightFieldInfo> probeLightField(const std::filesystem::path& path, const LightFieldReadOptions& options = {});
Result<LightField> readLightField(const std::filesystem::path& path, const LightFieldReadOptions& options = {},
                                  const ProgressCallback& progress = {});
Status writeLightField(const std::filesystem::path& path, const LightField& lightField,
                       const LightFieldWriteOptions& options = {}, const ProgressCallback& progress = {});

// Ok when every sample and weight is finite, else a Format error "<where>: sample 12 is NaN; only
// finite values are accepted" (or a weight, or infinite): samples are radiance and weights trust, and
// a non-finite one would spread through every photograph made from it. readLightField checks what it
// read, the Python package the arrays it is given.
Status checkFinite(const LightField& lightField, std::string_view where);

}  // namespace lfcam
