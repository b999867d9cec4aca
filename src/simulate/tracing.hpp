// Inside the simulator: the scene prepared for tracing (plane frames precomputed).
#pragma once

#include <cmath>
#include <vector>

#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/scene.hpp"

namespace lfcam::simulate_detail {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(const Vec3& a, double k) { return {a.x * k, a.y * k, a.z * k}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 normalize(const Vec3& a) { return a * (1.0 / std::sqrt(dot(a, a))); }

struct Hit {
  Rgb radiance{0, 0, 0};
  double depth = 0;  // z of the hit, mm; +infinity for the background
  double t = 0;
};

struct PreparedPlane {
  const Plane* plane = nullptr;
  Vec3 centre, right, down, normal;
  double halfWidth = 0, halfHeight = 0;
};

class PreparedScene {
 public:
  // `scene` must outlive this object.
  PreparedScene(const Scene& scene, const CameraModel& camera);
  // The first surface along origin + t direction, t > 0 (object space); a reflective one adds
  // what it mirrors, `bounces` deep.
  Hit trace(const Vec3& origin, const Vec3& direction, int bounces = 1) const;
  // The ray that leaves the main lens at (lensX, lensY) and, on the image side, passes through
  // (imageX, imageY) at the distance F where the focus plane is imaged.
  Hit traceThroughLens(double lensX, double lensY, double imageX, double imageY) const;

 private:
  std::vector<PreparedPlane> planes;
  std::vector<PointLight> lights;
  Rgb background;
  double focusDistance, imageDistance;
};

}  // namespace lfcam::simulate_detail
