// LensletGrid: the lattice formula of lenslet_grid.hpp and its grid.json form (docs/formats.md).
#include "lfcam/calibrate/lenslet_grid.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "calibrate/calibrate_internal.hpp"
#include "calibrate/grid_json.hpp"
#include "core/atomic_file.hpp"
#include "core/json_reader.hpp"
#include "core/text_file.hpp"

namespace lfcam {

namespace {
constexpr const char* kFormatName = "lfcam-lenslet-grid";
constexpr int kFormatVersion = 1;
}  // namespace

std::array<double, 2> LensletGrid::latticeCentre(int i, int j) const {
  const bool shifted = packing == Packing::Hexagonal && ((j + hexParity) & 1);
  const double a = (i + (shifted ? 0.5 : 0.0)) * pitchX, b = j * pitchY;
  const double c = std::cos(rotationRad), s = std::sin(rotationRad);
  return {origin[0] + c * a - s * b, origin[1] + s * a + c * b};
}

std::array<double, 2> LensletGrid::centre(int i, int j) const {
  std::array<double, 2> p = latticeCentre(i, j);
  if (warp.columns < 2) return p;
  // Mesh coordinates, clamped: microlenses beyond the grid keep its edge's offset.
  const double u = std::clamp(double(i) * (warp.columns - 1) / std::max(1, columns - 1), 0.0, warp.columns - 1.0);
  const double v = std::clamp(double(j) * (warp.rows - 1) / std::max(1, rows - 1), 0.0, warp.rows - 1.0);
  const int p0 = std::min(int(u), warp.columns - 2), q0 = std::min(int(v), warp.rows - 2);
  const double fu = u - p0, fv = v - q0;
  for (int axis = 0; axis < 2; ++axis) {
    auto at = [&](int dp, int dq) { return warp.offsets[std::size_t(q0 + dq) * warp.columns + p0 + dp][axis]; };
    p[axis] += (1 - fv) * ((1 - fu) * at(0, 0) + fu * at(1, 0)) + fv * ((1 - fu) * at(0, 1) + fu * at(1, 1));
  }
  return p;
}

namespace {

nlohmann::json warpToJson(const GridWarp& warp) {
  nlohmann::json offsets = nlohmann::json::array();
  for (const auto& o : warp.offsets) offsets.push_back({o[0], o[1]});
  return {{"columns", warp.columns}, {"rows", warp.rows}, {"offsets_px", offsets}};
}

}  // namespace

nlohmann::json gridToJson(const LensletGrid& grid) {
  nlohmann::json json = {{"format", kFormatName},
                         {"version", kFormatVersion},
                         {"packing", packingName(grid.packing)},
                         {"pitch_x_px", grid.pitchX},
                         {"pitch_y_px", grid.pitchY},
                         {"rotation_deg", grid.rotationRad * 180.0 / M_PI},
                         {"origin_px", {grid.origin[0], grid.origin[1]}},
                         {"columns", grid.columns},
                         {"rows", grid.rows},
                         {"hex_parity", grid.hexParity},
                         {"fit",
                          {{"lenslets_found", grid.fit.lensletsFound},
                           {"lenslets_used", grid.fit.lensletsUsed},
                           {"rms_residual_px", grid.fit.rmsResidualPx},
                           {"max_residual_px", grid.fit.maxResidualPx},
                           {"self_calibrated", grid.fit.selfCalibrated}}}};
  if (grid.warp.columns > 0) json["warp"] = warpToJson(grid.warp);
  return json;
}

Result<LensletGrid> gridFromJson(const nlohmann::json& json, const std::string& where) {
  using json_reader::JsonObject;
  JsonObject root(json, where, "");
  LFCAM_TRY(root.requireObject());
  std::string format, packing;
  LFCAM_TRY(root.string("format", format));
  if (format != kFormatName) return root.fail("format", "expected \"" + std::string(kFormatName) + "\"");
  int version = 0;
  LFCAM_TRY(root.integer("version", version, 1, 1000));
  if (version != kFormatVersion)
    return makeError(ErrorCode::Unsupported, where + ": version: " + std::to_string(version) + " is not supported");
  LensletGrid grid;
  LFCAM_TRY(root.string("packing", packing));
  if (packing == "square")
    grid.packing = Packing::Square;
  else if (packing == "hexagonal")
    grid.packing = Packing::Hexagonal;
  else
    return root.fail("packing", "expected \"square\" or \"hexagonal\"");
  for (const char* key : {"pitch_x_px", "pitch_y_px", "rotation_deg", "origin_px", "columns", "rows"})
    if (!root.has(key)) return root.fail(key, "missing");
  double rotationDeg = 0;
  LFCAM_TRY(root.number("pitch_x_px", grid.pitchX, 0, 1e5, true));
  LFCAM_TRY(root.number("pitch_y_px", grid.pitchY, 0, 1e5, true));
  LFCAM_TRY(root.number("rotation_deg", rotationDeg, -180, 180));
  grid.rotationRad = rotationDeg * M_PI / 180.0;
  LFCAM_TRY(root.numbers("origin_px", grid.origin, -1e7, 1e7));
  LFCAM_TRY(root.integer("columns", grid.columns, 1, 1000000));
  LFCAM_TRY(root.integer("rows", grid.rows, 1, 1000000));
  LFCAM_TRY(root.integer("hex_parity", grid.hexParity, 0, 1));
  if (root.has("warp")) {
    JsonObject warp(root.at("warp"), where, "warp");
    LFCAM_TRY(warp.requireObject());
    LFCAM_TRY(warp.integer("columns", grid.warp.columns, 2, 10000));
    LFCAM_TRY(warp.integer("rows", grid.warp.rows, 2, 10000));
    const auto& offsets = warp.at("offsets_px");
    warp.markSeen("offsets_px");
    const std::size_t count = std::size_t(grid.warp.columns) * grid.warp.rows;
    if (!offsets.is_array() || offsets.size() != count)
      return warp.fail(warp.keyPath("offsets_px"), "expected " + std::to_string(count) + " [dx, dy] pairs");
    for (const auto& pair : offsets) {
      if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number() || !pair[1].is_number())
        return warp.fail(warp.keyPath("offsets_px"), "expected [dx, dy] pairs of numbers");
      const double dx = pair[0].get<double>(), dy = pair[1].get<double>();
      if (!(std::abs(dx) < 1e4 && std::abs(dy) < 1e4))
        return warp.fail(warp.keyPath("offsets_px"), "an offset beyond 1e4 px");
      grid.warp.offsets.push_back({dx, dy});
    }
    LFCAM_TRY(warp.noUnknownKeys());
  }
  root.markSeen("warp");
  if (root.has("fit")) {
    JsonObject fit(root.at("fit"), where, "fit");
    LFCAM_TRY(fit.requireObject());
    LFCAM_TRY(fit.integer("lenslets_found", grid.fit.lensletsFound, 0, 2000000000));
    LFCAM_TRY(fit.integer("lenslets_used", grid.fit.lensletsUsed, 0, 2000000000));
    LFCAM_TRY(fit.number("rms_residual_px", grid.fit.rmsResidualPx, 0, 1e9));
    LFCAM_TRY(fit.number("max_residual_px", grid.fit.maxResidualPx, 0, 1e9));
    // Optional: grids written before it were calibrated from white or pinhole images.
    LFCAM_TRY(fit.boolean("self_calibrated", grid.fit.selfCalibrated));
    LFCAM_TRY(fit.noUnknownKeys());
  }
  root.markSeen("fit");
  LFCAM_TRY(root.noUnknownKeys());
  return grid;
}

Result<nlohmann::json> calibrate_detail::readJsonFile(const std::filesystem::path& path, const char* expected) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return makeError(ErrorCode::Usage, path.string() + ": is a folder, expected " + expected);
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorCode::Io, path.string() + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return makeError(ErrorCode::Io, path.string() + ": cannot read");
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {  // syntax, and numbers out of range (1e999)
    std::string message = e.what();
    const auto at = message.find("parse error");
    if (at != std::string::npos) message = message.substr(at);
    return makeError(ErrorCode::Format, path.string() + ": not valid JSON: " + message);
  }
}

Result<LensletGrid> readGrid(const std::filesystem::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto json, calibrate_detail::readJsonFile(path, "a grid file (.json)"));
  return gridFromJson(json, path.string());
}

Status writeGrid(const std::filesystem::path& path, const LensletGrid& grid) {
  return writeTextFileAtomically(path, gridToJson(grid).dump(2) + "\n");
}

}  // namespace lfcam
