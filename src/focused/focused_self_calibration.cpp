#include "lfcam/focused/focused_self_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/focused/envelope_lattice.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/lens_types_from_sharpness.hpp"
#include "lfcam/focused/micro_image_sharpness.hpp"

namespace lfcam {

namespace {

// The grid's lattice from the lens in its middle: e2 is the step to the next row.
MicroImageLattice latticeOf(const LensletGrid& grid) {
  const double c = std::cos(grid.rotationRad), s = std::sin(grid.rotationRad);
  const double across = grid.packing == Packing::Hexagonal ? grid.pitchX / 2 : 0;
  return {.reference = grid.latticeCentre(grid.columns / 2, grid.rows / 2),
          .e1 = {c * grid.pitchX, s * grid.pitchX},
          .e2 = {c * across - s * grid.pitchY, s * across + c * grid.pitchY}};
}

double meanOf(const Image& image) {
  const auto& p = image.pixels();
  return p.empty() ? 0 : std::accumulate(p.begin(), p.end(), 0.0) / double(p.size());
}

}  // namespace

Result<FocusedSelfCalibration> calibrateFocusedCapture(const Image& capture, const Image* white,
                                                       const FocusedSelfCalibrationOptions& options,
                                                       const std::string& where) {
  if (white && (white->width() != capture.width() || white->height() != capture.height()))
    return makeError(ErrorCode::Usage, where + ": the white image is " + std::to_string(white->width()) + "x" +
                                           std::to_string(white->height()) + ", the capture " +
                                           std::to_string(capture.width()) + "x" + std::to_string(capture.height()));
  CalibrationOptions lattice;
  lattice.target = white ? CalibrationTarget::White : CalibrationTarget::Scene;
  LFCAM_ASSIGN_OR_RETURN(const Calibration found, calibrateGridDetailed(white ? *white : capture, lattice,
                                                                        white ? where + " (its white image)" : where));
  const LensletGrid& grid = found.grid;
  FocusedSelfCalibration result;
  result.gridFit = grid.fit;
  // A white image's lenses each give their centre of symmetry (0.02 px on the simulator's); a
  // capture's are biased by what they show (pixels, coherently over tens of lenses), so its lattice
  // is refined by the phase of its envelope (0.3-0.4 px: the envelope's own tilt within each lens).
  const MicroImageLattice refined =
      white ? latticeOf(grid) : refineLatticeByEnvelope(capture, latticeOf(grid), grid.packing);
  // Raytrix's model has one diameter: the mean of the two basis vectors' lengths.
  const double diameter = 0.5 * (std::hypot(refined.e1[0], refined.e1[1]) + std::hypot(refined.e2[0], refined.e2[1]));
  FocusedCalibration& calibration = result.calibration;
  calibration = focusedGrid(refined.reference, diameter, grid.packing, std::atan2(refined.e1[1], refined.e1[0]),
                            capture.width(), capture.height());
  calibration.borderPx = options.borderPx;
  calibration.lensTypes = {LensType{}};
  // A capture's lenses show their centres by their vignetting. Without it (a capture devignetted
  // by the camera's software, as the R42 crop is: 35 of 891 lenses) the lattice found is the
  // period of what the lenses show, D (1 - 1 / v), not theirs; the simulator's give 60 % or more.
  const int lenses = calibration.grid.columns * calibration.grid.rows;
  if (!white && grid.fit.lensletsUsed < lenses / 5)
    return makeError(ErrorCode::Format, where + ": no micro-image lattice to be found in it (only " +
                                            std::to_string(grid.fit.lensletsUsed) + " of " + std::to_string(lenses) +
                                            " micro-images show their vignetting: devignetted?); give its "
                                            "calibration or a white image");

  // Coarse maps: a few photograph pixels a micro-image, candidates up to half its diameter.
  FocusedDepthRequest request;
  request.pixelsPerLens = std::max(2.0, std::round(diameter / 6));
  request.maxVirtualDepth = std::max(4.0, diameter / 2);
  auto depthFor = [&](MicroImageOrientation orientation) {
    FocusedCalibration c = calibration;
    c.orientation = orientation;
    return estimateFocusedDepth(capture, c, request);
  };
  std::optional<FocusedDepth> depth;
  if (options.orientation) {
    calibration.orientation = *options.orientation;
    LFCAM_ASSIGN_OR_RETURN(depth, depthFor(*options.orientation));
  } else {
    LFCAM_ASSIGN_OR_RETURN(FocusedDepth upright, depthFor(MicroImageOrientation::Upright));
    LFCAM_ASSIGN_OR_RETURN(FocusedDepth inverted, depthFor(MicroImageOrientation::Inverted));
    result.confidenceUpright = meanOf(upright.confidence);
    result.confidenceInverted = meanOf(inverted.confidence);
    const bool isUpright = result.confidenceUpright >= result.confidenceInverted;
    calibration.orientation = isUpright ? MicroImageOrientation::Upright : MicroImageOrientation::Inverted;
    depth = std::move(isUpright ? upright : inverted);
  }
  const LensTypeFinding types = lensTypesFromSharpness(
      calibration, {.sharpness = microImageSharpness(capture, calibration), .virtualDepth = depth->lensVirtualDepth});
  calibration.lensTypes = types.lensTypes;
  result.lensTypeSpread = types.spread;
  return result;
}

}  // namespace lfcam
