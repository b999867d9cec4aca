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

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam {

Image refocus(const LightField& lightField, double slope);

// A focal stack: refocus at each slope, bit for bit, in less time than one call per slope (each
// block of rows is refocused at every slope while its views' rows are in cache).
std::vector<Image> refocus(const LightField& lightField, std::span<const double> slopes);

// The same stack a batch at a time, so that about `budgetBytes` of photographs at most are held:
// use(k, photo) for each slopes[k], in order.
void refocusEach(const LightField& lightField, std::span<const double> slopes,
                 const std::function<void(std::size_t index, Image&& photo)>& use,
                 std::size_t budgetBytes = std::size_t(256) << 20);

}  // namespace lfcam
