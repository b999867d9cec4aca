#include "photo/focal_stack_output.hpp"

#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/parallel.hpp"

namespace lfcam {

namespace {
// Slices rendered but not yet written, each one photograph's memory.
constexpr std::size_t kSlicesWaitingToBeWritten = 4;
}  // namespace

std::string stackSliceName(int index, const std::string& extension) {
  char name[64];
  std::snprintf(name, sizeof name, "slice_%03d.%s", index, extension.c_str());
  return name;
}

Status writeFocalStack(const std::filesystem::path& folder, const LightField& lightField, const ResolvedPhoto& camera,
                       const std::vector<double>& slopes, const std::string& extension,
                       const ImageWriteOptions& writeOptions, const std::function<void(double)>& progress) {
  const auto& optics = lightField.metadata.optics;
  return writeFolderAtomically(folder, [&](const std::filesystem::path& temporary) -> Status {
    nlohmann::json slices = nlohmann::json::array();
    // Each slice is encoded and written while the next is rendered; a few wait at most.
    BackgroundTasks writes(kSlicesWaitingToBeWritten);
    LFCAM_TRY(renderPhotos(lightField, camera, slopes, [&](int index, double slope, Image&& photo) -> Status {
      const std::string name = stackSliceName(index, extension);
      nlohmann::json slice{{"file", name}, {"slope", slope}};
      if (optics) slice["alpha"] = optics->alphaFromSlope(slope);
      slices.push_back(slice);
      progress(double(index + 1) / double(slopes.size()));
      auto shared = std::make_shared<Image>(std::move(photo));
      return writes.add([&, shared, name] { return writeImage(temporary / name, *shared, writeOptions); });
    }));
    LFCAM_TRY(writes.wait());
    std::ofstream out(temporary / "stack.json");
    out << nlohmann::json{{"slices", slices}}.dump(2) << "\n";
    if (!out) return makeError(ErrorCode::Io, (folder / "stack.json").string() + ": cannot write");
    return {};
  });
}

}  // namespace lfcam
