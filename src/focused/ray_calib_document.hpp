// The contents of a Raytrix calibration (RayCalibData), as its XML and lfcam's JSON of the same
// keys both hold them, before they become a FocusedCalibration for an image of a given size.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam::focused_detail {

struct RayCalibDocument {
  std::array<double, 2> offset{0, 0};  // reference lens centre from the image centre, pixels, y up
  double diameter = 0;                 // pixels
  double rotation = 0;                 // radians, counter-clockwise with y up
  double lensBorder = 0;               // pixels
  std::optional<double> tcp;           // virtual depth
  std::array<double, 2> lensBaseX{1, 0}, lensBaseY{0.5, -0.8660254037844386};  // lens units, y up
  std::optional<std::array<double, 2>> subGridBase;                            // lens units, y up
  std::vector<LensType> lensTypes;
  MicroImageOrientation orientation = MicroImageOrientation::Upright;
  std::optional<FocusedOptics> optics;
};

// Checks what lfcam can use (one of the two lattices, sizes, lens types telling lenses apart) and
// places the grid on a width x height image; errors name `where` and the key.
Result<FocusedCalibration> calibrationFromDocument(const RayCalibDocument& document, const std::string& where,
                                                   int width, int height);
RayCalibDocument documentFromCalibration(const FocusedCalibration& calibration);

const char* orientationName(MicroImageOrientation orientation);
std::optional<MicroImageOrientation> orientationFromName(const std::string& name);

}  // namespace lfcam::focused_detail
