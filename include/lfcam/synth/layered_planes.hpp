// A synthetic light field with exact ground truth: textured fronto-parallel planes at known
// disparities, with occlusion, generated directly in (u, v, s, t) (no camera model involved).
//
// A plane of disparity d seen from view (u, v) (view steps from the centre) shows at pixel
// (s, t) its own point (s + u d, t + v d), in the coordinates of the centre view; the nearest
// plane (largest d) whose shape covers that point wins. Each pixel is the box-filtered average of
// supersampling^2 stratified samples over its area, as a real sensor pixel integrates.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"

namespace lfcam {

enum class PlaneTexture { Checkerboard, Noise, Stripes, Rings };

struct TexturedPlane {
  double disparity = 0;  // pixels per view step
  PlaneTexture texture = PlaneTexture::Noise;
  double period = 16;           // feature size of the texture, pixels
  float colour[3] = {1, 1, 1};  // linear RGB tint
  // Extent in centre-view pixel coordinates; a plane with an empty extent covers everything
  // (a background).
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool elliptical = false;  // an ellipse inscribed in the extent instead of a box
};

struct LayeredPlanesScene {
  int nu = 9, nv = 9, ns = 256, nt = 256;
  int supersampling = 3;
  std::uint64_t seed = 1;
  std::vector<TexturedPlane> planes;
  Optics optics;  // plausible plenoptic optics, so that alpha <-> slope is defined
};

// The built-in default: a background and three cards at different depths, with views x views
// views of width x height pixels (height 0: square; the layout scales with the size, disparities
// do not).
LayeredPlanesScene defaultLayeredPlanesScene(int views = 9, int width = 256, std::uint64_t seed = 1, int height = 0);

struct LayeredPlanesLightField {
  LightField lightField;
  Image disparity;  // ns x nt, one channel: the disparity seen at the aperture centre
};

LayeredPlanesLightField renderLayeredPlanes(const LayeredPlanesScene& scene, const ProgressCallback& progress = {});

}  // namespace lfcam
