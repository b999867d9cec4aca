// decodeLightField: the decoder's pipeline (decode.hpp); the kernels are in the other files.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "decode/decode_internal.hpp"
#include "lfcam/decode/decode.hpp"

namespace lfcam {

namespace {

using decode_detail::CfaTable;

constexpr float kHotPixelThreshold = 0.25f;  // of full scale above every same-colour neighbour
constexpr float kDarkWhite = 0.02f;          // white response (of its brightest) below which a photosite is unlit

std::string sizeText(const Image& image) {
  return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

Status checkSameSize(const Image& image, const Image& mosaic, const std::string& what) {
  if (image.width() != mosaic.width() || image.height() != mosaic.height() || image.channels() < 1)
    return makeError(ErrorCode::Usage, what + ": " + sizeText(image) + " does not match the raw's " + sizeText(mosaic));
  return {};
}

// (raw - offset) / (white level - black level), with offset the dark frame or the black level.
Image normalise(const RawImage& raw, const RawImage* dark) {
  const Image& mosaic = raw.mosaic;
  Image out(mosaic.width(), mosaic.height(), 1);
  const float black = float(raw.blackLevel), scale = float(1.0 / (raw.whiteLevel - raw.blackLevel));
  const float* in = mosaic.plane(0);
  const float* darkPlane = dark ? dark->mosaic.plane(0) : nullptr;
  float* o = out.plane(0);
  const std::size_t n = mosaic.planeSize();
  parallelFor(0, n, 1 << 16, [&](std::size_t begin, std::size_t end) {
    if (darkPlane)
      for (std::size_t k = begin; k < end; ++k) o[k] = (in[k] - darkPlane[k]) * scale;
    else
      for (std::size_t k = begin; k < end; ++k) o[k] = (in[k] - black) * scale;
  });
  return out;
}

// The brightest level of each colour of the white image (99.5th percentile, hot pixels aside).
std::array<float, 3> whiteReferences(const Image& white, ColorFilter filter) {
  const bool mono = filter == ColorFilter::Mono;
  const CfaTable cfa(mono ? ColorFilter::RGGB : filter);
  const int w = white.width(), h = white.height();
  // About a million photosites are plenty for a percentile: every stride-th 2x2 block.
  const int stride = std::max(1, int(std::sqrt(double(w) * h / 1e6)));
  std::array<std::vector<float>, 3> values;
  for (int y = 0; y < h; ++y) {
    if ((y / 2) % stride) continue;
    for (int x = 0; x < w; ++x)
      if ((x / 2) % stride == 0) values[std::size_t(mono ? 0 : cfa(x, y))].push_back(white.at(x, y, 0));
  }
  std::array<float, 3> refs{1, 1, 1};
  for (std::size_t c = 0; c < 3; ++c) {
    auto& v = values[mono ? 0 : c];
    if (v.empty()) continue;
    const std::size_t k = std::min(v.size() - 1, std::size_t(0.995 * double(v.size())));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    refs[c] = std::max(v[k], 1e-6f);
  }
  return refs;
}

// Devignetting per photosite: value / white (radiance relative to the white image's) and the
// white's response over its brightest (the weight).
Image devignette(Image& value, const Image& white, ColorFilter filter) {
  const auto refs = whiteReferences(white, filter);
  const CfaTable cfa(filter == ColorFilter::Mono ? ColorFilter::RGGB : filter);
  const int w = value.width(), h = value.height();
  Image weight(w, h, 1);
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y) {
      float* v = value.row(y, 0);
      float* wt = weight.row(y, 0);
      const float* wh = white.row(y, 0);
      for (int x = 0; x < w; ++x) {
        const float ref = refs[std::size_t(filter == ColorFilter::Mono ? 0 : cfa(x, y))];
        const float level = wh[x] / ref;
        const bool lit = level > kDarkWhite;
        v[x] = lit ? v[x] / wh[x] : 0.0f;
        wt[x] = lit ? std::min(level, 1.0f) : 0.0f;
      }
    }
  });
  return weight;
}

// Unlit photosites (between microlens images) get the mean of the nearest ring of lit ones of
// their colour. Left at 0, they would pull down every demosaicing and Catmull-Rom tap that reaches
// them, and through the cubic's negative lobes push the views at the aperture's rim up (by up to
// 0.05 RMS in mono). Reads only lit photosites and writes only unlit ones: rows run in parallel.
void fillUnlit(Image& value, const Image& weight, ColorFilter filter) {
  const int w = value.width(), h = value.height(), step = filter == ColorFilter::Mono ? 1 : 2;
  constexpr int kRings = 3;
  float* v = value.plane(0);
  const float* wt = weight.plane(0);
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < w; ++x) {
        if (wt[std::size_t(y) * w + x] > 0) continue;
        for (int r = step; r <= kRings * step; r += step) {
          float sum = 0;
          int count = 0;
          for (int dy = -r; dy <= r; dy += step)
            for (int dx = -r; dx <= r; dx += (std::abs(dy) == r ? step : 2 * r)) {
              const int xx = x + dx, yy = y + dy;
              if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
              const std::size_t k = std::size_t(yy) * w + xx;
              if (wt[k] > 0) sum += v[k], ++count;
            }
          if (count) {
            v[std::size_t(y) * w + x] = sum / float(count);
            break;
          }
        }
      }
  });
}

// Camera RGB -> white-balanced, colour-corrected RGB, per sample.
void correctColor(LightField& lf, const std::array<double, 3>& gains, const std::array<double, 9>& matrix) {
  float m[9];
  for (int k = 0; k < 9; ++k) m[k] = float(matrix[std::size_t(k)] * gains[std::size_t(k % 3)]);
  const std::size_t pixels = lf.shape().viewPixels();
  parallelFor(0, lf.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const int u = int(view % std::size_t(lf.nu())), v = int(view / std::size_t(lf.nu()));
      float* r = lf.plane(u, v, 0);
      float* g = lf.plane(u, v, 1);
      float* b = lf.plane(u, v, 2);
      for (std::size_t k = 0; k < pixels; ++k) {
        const float R = r[k], G = g[k], B = b[k];
        r[k] = m[0] * R + m[1] * G + m[2] * B;
        g[k] = m[3] * R + m[4] * G + m[5] * B;
        b[k] = m[6] * R + m[7] * G + m[8] * B;
      }
    }
  });
}

Status checkInputs(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options) {
  const Image& mosaic = raw.mosaic;
  if (mosaic.empty() || mosaic.channels() != 1)
    return makeError(ErrorCode::Usage, "decode: the raw must be one non-empty channel of photosites");
  if (!(raw.whiteLevel > raw.blackLevel))
    return makeError(ErrorCode::Usage, "decode: white level " + std::to_string(raw.whiteLevel) +
                                           " is not above black level " + std::to_string(raw.blackLevel));
  if (!(grid.pitchX > 1 && grid.pitchY > 1) || grid.columns < 1 || grid.rows < 1 || !std::isfinite(grid.rotationRad))
    return makeError(ErrorCode::Usage, "decode: the lenslet grid is empty or its pitch is below 2 pixels");
  if (options.packing && *options.packing != grid.packing)
    return makeError(ErrorCode::Usage, std::string("decode: the lenslet grid is ") + packingName(grid.packing) +
                                           ", not the " + packingName(*options.packing) + " array expected");
  if (options.views < 0 || options.views > 256)
    return makeError(ErrorCode::Usage, "decode: views must be in [1, 256], not " + std::to_string(options.views));
  if (options.dark) LFCAM_TRY(checkSameSize(options.dark->mosaic, mosaic, "dark frame"));
  if (const RawImage* white = options.white) {
    LFCAM_TRY(checkSameSize(white->mosaic, mosaic, "white image"));
    if (!(white->whiteLevel > white->blackLevel))
      return makeError(ErrorCode::Usage, "white image: white level is not above black level");
  }
  if (options.whiteImage) LFCAM_TRY(checkSameSize(*options.whiteImage, mosaic, "white image"));
  return {};
}

int viewCount(const LensletGrid& grid, const DecodeOptions& options) {
  return options.views > 0 ? options.views : std::max(1, int(std::lround(grid.pitchX)));
}

}  // namespace

namespace decode_detail {

Result<Devignetted> devignettedMosaic(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options) {
  LFCAM_TRY(checkInputs(raw, grid, options));
  const int channels = raw.colorFilter == ColorFilter::Mono ? 1 : 3;
  const int n = viewCount(grid, options);
  const double samples = double(n) * n * grid.columns * grid.rows * (channels + 1);
  if (samples > 4e9)
    return makeError(ErrorCode::Resource, "decode: light field too large (" + std::to_string(samples) + " samples)");
  const ColorFilter filter = raw.colorFilter;

  // 1. Offset and scale, hot pixels.
  Devignetted out;
  out.value = normalise(raw, options.dark);
  if (options.repairHotPixels) repairHotPixels(out.value, filter, kHotPixelThreshold);

  // 2. Devignetting by the white image (same offset treatment: the dark frame holds the
  //    sensor's offset for both).
  if (options.white || options.whiteImage) {
    Image white;
    if (options.white) {
      white = normalise(*options.white, options.dark);
      if (options.repairHotPixels) repairHotPixels(white, filter, kHotPixelThreshold);
    } else {
      const Image& given = *options.whiteImage;
      white = Image(given.width(), given.height(), 1);
      std::copy(given.plane(0), given.plane(0) + given.planeSize(), white.plane(0));
    }
    out.weight = devignette(out.value, white, filter);
    fillUnlit(out.value, out.weight, filter);
  }
  return out;
}

Result<LightField> decodeDemosaiced(Image planes, Image weight, const RawImage& raw, const LensletGrid& grid,
                                    const DecodeOptions& options, Kernels kernels) {
  LFCAM_TRY(checkInputs(raw, grid, options));
  const int channels = raw.colorFilter == ColorFilter::Mono ? 1 : 3;
  if (planes.channels() != channels || planes.width() != raw.mosaic.width() || planes.height() != raw.mosaic.height())
    return makeError(ErrorCode::Usage, "decode: the demosaiced planes do not match the raw");
  const int n = viewCount(grid, options);
  const bool hasWhite = options.white || options.whiteImage;
  const bool hexagonal = grid.packing == Packing::Hexagonal;

  // 4. Dicing.
  ViewLayout layout;
  layout.views = n;
  layout.sampling = options.sampling;
  if (options.sampling == Sampling::IntegralPitch)
    layout.step.fill(grid.pitchX / std::max(1.0, std::round(grid.pitchX)));
  if (options.sampling == Sampling::Bricks) {
    layout.step = {grid.pitchX / n, grid.pitchY / n};
    layout.firstRow = hexagonal && grid.hexParity == 1 ? 1 : 0;
    if (grid.rows == layout.firstRow)
      return makeError(ErrorCode::Usage,
                       "decode: the grid's only row of microlenses is shifted, and bricks start with an unshifted one");
  }
  // Written once here: ordinary pages fault in faster (huge_page_allocator.hpp).
  LightField lf(LightFieldShape{n, n, grid.columns, grid.rows - layout.firstRow, channels}, Pages::Ordinary);
  lf.enableWeight(0);
  sampleLenslets(planes, weight, grid, layout, lf, kernels == Kernels::Reference);
  planes = Image();
  weight = Image();

  // Without a white image the aperture is a disc of the microlens image's diameter.
  if (!hasWhite) {
    const double diameter = options.apertureDiameterPx > 0 ? options.apertureDiameterPx : grid.pitchX;
    for (int v = 0; v < n; ++v)
      for (int u = 0; u < n; ++u) {
        const double du = lf.uFromCentre(u) * layout.step[0], dv = lf.vFromCentre(v) * layout.step[1];
        if (du * du + dv * dv <= 0.25 * diameter * diameter) continue;
        float* wt = lf.weightPlane(u, v);
        std::fill(wt, wt + lf.shape().viewPixels(), 0.0f);
      }
  }

  // 5. Colour: the white image already divided out each colour's response, so the camera's white
  //    balance gains apply only without it.
  if (channels == 3 && options.applyWhiteBalance && (raw.colorMatrix || (!hasWhite && raw.whiteBalance))) {
    const std::array<double, 3> gains =
        !hasWhite && raw.whiteBalance ? *raw.whiteBalance : std::array<double, 3>{1, 1, 1};
    const std::array<double, 9> identity{1, 0, 0, 0, 1, 0, 0, 0, 1};
    correctColor(lf, gains, raw.colorMatrix.value_or(identity));
  }

  // 6. Hexagonal rows onto a rectangular s grid.
  if (hexagonal && options.hexToRectangular && options.sampling != Sampling::Bricks)
    hexRowsToRectangular(lf, 1 - grid.hexParity);

  lf.metadata.optics = options.optics;
  lf.metadata.source = "lfcam decode" + (raw.source.empty() ? std::string() : " of a " + raw.source + " raw") + ": " +
                       std::to_string(grid.columns) + "x" + std::to_string(grid.rows) + " " +
                       packingName(grid.packing) + " microlenses, pitch " + std::to_string(grid.pitchX) + " px" +
                       (grid.fit.selfCalibrated ? ", grid self-calibrated from the raw (residual RMS " +
                                                      std::to_string(grid.fit.rmsResidualPx) + " px over " +
                                                      std::to_string(grid.fit.lensletsUsed) + " microlenses)"
                                                : std::string());
  return lf;
}

Result<LightField> decodeLightField(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options,
                                    Kernels kernels) {
  LFCAM_ASSIGN_OR_RETURN(auto prepared, devignettedMosaic(raw, grid, options));
  Image& value = prepared.value;
  const ColorFilter filter = raw.colorFilter;
  const bool reference = kernels == Kernels::Reference;

  // 3. Demosaicing.
  Image planes = filter != ColorFilter::Mono && options.demosaic == DemosaicMethod::LightFieldAware
                     ? demosaicLightField(value, filter, grid, prepared.weight, reference)
                 : reference ? demosaicReference(value, filter, options.demosaic, &grid)
                             : demosaic(value, filter, options.demosaic, &grid);
  value = Image();
  return decodeDemosaiced(std::move(planes), std::move(prepared.weight), raw, grid, options, kernels);
}

}  // namespace decode_detail

Result<LightField> decodeLightField(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options) {
  return decode_detail::decodeLightField(raw, grid, options, decode_detail::Kernels::Fast);
}

}  // namespace lfcam
