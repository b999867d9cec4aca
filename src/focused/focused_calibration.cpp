// FocusedCalibration: the grid placed on an image, lens types, and the file formats chosen by
// extension.
#include "lfcam/focused/focused_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/text_file.hpp"
#include "focused/ray_calib_document.hpp"
#include "io/io_support.hpp"

namespace lfcam {

namespace {

constexpr double kSqrt3 = 1.7320508075688772;

// A proper 3-colouring of the lattice, from a lattice position in lens units in the image's frame
// (y down): neighbours always differ, and Raytrix's three lens types are its three colours.
double colourOf(Packing packing, double across, double down) {
  return packing == Packing::Hexagonal ? across - kSqrt3 * down : across - down;
}

int colourClass(double colour) {
  const long k = std::lround(colour);
  return int(((k % 3) + 3) % 3);
}

bool near(double a, double b) { return std::abs(a - b) < 1e-3; }

}  // namespace

int FocusedCalibration::lensType(int i, int j) const {
  if (lensTypes.size() <= 1) return 0;
  auto across = [&](int column, int row) {
    const bool shifted = grid.packing == Packing::Hexagonal && ((row + grid.hexParity) & 1);
    return column + (shifted ? 0.5 : 0.0);
  };
  const double rowStep = grid.packing == Packing::Hexagonal ? kSqrt3 / 2 : 1.0;
  const double colour = colourOf(grid.packing, across(i, j) - across(referenceLens[0], referenceLens[1]),
                                 (j - referenceLens[1]) * rowStep);
  const int wanted = colourClass(colour);
  for (std::size_t t = 0; t < lensTypes.size(); ++t)
    // A type's lenses lie at the reference lens less its offset (Raytrix's frame, y up), as
    // PlenopticToolbox 2.0 places them and as the R42 capture's sharpness shows (LensTypes test).
    if (colourClass(-colourOf(grid.packing, lensTypes[t].offset[0], -lensTypes[t].offset[1])) == wanted) return int(t);
  return 0;
}

double mainLensImageInFrontMm(const FocusedOptics& optics, MicroImageOrientation orientation, double virtualDepth) {
  const double b = optics.microlensesToSensorMm, F = optics.mainLensToMicrolensesMm;
  const double side = orientation == MicroImageOrientation::Inverted ? 1.0 : -1.0;
  return side * virtualDepth * b * F / (F + b + side * virtualDepth * b);
}

double distanceOfVirtualDepth(const FocusedOptics& optics, MicroImageOrientation orientation, double virtualDepth) {
  const double f = optics.mainFocalLengthMm;
  const double imageDistance =
      optics.mainLensToMicrolensesMm - mainLensImageInFrontMm(optics, orientation, virtualDepth);
  return imageDistance > f ? f * imageDistance / (imageDistance - f) : std::numeric_limits<double>::infinity();
}

Status checkFocusedOptics(const FocusedCalibration& calibration, const std::string& where) {
  if (calibration.optics) return {};
  return makeError(ErrorCode::Usage, where +
                                         ": its calibration holds no optics (lfcam_optics, docs/formats.md), so no "
                                         "distance; the virtual depth needs none");
}

Result<Image> focusedDistanceMap(const FocusedCalibration& calibration, const Image& virtualDepth,
                                 const std::string& where) {
  LFCAM_TRY(checkFocusedOptics(calibration, where));
  Image distance(virtualDepth.width(), virtualDepth.height(), 1);
  std::transform(
      virtualDepth.plane(0), virtualDepth.plane(0) + distance.pixels().size(), distance.pixels().begin(),
      [&](float v) { return float(distanceOfVirtualDepth(*calibration.optics, calibration.orientation, v)); });
  return distance;
}

FocusedCalibration focusedGrid(std::array<double, 2> referenceCentrePx, double diameterPx, Packing packing,
                               double rotationRad, int width, int height) {
  FocusedCalibration calibration;
  LensletGrid& grid = calibration.grid;
  grid.packing = packing;
  grid.pitchX = diameterPx;
  grid.pitchY = packing == Packing::Hexagonal ? diameterPx * kSqrt3 / 2 : diameterPx;
  grid.rotationRad = rotationRad;
  // The image's corners in the lattice's frame, relative to the reference lens, give the rows and
  // columns whose centres can fall inside it.
  const double c = std::cos(rotationRad), s = std::sin(rotationRad);
  double minAcross = 1e300, maxAcross = -1e300, minDown = 1e300, maxDown = -1e300;
  for (const auto& corner :
       {std::array<double, 2>{0, 0}, {double(width), 0}, {0, double(height)}, {double(width), double(height)}}) {
    const double dx = corner[0] - referenceCentrePx[0], dy = corner[1] - referenceCentrePx[1];
    const double across = (c * dx + s * dy) / grid.pitchX, down = (-s * dx + c * dy) / grid.pitchY;
    minAcross = std::min(minAcross, across);
    maxAcross = std::max(maxAcross, across);
    minDown = std::min(minDown, down);
    maxDown = std::max(maxDown, down);
  }
  const int firstRow = int(std::ceil(minDown)), lastRow = int(std::floor(maxDown));
  const double half = packing == Packing::Hexagonal ? 0.5 : 0.0;
  const int firstColumn = int(std::ceil(minAcross - half)), lastColumn = int(std::floor(maxAcross));
  grid.rows = std::max(1, lastRow - firstRow + 1);
  grid.columns = std::max(1, lastColumn - firstColumn + 1);
  calibration.referenceLens = {-firstColumn, -firstRow};
  // The reference lens's row is not shifted.
  grid.hexParity = packing == Packing::Hexagonal ? (-firstRow) & 1 : 0;
  const double a = firstColumn * grid.pitchX, b = firstRow * grid.pitchY;
  grid.origin = {referenceCentrePx[0] + c * a - s * b, referenceCentrePx[1] + s * a + c * b};
  calibration.imageWidth = width;
  calibration.imageHeight = height;
  return calibration;
}

namespace focused_detail {

const char* orientationName(MicroImageOrientation orientation) {
  return orientation == MicroImageOrientation::Upright ? "upright" : "inverted";
}

std::optional<MicroImageOrientation> orientationFromName(const std::string& name) {
  if (name == "upright") return MicroImageOrientation::Upright;
  if (name == "inverted") return MicroImageOrientation::Inverted;
  return std::nullopt;
}

Result<FocusedCalibration> calibrationFromDocument(const RayCalibDocument& d, const std::string& where, int width,
                                                   int height) {
  auto bad = [&](ErrorCode code, const std::string& key, const std::string& what) -> Error {
    return makeError(code, where + ": " + key + ": " + what);
  };
  if (!(d.diameter >= 3 && d.diameter < 1e5)) return bad(ErrorCode::Format, "diameter", "expected 3 to 1e5 pixels");
  if (!(std::abs(d.rotation) <= M_PI)) return bad(ErrorCode::Format, "rotation", "expected radians in [-pi, pi]");
  if (!(d.lensBorder >= 0 && d.lensBorder < d.diameter / 2))
    return bad(ErrorCode::Format, "lens_border", "expected 0 to half the diameter");
  if (d.optics && !(d.optics->mainFocalLengthMm > 0 && d.optics->microlensesToSensorMm > 0 &&
                    d.optics->mainLensToMicrolensesMm > d.optics->mainFocalLengthMm))
    return bad(ErrorCode::Format, "lfcam_optics",
               "expected a focal length and a microlens distance above 0, the microlenses beyond the focal length");
  if (d.tcp && !(*d.tcp > 0 && std::isfinite(*d.tcp)))
    return bad(ErrorCode::Format, "tcp", "expected a positive virtual depth");
  if (!near(d.lensBaseX[0], 1) || !near(d.lensBaseX[1], 0))
    return bad(ErrorCode::Unsupported, "lens_base_x", "only (1, 0) is supported (the grid's rotation turns it)");
  Packing packing;
  if (near(std::abs(d.lensBaseY[0]), 0.5) && near(std::abs(d.lensBaseY[1]), kSqrt3 / 2))
    packing = Packing::Hexagonal;
  else if (near(d.lensBaseY[0], 0) && near(std::abs(d.lensBaseY[1]), 1))
    packing = Packing::Square;
  else
    return bad(ErrorCode::Unsupported, "lens_base_y", "neither a hexagonal (0.5, 0.866) nor a square (0, 1) lattice");
  if (d.lensTypes.size() != 1 && d.lensTypes.size() != 3 && !d.lensTypes.empty())
    return bad(ErrorCode::Unsupported, "lens_type",
               std::to_string(d.lensTypes.size()) + " lens types; 1 or 3 are supported");
  int coloursSeen = 0;
  for (std::size_t t = 0; t < d.lensTypes.size(); ++t) {
    const LensType& type = d.lensTypes[t];
    const std::string key = "lens_type " + std::to_string(t);
    const double colour = colourOf(packing, type.offset[0], -type.offset[1]);
    if (!(std::abs(colour - std::round(colour)) < 1e-3))
      return bad(ErrorCode::Format, key + " offset", "not a lens of the lattice");
    if (!(type.minVirtualDepth > 0 && type.minVirtualDepth <= type.maxVirtualDepth))
      return bad(ErrorCode::Format, key + " depth_range", "expected 0 < min <= max");
    coloursSeen |= 1 << colourClass(colour);
  }
  if (d.lensTypes.size() == 3 && coloursSeen != 7)
    return bad(ErrorCode::Format, "lens_type", "two lens types share lenses (their offsets do not tell them apart)");
  if (width < 3 * d.diameter || height < 3 * d.diameter)
    return makeError(ErrorCode::Usage, where + ": the image (" + std::to_string(width) + "x" + std::to_string(height) +
                                           ") is smaller than three micro-images of " +
                                           io::shortestNumber(std::round(d.diameter * 100) / 100) + " pixels across");
  // Raytrix: the reference lens from the image's centre, y up; the rotation counter-clockwise.
  const std::array<double, 2> centre{0.5 * width + d.offset[0], 0.5 * height - d.offset[1]};
  if (!(centre[0] >= 0 && centre[0] <= width && centre[1] >= 0 && centre[1] <= height))
    return bad(ErrorCode::Format, "offset",
               "puts the reference lens outside the " + std::to_string(width) + "x" + std::to_string(height) +
                   " image: not this image's calibration");
  FocusedCalibration calibration = focusedGrid(centre, d.diameter, packing, -d.rotation, width, height);
  calibration.borderPx = d.lensBorder;
  calibration.totalCoveringPlane = d.tcp;
  calibration.lensTypes = d.lensTypes.empty() ? std::vector<LensType>{LensType{}} : d.lensTypes;
  calibration.orientation = d.orientation;
  calibration.optics = d.optics;
  return calibration;
}

RayCalibDocument documentFromCalibration(const FocusedCalibration& calibration) {
  RayCalibDocument d;
  const auto centre = calibration.grid.latticeCentre(calibration.referenceLens[0], calibration.referenceLens[1]);
  d.offset = {centre[0] - 0.5 * calibration.imageWidth, 0.5 * calibration.imageHeight - centre[1]};
  d.diameter = calibration.diameterPx();
  d.rotation = -calibration.grid.rotationRad;
  d.lensBorder = calibration.borderPx;
  d.tcp = calibration.totalCoveringPlane;
  if (calibration.grid.packing == Packing::Square) d.lensBaseY = {0, -1};
  if (calibration.lensTypes.size() == 3 && calibration.grid.packing == Packing::Hexagonal)
    d.subGridBase = std::array<double, 2>{3, -kSqrt3};  // Raytrix's: two steps of the same type
  d.lensTypes = calibration.lensTypes;
  d.orientation = calibration.orientation;
  d.optics = calibration.optics;
  return d;
}

}  // namespace focused_detail

Result<FocusedCalibration> readFocusedCalibration(const std::filesystem::path& path, int width, int height) {
  const std::string extension = io::lowerExtension(path);
  if (extension != ".xml" && extension != ".json")
    return makeError(ErrorCode::Usage, path.string() + ": expected a calibration file (.xml or .json)");
  LFCAM_ASSIGN_OR_RETURN(const std::string text, readTextFile(path, "a calibration file (.xml or .json)"));
  return extension == ".xml" ? parseRayCalibXml(text, path.string(), width, height)
                             : parseFocusedCalibrationJson(text, path.string(), width, height);
}

Status writeFocusedCalibration(const std::filesystem::path& path, const FocusedCalibration& calibration) {
  const std::string extension = io::lowerExtension(path);
  if (extension != ".xml" && extension != ".json")
    return makeError(ErrorCode::Usage, path.string() + ": expected a calibration file name ending .xml or .json");
  return writeTextFileAtomically(path,
                                 extension == ".xml" ? rayCalibXml(calibration) : focusedCalibrationJson(calibration));
}

}  // namespace lfcam
