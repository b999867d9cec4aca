// `lfcam info FILE.lfp`: a Lytro container's sections, what each holds, and its frame metadata.
#include "lytro_info.hpp"

#include <cstdio>

#include "raw_io/lytro_contents.hpp"

namespace lfcam::cli {

Status printLytroInfo(const std::string& path, bool asJson, const std::optional<WhiteNote>& white) {
  LFCAM_ASSIGN_OR_RETURN(auto container, readLytroContainer(path));
  const LytroContents contents = describeLytroContainer(container);
  if (asJson) {
    nlohmann::json sections = nlohmann::json::array();
    for (const LytroItem& item : contents.items) {
      nlohmann::json s = {{"type", lytroSectionKindName(item.section->kind)},
                          {"name", item.section->name},
                          {"offset", item.section->offset},
                          {"bytes", item.section->payload.size()},
                          {"kind", lytroItemKindName(item.kind)},
                          {"role", item.role}};
      if (item.width) s["size"] = {item.width, item.height};
      if (item.lambda) s["lambda"] = *item.lambda;
      sections.push_back(s);
    }
    nlohmann::json out = {
        {"path", path}, {"format", "lytro-container"}, {"sections", sections}, {"summary", contents.summary}};
    if (white) out["white"] = white->json;
    std::printf("%s\n", out.dump(2).c_str());
    return {};
  }
  std::printf("%s: Lytro container, %zu sections\n", path.c_str(), container.sections.size());
  if (contents.summary.contains("frame")) {
    const nlohmann::json& f = contents.summary["frame"];
    std::printf("  frame: %s%s%d x %d, %d-bit, %s, black %g, white %g\n", f.value("camera", "").c_str(),
                f.contains("camera") ? ", " : "", f["sensor"][0].get<int>(), f["sensor"][1].get<int>(),
                f["bits_per_pixel"].get<int>(), f["bayer"].get<std::string>().c_str(), f["black_level"].get<double>(),
                f["white_level"].get<double>());
    if (f.contains("lenslet"))
      std::printf("  microlenses: %s, pitch %.4f px, rotation %.6f rad, offset (%.3f, %.3f) px\n",
                  f["lenslet"]["packing"].get<std::string>().c_str(), f["lenslet"]["pitch_px"].get<double>(),
                  f["lenslet"]["rotation_rad"].get<double>(), f["lenslet"]["offset_px"][0].get<double>(),
                  f["lenslet"]["offset_px"][1].get<double>());
  }
  if (white) std::printf("  white: %s\n", white->text.c_str());
  for (const LytroItem& item : contents.items) {
    std::printf("  %s %-45s %9zu bytes  %s", lytroSectionKindName(item.section->kind),
                item.section->name.empty() ? "-" : item.section->name.c_str(), item.section->payload.size(),
                item.role.c_str());
    if (item.width) std::printf(", %d x %d", item.width, item.height);
    if (item.lambda) std::printf(", lambda %g", *item.lambda);
    std::printf("\n");
  }
  return {};
}

}  // namespace lfcam::cli
