#include "lfcam/edof/point_cloud.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "core/atomic_file.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {

namespace fs = std::filesystem;

Result<PointCloud> pointCloudFromDepth(const LightField& lightField, const Image& disparity, const Image& confidence,
                                       double minConfidence) {
  const auto& optics = lightField.metadata.optics;
  if (!optics || !optics->focalLengthMm || !(optics->lensToMicrolensMm > 0) || !(optics->spatialStepMm > 0))
    return makeError(ErrorCode::Usage,
                     "point cloud: the light field carries no optics with a focal length, so no metric positions");
  const int ns = lightField.ns(), nt = lightField.nt();
  for (const Image* map : {&disparity, &confidence})
    if (map->width() != ns || map->height() != nt || map->channels() != 1)
      return makeError(ErrorCode::Usage, "point cloud: the depth maps are " + std::to_string(map->width()) + "x" +
                                             std::to_string(map->height()) + ", the views " + std::to_string(ns) + "x" +
                                             std::to_string(nt));
  const Image centre = lightField.subApertureImage((lightField.nu() - 1) / 2, (lightField.nv() - 1) / 2);
  const int channels = centre.channels();
  auto code = [](float linear) {
    return std::uint8_t(std::lround(255.0f * srgbFromLinear(std::clamp(linear, 0.0f, 1.0f))));
  };
  // Microlens-plane position (mm) per pixel over the lens-to-microlens distance: z times it is the point.
  const double scale = optics->spatialStepMm / optics->lensToMicrolensMm;
  PointCloud cloud;
  for (int t = 0; t < nt; ++t)
    for (int s = 0; s < ns; ++s) {
      const float sure = confidence.at(s, t, 0);
      if (!(sure >= minConfidence)) continue;
      const auto z = distanceFromDisparity(*optics, disparity.at(s, t, 0));
      if (!z || !std::isfinite(*z)) continue;
      cloud.positions.push_back(
          {float((s + 0.5 - 0.5 * ns) * scale * *z), float((t + 0.5 - 0.5 * nt) * scale * *z), float(*z)});
      const float r = centre.at(s, t, 0), g = centre.at(s, t, std::min(1, channels - 1)),
                  b = centre.at(s, t, std::min(2, channels - 1));
      cloud.colors.push_back({code(r), code(g), code(b)});
      cloud.confidences.push_back(sure);
    }
  return cloud;
}

namespace {

void appendLittleEndian(std::string& bytes, float value) {
  const auto bits = std::bit_cast<std::uint32_t>(value);
  for (int k = 0; k < 4; ++k) bytes.push_back(char((bits >> (8 * k)) & 0xff));
}

}  // namespace

Status writePly(const fs::path& path, const PointCloud& cloud) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\ncomment lfcam depth: mm, x right, y down, z away\n"
      "element vertex " +
      std::to_string(cloud.positions.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
      "property uchar green\nproperty uchar blue\nproperty float confidence\nend_header\n";
  bytes.reserve(bytes.size() + cloud.positions.size() * 19);
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    for (float c : cloud.positions[i]) appendLittleEndian(bytes, c);
    for (std::uint8_t c : cloud.colors[i]) bytes.push_back(char(c));
    appendLittleEndian(bytes, cloud.confidences[i]);
  }
  return writeFileAtomically(path, [&](const fs::path& temporary) -> Status {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot create the file: " + std::strerror(errno));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot write the point cloud (disk full?)");
    return {};
  });
}

}  // namespace lfcam
