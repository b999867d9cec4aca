// RawImage: a sensor image as it left the camera, before any decoding: one value per photosite
// (a Bayer mosaic or monochrome), in digital numbers, with what is known about how to read it.
//
// Produced by readRaw (raw_io.hpp) from PNG/TIFF lenslet images, the simulator's output, Lytro
// containers (.lfp, .lfr) and camera raw files (LibRaw). Consumed by calibration (lenslet_grid.hpp)
// and decoding (decode.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/sensor_layout.hpp"

namespace lfcam {

// What the camera's own metadata says about its microlens array, in sensor pixels. Calibration
// uses it as a starting guess; it is never trusted without a fit.
struct LensletHint {
  double pitchPx = 0;                    // microlens pitch over pixel pitch
  double rotationRad = 0;                // of the lattice, x towards y
  std::array<double, 2> offsetPx{0, 0};  // centre of the lattice relative to the sensor centre
  Packing packing = Packing::Square;
};

// Which camera took a frame and how its lens stood, as its metadata says: what picks the white image
// of the same camera, zoom and focus from a database (white_database.hpp). Steps are the lens
// motors' positions; what is unknown stays empty.
struct CameraSetting {
  std::string serial, model, firmware;
  std::optional<double> zoomStep, focusStep;
  std::optional<double> exposureS;  // frame exposure, seconds
  // Which metadata layout the values came from: "lytro-frame" (devices.lens.zoomStep, ... of the
  // first generation and of Illum white images), "lytro-public" (zoomStep, ... at the top of an
  // Illum picture's public metadata), "side-car" (a JSON file beside an image); "" when none.
  std::string metadataKeys;
};

struct RawImage {
  // One channel, width x height photosites, values in DN (not scaled to [0, 1]).
  Image mosaic;
  ColorFilter colorFilter = ColorFilter::Mono;
  double blackLevel = 0;  // DN
  double whiteLevel = 1;  // DN of a saturated photosite
  std::optional<LensletHint> lenslet;
  std::optional<std::array<double, 3>> whiteBalance;  // gains for R, G, B
  std::optional<std::array<double, 9>> colorMatrix;   // camera RGB -> linear sRGB, row-major
  // The main lens and microlens geometry, when the metadata states it (the simulator's camera.json).
  std::optional<Optics> optics;
  CameraSetting setting;
  // Where the raw came from ("lytro-lfp", "lytro-lfr", "simulator", "libraw", "image") and the
  // frame metadata as the file gave it, as JSON text ("" when it gave none), for `lfcam info`.
  std::string source;
  std::string metadataJson;
};

}  // namespace lfcam
