// decode: a raw lenslet image (RawImage) and its microlens grid (LensletGrid) -> the light field
// L(u, v, s, t) (the paper's section 5.2, with the two shortcomings of its section 6.3 removed).
//
// Steps: black level or dark frame subtraction, hot-pixel repair, devignetting by the white image
// (per photosite, before demosaicing, so each colour is divided by its own response), demosaicing,
// sampling every microlens image at its fitted sub-pixel centre, hexagonal to rectangular
// resampling, white balance and colour matrix.
//
// Orientation: as the raw lies. Sample (s, t) is microlens (i, j) = (s, t) of the grid: a camera
// reads its sensor out turned by 180 degrees, undoing the main lens's inversion, so the scene
// stands upright in the raw's lenslet layout (as LFToolbox and PlenoptiCam keep it). The readout
// turns each microlens image too, which the microlens had inverted as the main lens inverts the
// scene: view (u, v) is the raw's point at the microlens image's centre plus (u - (nu - 1) / 2,
// v - (nv - 1) / 2) pixels, and it looks through the main lens that many view steps right of and
// below its centre, as seen from behind the camera (light_field.hpp). Views are one pixel apart in
// the raw's axes (the main lens does not turn with the microlens array). The simulator writes its
// raws the same way, so a decoded capture is scored against idealLightField as it is.
//
// Weights: the white image's response at each sample, over its brightest level (1: the full
// aperture reached that pixel, 0: no light); without a white image, 1 inside the aperture disc of
// diameter apertureDiameterPx and 0 outside. Values are radiance relative to the white image's
// (raw / white), so refocusing normalises by the weight (section 5.2).
#pragma once

#include <optional>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

enum class DemosaicMethod {
  MalvarHeCutler,   // gradient-corrected bilinear (Malvar, He, Cutler 2004): the default
  HamiltonAdams,    // the paper's choice: edge-directed green, colour differences for red and blue
  LensletAware,     // bilinear within each microlens image from its own pixels only: nothing leaks
                    // across a microlens boundary
  LightFieldAware,  // each missing colour blended from the microlens image's neighbours (2D) and the
                    // same view of the neighbouring microlenses (4D), by which predicts the
                    // measured colour better: defocused content is smooth only in the second
};

enum class Sampling {
  SubPixel,       // each microlens image sampled at its fitted centre, views one pixel apart,
                  // Catmull-Rom cubic interpolation: no vernier error (section 6.3)
  IntegralPitch,  // the paper's: rotate and scale the raw to round(pitch) pixels per microlens
                  // (bilinear), then dice: kept for comparison
  Bricks,         // a light-field microscope's rectified frame (docs/formats.md): each microlens's
                  // views tile its brick, pitchX wide and pitchY high in the lattice's axes, centred
                  // on its fitted centre (Catmull-Rom); a hexagonal grid's rows stay shifted
                  // (hexToRectangular is not applied) and start with an unshifted one (a grid whose
                  // row 0 is shifted loses that row)
};

struct DecodeOptions {
  // Not owned; must outlive the call. White image of the same camera and settings, as a raw (same
  // size and CFA), or as an image already black-subtracted (any scale, 1 channel, same size).
  // Neither: weights from the aperture disc.
  const RawImage* white = nullptr;
  const Image* whiteImage = nullptr;
  const RawImage* dark = nullptr;  // subtracted (from the raw and the white) instead of black levels
  bool repairHotPixels = true;
  DemosaicMethod demosaic = DemosaicMethod::MalvarHeCutler;
  Sampling sampling = Sampling::SubPixel;
  int views = 0;                  // across and down; 0: round(grid.pitchX)
  double apertureDiameterPx = 0;  // without a white image; 0: grid.pitchX
  // Hexagonal grids: interpolate the shifted rows onto the other rows' s positions. Off: odd
  // rows keep their half-pitch shift (as idealLightField stores them).
  bool hexToRectangular = true;
  bool applyWhiteBalance = true;  // raw.whiteBalance and raw.colorMatrix, when present
  std::optional<Optics> optics;   // copied into metadata (the grid alone has no millimetres)
  // The packing the caller knows (a microscope's array): a grid of the other is refused, as a
  // white image calibrated wrongly would otherwise give a frame of the wrong layout.
  std::optional<Packing> packing;
};

Result<LightField> decodeLightField(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options = {});

// The steps on their own, for tests and other tools.

// Demosaics a one-channel mosaic (any scale) into 3 planes (R, G, B); a Mono filter gives a copy.
// LensletAware and LightFieldAware need the grid (without it: Malvar-He-Cutler); the others ignore it.
Image demosaic(const Image& mosaic, ColorFilter filter, DemosaicMethod method, const LensletGrid* grid = nullptr);

// Replaces each photosite more than `threshold` above every same-colour neighbour (8 of them, two
// pixels away in a Bayer mosaic) by their median. Returns the number repaired.
int repairHotPixels(Image& mosaic, ColorFilter filter, float threshold);

// Interpolates the shifted rows of a hexagonal-grid light field (decoded with hexToRectangular
// off, or idealLightField) onto the s positions of the other rows (cubic along s). shiftedT: the
// parity of the rows t whose sample s lies at s + 1/2 (a grid's shifted rows j = t, half a pitch
// towards +x in the raw): 1 - hexParity.
void hexRowsToRectangular(LightField& lightField, int shiftedT);

}  // namespace lfcam
