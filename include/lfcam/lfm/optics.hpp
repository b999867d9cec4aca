// LfmOptics: the light-field microscope of Broxton et al. 2013 ("Wave optics theory and 3-D
// deconvolution for the light field microscope", Optics Express 21(21)): an objective and tube lens
// forming the native image on a microlens array, the sensor one microlens focal length behind it.
//
// Units: as microscopists write them (and napari-LF's metadata.txt): the wavelength in nanometres,
// the tube lens's focal length in millimetres, every other length in micrometres. Object-space
// lengths (depths, lateral positions of a point) are micrometres in the specimen; image-side ones
// (microlens pitch, pixel size) are micrometres behind the tube lens.
//
// The microlens array is a square grid whose lenslet centres lie on multiples of the pitch from the
// optical axis; each lenslet's refracting part is a square centred in its cell, of area
// fillFactor times the cell's, and the rest of the cell is opaque. The sensor sits at the microlens
// focal plane.
#pragma once

#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam {

struct LfmOptics {
  // napari-LF's sample data (../shared/data/lfm-guv): a 60x / 1.2 water objective at 593 nm.
  double magnification = 60;       // objective with its tube lens, > 0
  double numericalAperture = 1.2;  // object side, n sin(alpha), in (0, immersionIndex)
  double immersionIndex = 1.35;    // n of the medium the point sits in, >= 1
  double wavelengthNm = 593;       // in vacuum
  double tubeFocalLengthMm = 200;  // the objective's focal length is this / magnification
  double microlensPitchUm = 100;   // centre to centre
  double microlensFocalLengthUm = 2500;
  double microlensFillFactor = 1.0;  // refracting area / cell area, (0, 1]
  double pixelSizeUm = 6.5;          // sensor pixel pitch (square pixels)
  int supersample = 3;               // field samples per pixel along x and y, >= 1

  double wavelengthUm() const { return wavelengthNm * 1e-3; }
  double sinAlpha() const { return numericalAperture / immersionIndex; }  // half-angle of the cone
  double objectiveFocalLengthUm() const { return tubeFocalLengthMm * 1e3 / magnification; }
  // The image-side cutoff of the native image: NA / (lambda M), cycles per micrometre.
  double imageCutoffPerUm() const { return numericalAperture / (wavelengthUm() * magnification); }
  // Image-side sample spacing of the field: pixelSizeUm / supersample.
  double sampleSpacingUm() const { return pixelSizeUm / supersample; }
};

// Ok, or the first thing wrong in one line ("NA 1.4 above the immersion index 1.33: no light
// reaches the objective"), ErrorCode::Usage.
Status validateLfmOptics(const LfmOptics& optics);

// The optics in the "calibrate" section of napari-LF's metadata.txt (a JSON file): objective_*,
// tubelens_focal_length, center_wavelength, medium_index, ulens_*, pixel_size (its supersample is
// the volume's voxels a lenslet: volume_request.hpp reads it).
// `text` is the file's content, `where` its name for messages. Missing keys keep their defaults
// in `defaults`; only the square microlens profile ("rect" or absent) is accepted. Validated.
Result<LfmOptics> parseNapariLfOptics(const std::string& text, const std::string& where,
                                      const LfmOptics& defaults = {});

}  // namespace lfcam
