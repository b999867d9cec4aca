// The plain float64 oracles the fast renderers are tested against (not public): per output pixel,
// straight from the equations, with no threading and no shortcuts.
#pragma once

#include <functional>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/render/denoise.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "lfcam/render/tilted_focus.hpp"

namespace lfcam {

// refocus (refocus.hpp), per pixel and per view.
Image refocusReference(const LightField& lightField, double slope);

// The same formula with its own slope at each output pixel (x, y) (pixel indices); a pixel whose
// slope is not finite is 0. With `keep`, only the taps (column, row) of view (u, v) for which
// keep(u, v, row, column, x, y) holds count for pixel (x, y), unless it holds for none: then all do.
using KeepTap = std::function<bool(int u, int v, int row, int column, int x, int y)>;
Image refocusSlopeFieldReference(const LightField& lightField, const std::function<double(int x, int y)>& slopeAt,
                                 const KeepTap& keep = {});

// refocusTilted (tilted_focus.hpp): refocusSlopeFieldReference at the plane's slope at each pixel centre.
Image refocusTiltedReference(const LightField& lightField, const FocusPlane& plane);

// refocusUpsampled (upsampled_refocus.hpp): every sample of every view splatted on the fine grid.
Result<Image> refocusUpsampledReference(const LightField& lightField, double slope, int factor);

// renderSyntheticPhoto (synthetic_camera.hpp): the geometry per output pixel and per aperture
// sample, with quadrilinear interpolation of the light field. supersampling = 1 samples the
// aperture at the views (what Fast computes), more samples between them (what Quadrature computes).
Result<Image> renderSyntheticPhotoReference(const LightField& lightField, const SyntheticCamera& camera,
                                            int supersampling = 1);

// observe (synthetic_camera.hpp), per pixel.
Result<Image> observeReference(const LightField& lightField, const Observer& observer);

// denoise (denoise.hpp): the same padded, sheared and mirrored frame, transformed by 1D DFTs term
// by term over the full (not half) spectrum, the passband at every bin. Small light fields only
// (each DFT is quadratic in its length).
Result<LightField> denoiseReference(const LightField& lightField, const DenoiseOptions& options);

}  // namespace lfcam
