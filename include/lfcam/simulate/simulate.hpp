// simulate: a physically based plenoptic (or conventional) camera, traced ray by ray.
//
// Each pixel integrates the irradiance over its area (the box filter of section 3.3). In
// light-field mode, rays run from a point in the pixel through a point on a microlens (a thin
// lens of the array; the opaque rest of its cell blocks them) and then through the main lens
// (a thin lens; rays outside its aperture are blocked) into the scene. The samples are stratified
// jointly over the pixel and over the microlens (light-field mode) or the main-lens aperture
// (conventional mode); every microlens whose image can reach the pixel is traced, so microlens
// images overlap when the main lens is faster than the microlenses (Figure 2). Irradiance
// includes the cos^4 fall-off of the ray between the main lens and the image plane.
//
// Determinism: every pixel draws its samples from a generator seeded by (seed, pixel), and the
// noise of each row from one seeded by (seed, row): the result does not depend on the number of
// threads. Threads: lfcam::parallelFor over rows.
//
// Cost: samples x (microlenses reaching the pixel, 1 or 2 with matched f-numbers) rays per pixel.
#pragma once

#include <cstdint>
#include <filesystem>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/scene.hpp"

namespace lfcam {

struct SimulationOptions {
  int samplesPerPixel = 16;  // rounded up to a square number n x n (stratified), at most 32 x 32
};

// Both images are laid out as the camera stores its raw: the sensor turned by 180 degrees, so
// that the scene stands upright (camera_model.hpp).
struct SensorCapture {
  // Irradiance per unit scene radiance (steradians) of each pixel's own colour filter; 1 channel,
  // sensor width x height. No noise.
  Image irradiance;
  // The raw mosaic in digital numbers (DN, black level included, with noise when enabled), one
  // channel, stored as DN (not scaled to [0, 1]): raw.at(x, y, 0) is an integer in
  // [0, 2^bitDepth - 1].
  Image raw;
  std::uint64_t rays = 0;  // rays traced (for benchmarks)
};

// Traces the scene through the camera onto the sensor, then applies the sensor model.
SensorCapture simulateCapture(const Scene& scene, const CameraModel& camera, const SimulationOptions& options = {},
                              const ProgressCallback& progress = {});

// The sensor model alone: irradiance (as in SensorCapture) -> DN with shot noise, read noise,
// full-well clipping, quantisation and hot pixels.
Image applySensor(const Image& irradiance, const Sensor& sensor);

// The ideal light field: the scene's radiance along the ray from lens point (u, v) through each
// microlens centre, with no sensor in the way. (s, t) is microlens (s, t) of the raw's grid
// (gridFromCamera), the simulator's microlens (columns - 1 - s, rows - 1 - t): the right way up.
// (u, v): views spaced du = F * pixelPitch / separation on the lens (one sensor pixel under a
// microlens), as many as the microlens image is pixels across (rounded), centred on the axis, u
// to the right and v down as seen from behind the camera. Weight 1 for lens points inside the
// aperture, 0 outside. Hexagonal lattices: rows t with (t + rows) odd (the grid's shifted rows)
// lie half a pitch towards +s of the others. Channels: 3 (RGB), or 1 (luminance) for a monochrome
// sensor. metadata.optics is set.
// Requires a microlens array (Usage error otherwise).
Result<LightField> idealLightField(const Scene& scene, const CameraModel& camera);

// The ideal light field filtered as the sensor samples it, what a decoded capture can be fairly
// scored against: each sample is the mean radiance over the lens square one view step wide around
// (u, v) (the footprint of one pixel) and over the refracting part of the microlens's cell (the
// footprint of one (s, t) sample), from boxSamples^2 stratified points of each, paired; rays the
// aperture stops are left out (as devignetting by the white image leaves them out). Otherwise as
// idealLightField; boxSamples <= 1 gives the point-sampled field.
Result<LightField> idealLightFieldBoxFiltered(const Scene& scene, const CameraModel& camera, int boxSamples);
// Depth (mm along z to the first surface hit; +infinity when nothing is hit) of the central ray
// through each microlens centre, in the (s, t) layout of idealLightField.
Result<Image> idealDepth(const Scene& scene, const CameraModel& camera);
// The same from the lens point of view (u, v) of idealLightField: the truth for a depth map of that
// view. With an even number of views there is no centre view, and the one lfcam depth maps,
// ((views - 1) / 2, (views - 1) / 2), lies half a view step off the axis, where a surface at
// disparity d is seen d / 2 pixels aside of where the central ray sees it.
Result<Image> idealDepthOfView(const Scene& scene, const CameraModel& camera, int u, int v);

struct CaptureOutputs {
  bool white = true;  // white.png
  // depth.pfm and ideal.lf.h5 (light-field mode); for a focused plenoptic camera raw.xml beside the
  // raw, and ideal.pfm and virtual_depth.pfm on the frame of a quarter of the micro-image diameter
  // in pixels per lens (simulate/focused_truth.hpp).
  bool groundTruth = true;
  std::string rawExtension = ".png";  // or ".tiff"
};

// Writes the outputs of `lfcam simulate` into `folder`, atomically (docs/formats.md):
// raw.png, white.png, camera.json, depth.pfm, ideal.lf.h5.
Status writeSimulation(const std::filesystem::path& folder, const Scene& scene, const CameraModel& camera,
                       const SimulationOptions& options, const CaptureOutputs& outputs = {},
                       const ProgressCallback& progress = {});

}  // namespace lfcam
