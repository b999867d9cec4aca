// The plain float64 oracles the fast renderers are tested against (not public): per output pixel,
// straight from the equations, with no threading and no shortcuts.
#pragma once

#include "lfcam/image.hpp"
#include "lfcam/light_field.hpp"
#include "lfcam/result.hpp"
#include "lfcam/synthetic_camera.hpp"

namespace lfcam {

// refocus (refocus.hpp), per pixel and per view.
Image refocusReference(const LightField& lightField, double slope);

// renderSyntheticPhoto (synthetic_camera.hpp): the geometry per output pixel and per aperture
// sample, with quadrilinear interpolation of the light field. supersampling = 1 samples the
// aperture at the views (what Fast computes), more samples between them (what Quadrature computes).
Result<Image> renderSyntheticPhotoReference(const LightField& lightField, const SyntheticCamera& camera,
                                            int supersampling = 1);

// observe (synthetic_camera.hpp), per pixel.
Result<Image> observeReference(const LightField& lightField, const Observer& observer);

}  // namespace lfcam
