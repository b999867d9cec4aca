#include "focal_stack_output.hpp"

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "lfcam/atomic_file.hpp"

namespace lfcam::cli {

std::string stackSliceName(int index, const std::string& extension) {
  char name[64];
  std::snprintf(name, sizeof name, "slice_%03d.%s", index, extension.c_str());
  return name;
}

Status writeFocalStack(const std::filesystem::path& folder, const LightField& lightField, const PhotoSetup& camera,
                       const std::vector<double>& slopes, const std::string& extension,
                       const ImageWriteOptions& writeOptions, const std::function<void(double)>& progress) {
  const auto& optics = lightField.metadata.optics;
  return writeFolderAtomically(folder, [&](const std::filesystem::path& temporary) -> Status {
    nlohmann::json slices = nlohmann::json::array();
    LFCAM_TRY(renderPhotos(lightField, camera, slopes, [&](int index, double slope, Image&& photo) -> Status {
      const std::string name = stackSliceName(index, extension);
      nlohmann::json slice{{"file", name}, {"slope", slope}};
      if (optics) slice["alpha"] = optics->alphaFromSlope(slope);
      slices.push_back(slice);
      progress(double(index + 1) / double(slopes.size()));
      return writeImage(temporary / name, photo, writeOptions);
    }));
    std::ofstream out(temporary / "stack.json");
    out << nlohmann::json{{"slices", slices}}.dump(2) << "\n";
    if (!out) return makeError(ErrorCode::Io, (folder / "stack.json").string() + ": cannot write");
    return {};
  });
}

}  // namespace lfcam::cli
