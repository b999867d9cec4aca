// Digital refocusing by shift-and-add of the sub-aperture images: the paper's Equation 6 with a
// full aperture (beta = 1, A = 1), in the slope form of the HCI convention (light_field.hpp):
//
//   E(s, t) = sum_{u,v} w_{uv}(s - u d, t - v d) L(u, v, s - u d, t - v d)
//             / sum_{u,v} w_{uv}(s - u d, t - v d)
//
// with (u, v) in view steps from the aperture centre and d the slope in pixels per view step.
// Each view is resampled with bilinear interpolation; w is the light field's weight (1 where it
// has none) times the bilinear coefficient of each tap that lies inside the view, so every output
// pixel is normalised by the rays that actually contributed (section 5.2): no dark borders.
// A pixel that no ray reaches is 0.
//
// refocus is the fast kernel (float32, one pass per view, threaded over rows), tested against a
// plain float64 per-pixel oracle (src/render/references.hpp).
#pragma once

#include "lfcam/image.hpp"
#include "lfcam/light_field.hpp"

namespace lfcam {

Image refocus(const LightField& lightField, double slope);

}  // namespace lfcam
