// LfmOptics: the light-field microscope of Broxton et al. 2013 ("Wave optics theory and 3-D
// deconvolution for the light field microscope", Optics Express 21(21)): an objective and tube lens
// forming the native image on a microlens array, the sensor one microlens focal length behind it.
//
// Units: as microscopists write them (and napari-LF's metadata.txt): the wavelength in nanometres,
// the tube lens's focal length in millimetres, every other length in micrometres. Object-space
// lengths (depths, lateral positions of a point) are micrometres in the specimen; image-side ones
// (microlens pitch, pixel size) are micrometres behind the tube lens.
//
// The microlens array (MicrolensLayout) has a lenslet centred on the optical axis; each lenslet's
// refracting part is its cell (the points nearer its centre than any other's) shrunk about the
// centre to fillFactor of the cell's area, and the rest of the cell is opaque. The sensor sits at
// the microlens focal plane.
#pragma once

#include <optional>
#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam {

enum class MicrolensLayout {
  Square,     // lenslet (s, t) centred at (s, t) pitch; square cells
  Hexagonal,  // rows along x a pitch apart, rows sqrt(3)/2 pitch apart, odd rows (t = 1, 3, ... and
              // -1, -3, ...) shifted half a pitch toward +x: lenslet (s, t) at ((s + (t odd) / 2)
              // pitch, t sqrt(3)/2 pitch); hexagonal cells, two of their corners on the y axis
};

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
  MicrolensLayout array = MicrolensLayout::Square;
  double pixelSizeUm = 6.5;  // sensor pixel pitch along x
  // Pixel height / width: 1 on a camera; a rectified hexagonal frame's sqrt(3)/2 (frameOptics in psf.hpp).
  double pixelAspect = 1;
  int supersample = 3;  // field samples per pixel along x and y, >= 1

  double wavelengthUm() const { return wavelengthNm * 1e-3; }
  double sinAlpha() const { return numericalAperture / immersionIndex; }  // half-angle of the cone
  double objectiveFocalLengthUm() const { return tubeFocalLengthMm * 1e3 / magnification; }
  // The image-side cutoff of the native image: NA / (lambda M), cycles per micrometre.
  double imageCutoffPerUm() const { return numericalAperture / (wavelengthUm() * magnification); }
  // Image-side sample spacing of the field: pixelSizeUm / supersample along x, that times
  // pixelAspect along y.
  double sampleSpacingUm() const { return pixelSizeUm / supersample; }
  double sampleHeightUm() const { return sampleSpacingUm() * pixelAspect; }
  double pixelHeightUm() const { return pixelSizeUm * pixelAspect; }
  // Centre to centre of two rows of lenslets: the pitch, or sqrt(3)/2 of it for a hexagonal array.
  double rowPitchUm() const;
  // The lenslet rows in one period of the array along y: 1, or 2 for a hexagonal array (its odd
  // rows are shifted, so its rectangular period is a pitch wide and two rows high).
  int rowsPerPeriod() const { return array == MicrolensLayout::Hexagonal ? 2 : 1; }
};

// "square" or "hexagonal"; parseMicrolensLayout reads them back (nothing for another word).
const char* microlensLayoutName(MicrolensLayout array);
std::optional<MicrolensLayout> parseMicrolensLayout(const std::string& name);

// Ok, or the first thing wrong in one line ("NA 1.4 above the immersion index 1.33: no light
// reaches the objective"), ErrorCode::Usage.
Status validateLfmOptics(const LfmOptics& optics);

// The optics in the "calibrate" section of napari-LF's metadata.txt (a JSON file): objective_*,
// tubelens_focal_length, center_wavelength, medium_index, ulens_*, pixel_size (its supersample is
// the volume's voxels a lenslet: volume_request.hpp reads it).
// `text` is the file's content, `where` its name for messages. Missing keys keep their defaults
// in `defaults`; only napari-LF's default aperture profile ("rect" or absent) is accepted. lfcam's
// own key "ulens_array" ("square" or "hexagonal", which napari-LF has not) sets the array. Validated.
Result<LfmOptics> parseNapariLfOptics(const std::string& text, const std::string& where,
                                      const LfmOptics& defaults = {});

}  // namespace lfcam
