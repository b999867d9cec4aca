// whites.json (white_database_json.hpp, white_database.hpp).
#include <fstream>

#include <nlohmann/json.hpp>

#include "calibrate/white_database_json.hpp"
#include "core/atomic_file.hpp"
#include "core/json_reader.hpp"

namespace lfcam {

namespace {

namespace fs = std::filesystem;
constexpr const char* kFormatName = "lfcam-white-database";
constexpr int kFormatVersion = 1;
// Raised whenever calibrateGrid finds other grids than before, so that older caches are refused.
constexpr int kCalibrationRevision = 1;

fs::path folderOf(const fs::path& index) { return index.parent_path().empty() ? "." : index.parent_path(); }

std::string relativeToIndex(const fs::path& path, const fs::path& index) {
  const fs::path relative =
      fs::absolute(path).lexically_normal().lexically_relative(fs::absolute(folderOf(index)).lexically_normal());
  return !relative.empty() && *relative.begin() != ".." ? relative.generic_string() : fs::absolute(path).string();
}

}  // namespace

std::string whiteCalibrationVersion() {
  return std::string("lfcam ") + LFCAM_VERSION + ", calibration " + std::to_string(kCalibrationRevision);
}

Status writeWhiteDatabase(const WhiteDatabase& database) {
  nlohmann::json whites = nlohmann::json::array();
  for (const WhiteRecord& white : database.whites) {
    const CameraSetting& s = white.setting;
    nlohmann::json entry = {{"name", white.name},
                            {"serial", s.serial},
                            {"model", s.model},
                            {"firmware", s.firmware},
                            {"metadata_keys", s.metadataKeys},
                            {"zoom_step", *s.zoomStep},
                            {"focus_step", *s.focusStep},
                            {"size", {white.width, white.height}},
                            {"white", relativeToIndex(white.white, database.index)},
                            {"grid", relativeToIndex(white.grid, database.index)},
                            {"grid_rms_residual_px", white.residualPx}};
    if (s.exposureS) entry["exposure_s"] = *s.exposureS;
    whites.push_back(std::move(entry));
  }
  const nlohmann::json json = {
      {"format", kFormatName}, {"version", kFormatVersion}, {"made_by", database.madeBy}, {"whites", whites}};
  return writeFileAtomically(database.index, [&](const fs::path& temporary) -> Status {
    std::ofstream out(temporary);
    out << json.dump(1) << "\n";
    if (!out.flush()) return makeError(ErrorCode::Io, database.index.string() + ": cannot write");
    return {};
  });
}

Result<WhiteDatabase> readWhiteDatabase(const fs::path& index) {
  using json_reader::JsonObject;
  const std::string where = index.string();
  std::ifstream in(index);
  if (!in) return makeError(ErrorCode::Io, where + ": cannot open the white-image database");
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded() || !json.is_object() || json.value("format", "") != kFormatName)
    return makeError(ErrorCode::Format, where + ": not a white-image database (made by `lfcam whites index`)");
  JsonObject root(json, where, "");
  root.markSeen("format");
  int version = 0;
  WhiteDatabase database{.index = index};
  LFCAM_TRY(root.integer("version", version, 1, 1000));
  if (version != kFormatVersion)
    return makeError(ErrorCode::Unsupported, where + ": white-image database version " + std::to_string(version) +
                                                 " (this lfcam reads " + std::to_string(kFormatVersion) + ")");
  LFCAM_TRY(root.string("made_by", database.madeBy));
  if (database.madeBy != whiteCalibrationVersion())
    return makeError(ErrorCode::Format, where + ": its grids were made by " + database.madeBy + ", this is " +
                                            whiteCalibrationVersion() + ": run `lfcam whites index` again");
  if (!root.has("whites") || !root.at("whites").is_array())
    return makeError(ErrorCode::Format, where + ": whites: expected an array");
  root.markSeen("whites");
  const nlohmann::json& whites = root.at("whites");
  for (std::size_t k = 0; k < whites.size(); ++k) {
    JsonObject entry(whites[k], where, "whites[" + std::to_string(k) + "]");
    LFCAM_TRY(entry.requireObject());
    WhiteRecord white;
    CameraSetting& s = white.setting;
    std::string whitePath, gridPath;
    double zoom = 0, focus = 0;
    std::array<double, 2> size{0, 0};
    LFCAM_TRY(entry.string("name", white.name));
    LFCAM_TRY(entry.string("serial", s.serial));
    LFCAM_TRY(entry.string("model", s.model));
    LFCAM_TRY(entry.string("firmware", s.firmware));
    LFCAM_TRY(entry.string("metadata_keys", s.metadataKeys));
    LFCAM_TRY(entry.number("zoom_step", zoom, -1e9, 1e9));
    LFCAM_TRY(entry.number("focus_step", focus, -1e9, 1e9));
    LFCAM_TRY(entry.optionalNumber("exposure_s", s.exposureS, 0, 1e6));
    LFCAM_TRY(entry.numbers("size", size, 1, 100000));
    LFCAM_TRY(entry.string("white", whitePath));
    LFCAM_TRY(entry.string("grid", gridPath));
    LFCAM_TRY(entry.number("grid_rms_residual_px", white.residualPx, 0, 1e6));
    LFCAM_TRY(entry.noUnknownKeys());
    for (const char* key : {"zoom_step", "focus_step", "size", "white", "grid"})
      if (!entry.has(key)) return entry.fail(entry.keyPath(key), "missing");
    s.zoomStep = zoom;
    s.focusStep = focus;
    white.width = int(size[0]);
    white.height = int(size[1]);
    white.white = folderOf(index) / whitePath;  // an absolute path stays itself
    white.grid = folderOf(index) / gridPath;
    database.whites.push_back(std::move(white));
  }
  LFCAM_TRY(root.noUnknownKeys());
  return database;
}

}  // namespace lfcam
