#include "io/lenslet_image.hpp"

#include <climits>
#include <optional>
#include <sstream>
#include <string>

#include "io/io_support.hpp"
#include "io/macro_pixel_period.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kDescriptionTag = "lfcam lenslet";

struct ViewsPerLens {
  int nu = 0, nv = 0;
  bool given = false;  // by the caller (a wrong count is then a usage error)
};

// "16" when found, "16 or 24" when only plausible, "none" when neither.
std::string periodsOf(const MacroPixelPeriod& estimate) {
  if (estimate.period) return std::to_string(*estimate.period);
  if (estimate.plausible.empty()) return "none";
  std::string text;
  for (int period : estimate.plausible) text += (text.empty() ? "" : " or ") + std::to_string(period);
  return text;
}

std::string describe(int nu, int nv) {
  return std::string(kDescriptionTag) + " nu=" + std::to_string(nu) + " nv=" + std::to_string(nv);
}

// "lfcam lenslet nu=9 nv=9" -> (9, 9); anything else -> nothing.
std::optional<ViewsPerLens> parseDescription(const std::string& description) {
  if (description.rfind(kDescriptionTag, 0) != 0) return std::nullopt;
  std::istringstream words(description.substr(std::string(kDescriptionTag).size()));
  ViewsPerLens views;
  for (std::string word; words >> word;) {
    int* target = word.rfind("nu=", 0) == 0 ? &views.nu : word.rfind("nv=", 0) == 0 ? &views.nv : nullptr;
    if (!target) continue;
    try {
      *target = std::stoi(word.substr(3));
    } catch (...) {
      return std::nullopt;
    }
  }
  if (views.nu < 1 || views.nv < 1) return std::nullopt;
  return views;
}

// The views per lens: from the file's description, else the caller, else the image itself
// (which needs the pixels: `image` is read on demand and kept for the caller).
Result<ViewsPerLens> viewsPerLens(const fs::path& path, const LightFieldReadOptions& options,
                                  std::optional<Image>& image) {
  LFCAM_ASSIGN_OR_RETURN(auto description, readImageDescription(path));
  if (auto views = parseDescription(description)) return *views;
  if (options.lensletViews) {
    if (*options.lensletViews < 1)
      return fileError(ErrorCode::Usage, path,
                       "views per lens must be at least 1, not " + std::to_string(*options.lensletViews));
    return ViewsPerLens{*options.lensletViews, *options.lensletViews, true};
  }
  if (!image) {
    LFCAM_ASSIGN_OR_RETURN(auto read, readImage(path));
    image = std::move(read);
  }
  const MacroPixelPeriod nu = estimateMacroPixelPeriod(*image, true);
  const MacroPixelPeriod nv = estimateMacroPixelPeriod(*image, false);
  if (nu.period && nv.period) return ViewsPerLens{*nu.period, *nv.period};
  if (nu.plausible.empty() && nv.plausible.empty())
    return fileError(ErrorCode::Usage, path,
                     "no whole number of pixels repeats under each microlens; if it is a rectified lenslet "
                     "image, give the views per lens (--lenslet-views N)");
  return fileError(ErrorCode::Usage, path,
                   "unsure how many pixels repeat under each microlens (plausible across: " + periodsOf(nu) +
                       "; down: " + periodsOf(nv) +
                       "); if it is a rectified lenslet image, give the views per lens "
                       "(--lenslet-views N)");
}

Result<LightFieldShape> shapeOf(const fs::path& path, int width, int height, int channels, ViewsPerLens views) {
  if (width % views.nu != 0 || height % views.nv != 0)
    return fileError(views.given ? ErrorCode::Usage : ErrorCode::Format, path,
                     std::to_string(width) + "x" + std::to_string(height) + " pixels is not a whole number of " +
                         std::to_string(views.nu) + "x" + std::to_string(views.nv) + " macro-pixels" +
                         (views.given ? ": the views per lens given must divide both sides" : ""));
  return LightFieldShape{
      .nu = views.nu, .nv = views.nv, .ns = width / views.nu, .nt = height / views.nv, .channels = channels};
}

}  // namespace

Result<LightFieldInfo> probeLensletImage(const fs::path& path, const LightFieldReadOptions& options) {
  LFCAM_ASSIGN_OR_RETURN(auto header, readImageHeader(path));
  std::optional<Image> image;
  LFCAM_ASSIGN_OR_RETURN(auto views, viewsPerLens(path, options, image));
  LFCAM_ASSIGN_OR_RETURN(auto shape, shapeOf(path, header.width, header.height, header.channels, views));
  LightFieldInfo info;
  info.format = LightFieldFormat::LensletImage;
  info.shape = shape;
  info.metadata.source = path.string();
  return info;
}

Result<LightField> readLensletImage(const fs::path& path, const LightFieldReadOptions& options,
                                    const ProgressCallback& progress) {
  std::optional<Image> image;
  LFCAM_ASSIGN_OR_RETURN(auto views, viewsPerLens(path, options, image));
  if (!image) {
    LFCAM_ASSIGN_OR_RETURN(auto read, readImage(path));
    image = std::move(read);
  }
  LFCAM_ASSIGN_OR_RETURN(auto shape, shapeOf(path, image->width(), image->height(), image->channels(), views));

  LFCAM_TRY(checkSampleCount(path, {shape.views(), shape.viewPixels(), std::uint64_t(shape.channels)}));
  LightField lightField(shape);
  lightField.metadata.source = path.string();
  const int nu = shape.nu, nv = shape.nv;
  for (int v = 0; v < nv; ++v)
    for (int u = 0; u < nu; ++u) {
      for (int c = 0; c < shape.channels; ++c)
        for (int t = 0; t < shape.nt; ++t) {
          const float* row = image->row(t * nv + v, c);
          float* out = lightField.plane(u, v, c) + std::size_t(t) * shape.ns;
          for (int s = 0; s < shape.ns; ++s) out[s] = row[s * nu + u];
        }
      if (progress) progress(double(v * nu + u + 1) / double(shape.views()));
    }
  return lightField;
}

Status writeLensletImage(const fs::path& path, const LightField& lightField, std::optional<SampleType> sampleType,
                         const ProgressCallback& progress) {
  const LightFieldShape& shape = lightField.shape();
  const auto width = checkedProduct({std::uint64_t(shape.ns), std::uint64_t(shape.nu)});
  const auto height = checkedProduct({std::uint64_t(shape.nt), std::uint64_t(shape.nv)});
  if (!width || !height || *width > INT_MAX || *height > INT_MAX)
    return fileError(ErrorCode::Usage, path, "too large for one image");
  Image image(int(*width), int(*height), shape.channels);
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      for (int c = 0; c < shape.channels; ++c)
        for (int t = 0; t < shape.nt; ++t) {
          const float* in = lightField.plane(u, v, c) + std::size_t(t) * shape.ns;
          float* row = image.row(t * shape.nv + v, c);
          for (int s = 0; s < shape.ns; ++s) row[s * shape.nu + u] = in[s];
        }
      // Arranging is quick; the file write is the slow half.
      if (progress) progress(0.5 * double(v * shape.nu + u + 1) / double(shape.views()));
    }
  LFCAM_TRY(writeImage(path, image, {.sampleType = sampleType, .description = describe(shape.nu, shape.nv)}));
  if (progress) progress(1.0);
  return {};
}

}  // namespace lfcam::io
