// FocusedCalibration: where the micro-images of a focused plenoptic camera (plenoptic 2.0:
// Lumsdaine and Georgiev 2009; Raytrix) lie on the image, which lens type made each, and which way
// up they are.
//
// In such a camera each microlens images a small part of the main lens's image, sharply, onto the
// sensor; a point of that image at virtual depth v is seen by the micro-images around it, in the
// one centred at C at
//   S = C + orientation * (Q - C) / v
// where Q is the point as the main lens's centre sees it, in the image's pixel coordinates on the
// lattice of micro-image centres (the rendered photograph's frame), and orientation is +1 when the
// micro-images stand upright (Galilean: the main lens's image lies behind the microlenses, as in
// Raytrix cameras) and -1 when they are inverted (Keplerian: it lies in front of them, as in
// Lumsdaine and Georgiev's camera). Neighbouring micro-images D pixels apart see the point
// D / v pixels apart: v is what the image measures (Raytrix's virtual depth), a / b for a main-lens
// image a millimetres from microlenses b from the sensor (to within (F + b) / (F - a), F the
// main lens to the microlenses; simulate's focusedTruth computes it exactly).
//
// Pixel coordinates as image.hpp's: pixel (x, y) covers [x, x+1) x [y, y+1).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

enum class MicroImageOrientation { Upright, Inverted };

// A kind of microlens of a multi-focus array (Raytrix: three focal lengths, so that some kind is
// sharp at every depth).
struct LensType {
  // Raytrix's name of this kind: a lattice offset in lens pitches (x right, y up), (0, 0), (1, 0)
  // or (-1, 0). Its lenses lie at the reference lens less the offset: the reference's right-hand
  // neighbour is of the kind (-1, 0), as PlenopticToolbox 2.0 reads it and as a Raytrix R42
  // capture's sharpness shows.
  std::array<double, 2> offset{0, 0};
  // Virtual depths this kind images sharply.
  double minVirtualDepth = 1, maxVirtualDepth = 100;
};

// What turns virtual depth into distance: the main lens's focal length f, its distance F to the
// microlenses, theirs b to the sensor, mm. Raytrix's file holds none (lfcam's <lfcam_optics> does).
struct FocusedOptics {
  double mainFocalLengthMm = 0, mainLensToMicrolensesMm = 0, microlensesToSensorMm = 0;
};

struct FocusedCalibration {
  // Micro-image centres: pitchX is the micro-image diameter D (Raytrix's "diameter", centre to
  // centre), pitchY D sqrt(3) / 2 on a hexagonal array.
  LensletGrid grid;
  std::array<int, 2> referenceLens{0, 0};    // (i, j) of the lens the lens types' offsets start from
  double borderPx = 0;                       // the rim of each micro-image left out (Raytrix's lens_border)
  std::optional<double> totalCoveringPlane;  // Raytrix's tcp: the virtual depth seen by every point
  std::vector<LensType> lensTypes;           // one, or three on a multi-focus array
  MicroImageOrientation orientation = MicroImageOrientation::Upright;
  int imageWidth = 0, imageHeight = 0;  // the image it describes
  std::optional<FocusedOptics> optics;  // when known: distances (distanceOfVirtualDepth)

  double diameterPx() const { return grid.pitchX; }
  // Index into lensTypes of lens (i, j) of the grid.
  int lensType(int i, int j) const;
  // +1 upright, -1 inverted (the formula above).
  double orientationSign() const { return orientation == MicroImageOrientation::Upright ? 1.0 : -1.0; }
};

// How far in front of the microlenses (mm; negative: behind them) the main lens images the points
// at virtual depth v: a = s v b F / (F + b + s v b), s = +1 inverted (Keplerian), -1 upright, which
// solves v = s (a / b) (F + b) / (F - a) (the micro-image's magnification b / a, corrected for the
// main lens's perspective).
double mainLensImageInFrontMm(const FocusedOptics& optics, MicroImageOrientation orientation, double virtualDepth);
// The distance from the main lens (mm) of the points at virtual depth v; infinity at or beyond its
// focal plane.
double distanceOfVirtualDepth(const FocusedOptics& optics, MicroImageOrientation orientation, double virtualDepth);
// A Usage error naming `where` when the calibration holds no optics.
Status checkFocusedOptics(const FocusedCalibration& calibration, const std::string& where);
// A virtual depth map (focused_depth.hpp) as distances, mm (checkFocusedOptics first).
Result<Image> focusedDistanceMap(const FocusedCalibration& calibration, const Image& virtualDepth,
                                 const std::string& where);

// Raytrix's calibration XML (<RayCalibData>, docs/formats.md) and a JSON document of the same
// contents (its elements as keys, lens_type as an array "lens_types"), for an image of width x
// height pixels: Raytrix gives the reference lens's centre from the image's centre, y up. lfcam's
// own additions, both optional: the micro-images' orientation (default upright, as Raytrix's) and
// nothing else. `where` names the source in errors.
Result<FocusedCalibration> parseRayCalibXml(const std::string& text, const std::string& where, int width, int height);
Result<FocusedCalibration> parseFocusedCalibrationJson(const std::string& text, const std::string& where, int width,
                                                       int height);
// By the file's extension: .xml or .json.
Result<FocusedCalibration> readFocusedCalibration(const std::filesystem::path& path, int width, int height);

std::string rayCalibXml(const FocusedCalibration& calibration);
std::string focusedCalibrationJson(const FocusedCalibration& calibration);
// By the extension, atomically.
Status writeFocusedCalibration(const std::filesystem::path& path, const FocusedCalibration& calibration);

// The grid of micro-images whose centres lie in a width x height image, given the reference lens's
// centre (pixels), the diameter, the packing and the rotation (radians, x towards y); the
// reference lens is recorded in `referenceLens`.
FocusedCalibration focusedGrid(std::array<double, 2> referenceCentrePx, double diameterPx, Packing packing,
                               double rotationRad, int width, int height);

}  // namespace lfcam
