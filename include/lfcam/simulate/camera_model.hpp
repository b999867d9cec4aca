// CameraModel: the simulated plenoptic camera of the paper's section 3: a thin main lens, a
// microlens array at the main lens's image plane, and a sensor behind it. Also the conventional
// camera (no microlens array, the sensor at the image plane).
//
// Frames and units. Lengths in millimetres. The optical axis is z; the main lens (thin, its
// principal plane) is at z = 0. Lateral coordinates (x, y) are as seen from behind the camera
// looking at the scene: x to the right, y downwards, in the object space and in the image space
// alike. Scene points have z > 0 (distance in front of the lens). Image-side planes are given by
// their distance behind the lens: the microlens plane at F (imageDistance()), the sensor at
// F + microlensToSensor. The thin lens maps an image-side point (x, y) at distance F to the
// object point (-x d / F, -y d / F) at the focus distance d: the sensor image is upside down.
//
// Sensor pixels: pixel (px, py) covers x in [(px - W/2) p, (px + 1 - W/2) p), likewise y, with p
// the pixel pitch and W x H the resolution: the optical axis crosses the sensor's centre. Pixel
// centres are at (px + 0.5, py + 0.5) as in image.hpp.
//
// The raw as the camera stores it (simulateCapture, raw.png): a camera reads its sensor out turned
// by 180 degrees, so that the scene stands upright. Raw pixel (x, y) is sensor pixel (W - 1 - x,
// H - 1 - y); the colour filter pattern (Sensor::colorFilter) and every pixel position this model
// reports (microlensImageCentrePx, camera.json's lattice_px) are the raw's.
//
// Microlens lattice: microlens (i, j), i in [0, columns), j in [0, rows), has its centre at
//   centre = offset + R(rotation) * (a, b),
//   square:    a = (i - (columns - 1) / 2) pitch,             b = (j - (rows - 1) / 2) pitch
//   hexagonal: a = (i - (columns - 1) / 2 + (j odd ? 1/2 : 0)) pitch,
//              b = (j - (rows - 1) / 2) pitch sqrt(3) / 2
// on the microlens plane. Each microlens's cell is its Voronoi cell: a square, or a hexagon with
// flat sides left and right and corners at the top and bottom (before rotation); its refracting part is the cell scaled
// by sqrt(fillFactor) about the centre, and the rest of the cell is opaque.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/core/sensor_layout.hpp"

namespace lfcam {

struct MainLens {
  double focalLengthMm = 140.0;    // the paper's prototype: 140 mm ...
  double fNumber = 2.8;            // ... at f/2.8 (object side: focal length / aperture diameter)
  double focusDistanceMm = 457.2;  // 18 inches (section 6.1); its image-side f-number is ~f/4

  double apertureDiameterMm() const { return focalLengthMm / fNumber; }
  // F: where the focus plane is imaged (1/f = 1/d + 1/F).
  double imageDistanceMm() const;
  // The image-side f-number F / aperture (section 3.2): what must match the microlenses.
  double imageSideFNumber() const { return imageDistanceMm() / apertureDiameterMm(); }
  // Sets fNumber so that the image-side f-number is `n`.
  void setImageSideFNumber(double n) { fNumber = n * focalLengthMm / imageDistanceMm(); }
};

struct MicrolensArray {
  double pitchMm = 0.125;      // centre to centre (the paper: 125 um)
  double focalLengthMm = 0.5;  // the paper: 500 um, so f/4
  Packing packing = Packing::Square;
  double rotationDeg = 0;                // of the lattice about the optical axis, x towards y
  std::array<double, 2> offsetMm{0, 0};  // lateral shift of the lattice (microlens plane)
  std::optional<double> toSensorMm;      // default: focalLengthMm (section 3.1)
  double fillFactor = 1.0;               // refracting area / cell area, (0, 1]
  // Microlenses across and down; 0: as many as fit on the sensor.
  int columns = 0, rows = 0;

  // A multi-focus array (Raytrix): the focal lengths of three lens types, which the lattice's
  // 3-colouring assigns (lensType: neighbours are always of the other two types). Empty: one type,
  // focalLengthMm. With the sensor off the microlenses' focus (toSensorMm != focal length) the
  // camera is a focused plenoptic one (plenoptic 2.0): each microlens images the main lens's image
  // a = f b / |b - f| in front of it (b > f: Keplerian, inverted micro-images) or behind it
  // (b < f: Galilean, upright, as Raytrix's), b = toSensorMm.
  std::vector<double> typeFocalLengthsMm;

  double fNumber() const { return focalLengthMm / pitchMm; }
  int lensTypes() const { return typeFocalLengthsMm.empty() ? 1 : int(typeFocalLengthsMm.size()); }
  // Type of microlens (i, j) of the simulator's lattice (camera_model.hpp's indices).
  int lensType(int i, int j) const;
  double focalLengthOf(int i, int j) const {
    return typeFocalLengthsMm.empty() ? focalLengthMm : typeFocalLengthsMm[std::size_t(lensType(i, j))];
  }
  double separationMm() const { return toSensorMm.value_or(focalLengthMm); }
  double rowPitchMm() const { return packing == Packing::Square ? pitchMm : pitchMm * 0.8660254037844386; }
};

struct Sensor {
  int width = 1000, height = 1000;  // pixels (the paper's KAF-16802CE: about 4000 x 4000)
  double pixelPitchMm = 0.009;      // 9 um
  ColorFilter colorFilter = ColorFilter::RGGB;
  int bitDepth = 12;
  int blackLevel = 64;    // digital numbers (DN)
  int whiteLevel = 4095;  // DN; the highest code a pixel reports
  // Mean photo-electrons = exposure * electronsPerIrradiance * E, where E (steradians) is the
  // irradiance on the pixel per unit scene radiance: the integral of L cos(theta) d(omega) for
  // L = 1. A white surface (L = 1) seen through an image-side f/4 gives E = pi / 64 ~ 0.049.
  double exposure = 1.0;
  double electronsPerIrradiance = 200000.0;
  double fullWellElectrons = 20000.0;
  double readNoiseElectrons = 3.0;  // Gaussian, rms
  bool noise = true;                // photon shot noise (Poisson) and read noise
  double hotPixelFraction = 0;      // share of pixels stuck at whiteLevel
  std::uint64_t seed = 1;           // noise, hot pixels and ray samples

  // DN per electron: (whiteLevel - blackLevel) / fullWellElectrons.
  double gain() const { return (whiteLevel - blackLevel) / fullWellElectrons; }
  double widthMm() const { return width * pixelPitchMm; }
  double heightMm() const { return height * pixelPitchMm; }
};

struct CameraModel {
  MainLens mainLens;
  std::optional<MicrolensArray> microlenses;  // none: a conventional camera
  Sensor sensor;

  bool conventional() const { return !microlenses; }
  // A focused plenoptic camera (plenoptic 2.0): every lens type's focus at least 1 % off the
  // sensor, so that it images a plane of the main lens's image (virtual depth under 100).
  bool focusedPlenoptic() const;
  // Microlens counts after applying the "as many as fit" default (square: sensor size divided
  // by the pitch of the microlens images, floor).
  std::array<int, 2> microlensCounts() const;
  // Centre of microlens (i, j) on the microlens plane, mm.
  std::array<double, 2> microlensCentreMm(int i, int j) const;
  // The projection of the main lens's centre through microlens (i, j)'s centre onto the sensor,
  // in the raw's pixel coordinates (turned by 180 degrees, see above): the centre of its image in
  // the stored raw, what a calibration finds.
  std::array<double, 2> microlensImageCentrePx(int i, int j) const;
  // Diameter of the image of the main-lens aperture under one microlens, in pixels
  // (aperture * separation / F; section 3.2).
  double microlensImageDiameterPx() const;

  // The prototype of section 5 at reduced resolution (width x height pixels of 9 um, 125 um
  // microlenses of f/4, 140 mm f/2.8 main lens focused at 18 inches).
  static CameraModel paperPrototype(int width = 1000, int height = 1000);

  // Checks every value; the error names the key (as in the scene file) that is wrong.
  Status validate(const std::string& where) const;
};

}  // namespace lfcam
