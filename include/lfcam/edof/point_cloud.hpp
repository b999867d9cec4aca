// The scene as a coloured point cloud: each pixel of a disparity map placed in 3D at its metric
// distance (depth.hpp, distanceFromDisparity), coloured by the centre view, with its confidence.
//
// Frame: the main lens's centre at the origin, x right, y down, z along the optical axis away from
// the camera (the simulator's scene frame, scene.hpp, and OpenCV's camera frame), in mm. The ray
// through the centre of the lens is not bent (thin lens), so a pixel's point is its position on
// the microlens plane, (s + 0.5 - ns / 2, t + 0.5 - nt / 2) x spatialStepMm, scaled by z /
// lensToMicrolensMm; for the HCI benchmark (hci_parameters.hpp) that is its pinhole camera.
//
// File: PLY (binary, little-endian), vertices only, with the properties x y z (float, mm), red
// green blue (uchar, sRGB) and confidence (float, in [0, 1]), which MeshLab and Open3D read.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct PointCloud {
  std::vector<std::array<float, 3>> positions;      // mm, in the frame above
  std::vector<std::array<std::uint8_t, 3>> colors;  // sRGB codes
  std::vector<float> confidences;                   // in [0, 1]
};

// The points of `disparity` (ns x nt, pixels per view step) whose confidence is at least
// `minConfidence` and whose distance is finite (nearer than infinity), coloured by the centre view
// of `lightField`, whose optics give the distances. Usage error without optics or focal length, or
// for maps of another size than the light field's views.
Result<PointCloud> pointCloudFromDepth(const LightField& lightField, const Image& disparity, const Image& confidence,
                                       double minConfidence = 0);

// Writes `cloud` as a binary PLY file, atomically (atomic_file.hpp): on failure no file is left.
Status writePly(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace lfcam
