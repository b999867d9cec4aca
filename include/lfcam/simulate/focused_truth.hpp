// The ground truth of a simulated focused plenoptic camera (camera_model.hpp's
// typeFocalLengthsMm and toSensorMm): its calibration as the raw shows it, and, on a photograph's
// frame, the ideal all-in-focus photograph and the virtual depth of every pixel.
#pragma once

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/focused/focused_calibration.hpp"
#include "lfcam/focused/photo_frame.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/scene.hpp"

namespace lfcam {

// The micro-image grid of the raw (gridFromCamera), the reference lens nearest the image's
// centre, the lens types with their offsets in Raytrix's frame and the virtual depths each images
// within two pixels of blur, the total covering plane, and the micro-images' orientation (from
// the focal lengths against toSensorMm). Usage error without microlenses or with the sensor at the
// microlenses' focus (a plenoptic 1.0 camera).
Result<FocusedCalibration> focusedCalibrationFromCamera(const CameraModel& camera);

// The image-measured virtual depth (FocusedCalibration's v: micro-images D pixels apart see a
// point D / v apart) of a scene point `depthMm` in front of the main lens: (a / b) (F + b) / (F - a),
// a the distance of its image in front of the microlenses (negative behind), b toSensorMm, F the
// microlenses' distance from the main lens; positive when the micro-images are the camera's way
// up, +infinity for a point imaged on the microlenses.
double focusedVirtualDepth(const CameraModel& camera, double depthMm);

// Its inverse: the distance in front of the main lens (mm) of the points at virtual depth v.
double depthOfFocusedVirtualDepth(const CameraModel& camera, double virtualDepth);

struct FocusedTruth {
  Image allInFocus;    // RGB: the scene's radiance along the main lens's central ray, box-filtered
  Image virtualDepth;  // one channel: focusedVirtualDepth of the surface the central ray meets
};

// On `frame` (of focusedCalibrationFromCamera's calibration): each pixel the mean of boxSamples^2
// stratified points of its area, the virtual depth at its centre.
Result<FocusedTruth> focusedTruth(const Scene& scene, const CameraModel& camera, const FocusedPhotoFrame& frame,
                                  int boxSamples = 4);

}  // namespace lfcam
