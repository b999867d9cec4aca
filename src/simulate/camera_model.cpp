// The camera model: derived geometry, validation, and its JSON form.
#include "lfcam/simulate/camera_model.hpp"

#include <cmath>
#include <limits>

#include "core/json_reader.hpp"
#include "core/memory_budget.hpp"
#include "simulate/camera_json.hpp"
#include "simulate/simulated_grid.hpp"

namespace lfcam {

using json_reader::JsonObject;

double MainLens::imageDistanceMm() const {
  // Thin lens: 1/f = 1/d + 1/F. Focus at infinity (or closer than f, refused by validate) -> f.
  if (!std::isfinite(focusDistanceMm) || focusDistanceMm <= focalLengthMm) return focalLengthMm;
  return focalLengthMm * focusDistanceMm / (focusDistanceMm - focalLengthMm);
}

std::array<int, 2> CameraModel::microlensCounts() const {
  if (!microlenses) return {0, 0};
  const MicrolensArray& m = *microlenses;
  // The microlens images are spaced pitch * (1 + separation / F) on the sensor.
  const double scale = 1.0 + m.separationMm() / mainLens.imageDistanceMm();
  const int columns = m.columns > 0 ? m.columns : std::max(1, int(std::floor(sensor.widthMm() / (m.pitchMm * scale))));
  const int rows = m.rows > 0 ? m.rows : std::max(1, int(std::floor(sensor.heightMm() / (m.rowPitchMm() * scale))));
  return {columns, rows};
}

int MicrolensArray::lensType(int i, int j) const {
  if (typeFocalLengthsMm.size() <= 1) return 0;
  // Twice (across - sqrt(3) down) in pitches (hexagonal; across - down on a square lattice): an
  // integer whose class mod 3 differs between any two neighbours, a proper 3-colouring.
  const long colour = packing == Packing::Hexagonal ? 2 * long(i) + (j & 1) - 3 * long(j) : long(i) - long(j);
  return int(((colour % 3) + 3) % 3);
}

bool CameraModel::focusedPlenoptic() const {
  if (!microlenses) return false;
  for (int type = 0; type < microlenses->lensTypes(); ++type) {
    // (type, 0) runs through every type: neighbours along a row differ.
    const double f = microlenses->focalLengthOf(type, 0);
    if (std::abs(microlenses->separationMm() - f) <= 0.01 * f) return false;
  }
  return true;
}

std::array<double, 2> CameraModel::microlensCentreMm(int i, int j) const {
  const MicrolensArray& m = *microlenses;
  const auto [columns, rows] = microlensCounts();
  double a = (i - 0.5 * (columns - 1)) * m.pitchMm;
  if (m.packing == Packing::Hexagonal && (j & 1)) a += 0.5 * m.pitchMm;
  const double b = (j - 0.5 * (rows - 1)) * m.rowPitchMm();
  const double angle = m.rotationDeg * M_PI / 180.0;
  const double c = std::cos(angle), s = std::sin(angle);
  return {m.offsetMm[0] + c * a - s * b, m.offsetMm[1] + s * a + c * b};
}

std::array<double, 2> CameraModel::microlensImageCentrePx(int i, int j) const {
  const auto centre = microlensCentreMm(i, j);
  const double scale = 1.0 + microlenses->separationMm() / mainLens.imageDistanceMm();
  // On the sensor at (W/2, H/2) + centre * scale / pitch; the raw turns it about the sensor's centre.
  return {0.5 * sensor.width - centre[0] * scale / sensor.pixelPitchMm,
          0.5 * sensor.height - centre[1] * scale / sensor.pixelPitchMm};
}

double CameraModel::microlensImageDiameterPx() const {
  if (!microlenses) return 0;
  return mainLens.apertureDiameterMm() * microlenses->separationMm() / mainLens.imageDistanceMm() / sensor.pixelPitchMm;
}

CameraModel CameraModel::paperPrototype(int width, int height) {
  CameraModel camera;
  camera.microlenses = MicrolensArray{};
  camera.sensor.width = width;
  camera.sensor.height = height;
  return camera;
}

Status CameraModel::validate(const std::string& where) const {
  auto bad = [&](const std::string& key, const std::string& message) -> Status {
    return makeError(ErrorCode::Usage, where + ": " + key + ": " + message);
  };
  const MainLens& l = mainLens;
  if (!(l.focalLengthMm > 0) || !std::isfinite(l.focalLengthMm))
    return bad("camera.main_lens.focal_length_mm", "must be positive");
  if (!(l.fNumber > 0) || !std::isfinite(l.fNumber)) return bad("camera.main_lens.f_number", "must be positive");
  if (!(l.focusDistanceMm > l.focalLengthMm))
    return bad("camera.main_lens.focus_distance_mm",
               "must be beyond the focal length (" + std::to_string(l.focalLengthMm) + " mm)");
  const Sensor& s = sensor;
  if (s.width < 1 || s.height < 1 || double(s.width) * s.height > 1e9)
    return bad("camera.sensor.width", "the sensor must have 1 to 1e9 pixels");
  // The simulation holds about four float images of the sensor at once (irradiance, raw, codes).
  LFCAM_TRY(
      checkMemory(where, checkedProduct({std::uint64_t(s.width), std::uint64_t(s.height), 4 * sizeof(float)}),
                  "a simulated sensor of " + std::to_string(s.width) + " x " + std::to_string(s.height) + " pixels"));
  if (!(s.pixelPitchMm > 0)) return bad("camera.sensor.pixel_pitch_mm", "must be positive");
  if (s.bitDepth < 1 || s.bitDepth > 16) return bad("camera.sensor.bit_depth", "must be in [1, 16]");
  if (s.whiteLevel > (1 << s.bitDepth) - 1) return bad("camera.sensor.white_level", "exceeds the bit depth");
  if (s.blackLevel < 0 || s.blackLevel >= s.whiteLevel)
    return bad("camera.sensor.black_level", "must be below the white level");
  if (!(s.fullWellElectrons > 0)) return bad("camera.sensor.full_well", "must be positive");
  if (microlenses) {
    const MicrolensArray& m = *microlenses;
    if (!(m.pitchMm > 0)) return bad("camera.microlenses.pitch_mm", "must be positive");
    if (!(m.focalLengthMm > 0)) return bad("camera.microlenses.focal_length_mm", "must be positive");
    if (!(m.separationMm() > 0)) return bad("camera.microlenses.to_sensor_mm", "must be positive");
    if (!(m.fillFactor > 0 && m.fillFactor <= 1)) return bad("camera.microlenses.fill_factor", "must be in (0, 1]");
    if (!m.typeFocalLengthsMm.empty()) {
      if (m.typeFocalLengthsMm.size() != 3)
        return bad("camera.microlenses.focal_lengths_mm", "expected three lens types");
      int shorter = 0;
      for (const double f : m.typeFocalLengthsMm) {
        if (!(f > 0)) return bad("camera.microlenses.focal_lengths_mm", "must be positive");
        shorter += f < m.separationMm();
      }
      if (shorter != 0 && shorter != 3)
        return bad("camera.microlenses.focal_lengths_mm",
                   "all shorter (Keplerian) or all longer (Galilean) than to_sensor_mm, not some of each");
    }
    if (m.pitchMm < 0.5 * s.pixelPitchMm) return bad("camera.microlenses.pitch_mm", "smaller than half a pixel");
    const auto counts = microlensCounts();
    if (double(counts[0]) * counts[1] > 1e8) return bad("camera.microlenses.columns", "too many microlenses");
  }
  return {};
}

Result<CameraModel> cameraFromJson(const nlohmann::json& json, const CameraModel& base, const std::string& where) {
  CameraModel camera = base;
  JsonObject root(json, where, "camera");
  LFCAM_TRY(root.requireObject());

  if (root.has("main_lens")) {
    JsonObject o(root.at("main_lens"), where, "camera.main_lens");
    LFCAM_TRY(o.requireObject());
    MainLens& l = camera.mainLens;
    LFCAM_TRY(o.number("focal_length_mm", l.focalLengthMm, 0, 1e5, true));
    LFCAM_TRY(o.number("focus_distance_mm", l.focusDistanceMm, 0, 1e12, true));
    LFCAM_TRY(o.number("f_number", l.fNumber, 0, 1e4, true));
    std::optional<double> imageSide;
    LFCAM_TRY(o.optionalNumber("image_f_number", imageSide, 0, 1e4, true));
    if (imageSide && o.has("f_number"))
      return o.fail("camera.main_lens.image_f_number", "give f_number or image_f_number, not both");
    if (!(l.focusDistanceMm > l.focalLengthMm))
      return o.fail("camera.main_lens.focus_distance_mm", "must be beyond the focal length");
    if (imageSide) l.setImageSideFNumber(*imageSide);
    LFCAM_TRY(o.noUnknownKeys());
  }
  root.markSeen("main_lens");

  if (root.has("microlenses") || (json.contains("microlenses") && json.at("microlenses").is_null())) {
    const auto& value = json.at("microlenses");
    if (value.is_boolean() && !value.get<bool>()) {
      camera.microlenses.reset();  // conventional camera
    } else if (value.is_null()) {
      camera.microlenses.reset();
    } else {
      JsonObject o(value, where, "camera.microlenses");
      if (!value.is_object())
        return o.fail("camera.microlenses", "expected an object, or false for a conventional camera");
      MicrolensArray m = camera.microlenses.value_or(MicrolensArray{});
      LFCAM_TRY(o.number("pitch_mm", m.pitchMm, 0, 1e3, true));
      LFCAM_TRY(o.number("focal_length_mm", m.focalLengthMm, 0, 1e4, true));
      std::string packing = packingName(m.packing);
      LFCAM_TRY(o.string("packing", packing));
      if (packing == "square")
        m.packing = Packing::Square;
      else if (packing == "hexagonal" || packing == "hex")
        m.packing = Packing::Hexagonal;
      else
        return o.fail("camera.microlenses.packing", "expected \"square\" or \"hexagonal\", got \"" + packing + "\"");
      LFCAM_TRY(o.number("rotation_deg", m.rotationDeg, -360, 360));
      LFCAM_TRY(o.numbers("offset_mm", m.offsetMm, -1e4, 1e4));
      LFCAM_TRY(o.optionalNumber("to_sensor_mm", m.toSensorMm, 0, 1e4, true));
      if (o.has("focal_lengths_mm")) {
        std::array<double, 3> focal{};
        LFCAM_TRY(o.numbers("focal_lengths_mm", focal, 1e-6, 1e4));
        m.typeFocalLengthsMm.assign(focal.begin(), focal.end());
      }
      o.markSeen("focal_lengths_mm");
      LFCAM_TRY(o.number("fill_factor", m.fillFactor, 0, 1, true));
      LFCAM_TRY(o.integer("columns", m.columns, 0, 100000));
      LFCAM_TRY(o.integer("rows", m.rows, 0, 100000));
      LFCAM_TRY(o.noUnknownKeys());
      camera.microlenses = m;
    }
  }
  root.markSeen("microlenses");

  if (root.has("sensor")) {
    JsonObject o(root.at("sensor"), where, "camera.sensor");
    LFCAM_TRY(o.requireObject());
    Sensor& s = camera.sensor;
    LFCAM_TRY(o.integer("width", s.width, 1, 100000));
    LFCAM_TRY(o.integer("height", s.height, 1, 100000));
    LFCAM_TRY(o.number("pixel_pitch_mm", s.pixelPitchMm, 0, 1e3, true));
    std::string cfa = colorFilterName(s.colorFilter);
    LFCAM_TRY(o.string("color_filter", cfa));
    if (cfa == "RGGB")
      s.colorFilter = ColorFilter::RGGB;
    else if (cfa == "BGGR")
      s.colorFilter = ColorFilter::BGGR;
    else if (cfa == "GRBG")
      s.colorFilter = ColorFilter::GRBG;
    else if (cfa == "GBRG")
      s.colorFilter = ColorFilter::GBRG;
    else if (cfa == "mono")
      s.colorFilter = ColorFilter::Mono;
    else
      return o.fail("camera.sensor.color_filter", "expected RGGB, BGGR, GRBG, GBRG or mono, got \"" + cfa + "\"");
    LFCAM_TRY(o.integer("bit_depth", s.bitDepth, 1, 16));
    const bool whiteGiven = o.has("white_level");
    LFCAM_TRY(o.integer("black_level", s.blackLevel, 0, 65535));
    LFCAM_TRY(o.integer("white_level", s.whiteLevel, 1, 65535));
    if (!whiteGiven) s.whiteLevel = (1 << s.bitDepth) - 1;
    if (s.whiteLevel > (1 << s.bitDepth) - 1) return o.fail("camera.sensor.white_level", "exceeds 2^bit_depth - 1");
    if (s.blackLevel >= s.whiteLevel) return o.fail("camera.sensor.black_level", "must be below white_level");
    LFCAM_TRY(o.number("exposure", s.exposure, 0, 1e9));
    LFCAM_TRY(o.number("electrons_per_irradiance", s.electronsPerIrradiance, 0, 1e12));
    LFCAM_TRY(o.number("full_well", s.fullWellElectrons, 0, 1e9, true));
    LFCAM_TRY(o.number("read_noise", s.readNoiseElectrons, 0, 1e6));
    LFCAM_TRY(o.boolean("noise", s.noise));
    LFCAM_TRY(o.number("hot_pixels", s.hotPixelFraction, 0, 1));
    LFCAM_TRY(o.unsignedInteger("seed", s.seed));
    LFCAM_TRY(o.noUnknownKeys());
  }
  root.markSeen("sensor");
  LFCAM_TRY(root.noUnknownKeys());
  LFCAM_TRY(camera.validate(where));
  return camera;
}

nlohmann::json cameraToJson(const CameraModel& camera) {
  using nlohmann::json;
  const MainLens& l = camera.mainLens;
  const Sensor& s = camera.sensor;
  json out;
  out["lfcam_format"] = "lfcam-simulated-camera";
  out["lfcam_version"] = 1;
  out["units"] = "lengths in mm unless the key says px; x right, y down, seen from behind the camera";
  out["main_lens"] = {{"focal_length_mm", l.focalLengthMm},
                      {"f_number", l.fNumber},
                      {"aperture_diameter_mm", l.apertureDiameterMm()},
                      {"focus_distance_mm", l.focusDistanceMm},
                      {"image_distance_mm", l.imageDistanceMm()},
                      {"image_f_number", l.imageSideFNumber()}};
  out["sensor"] = {
      {"width", s.width},
      {"height", s.height},
      {"pixel_pitch_mm", s.pixelPitchMm},
      {"distance_from_lens_mm", l.imageDistanceMm() + (camera.microlenses ? camera.microlenses->separationMm() : 0.0)},
      {"color_filter", colorFilterName(s.colorFilter)},
      {"bit_depth", s.bitDepth},
      {"black_level", s.blackLevel},
      {"white_level", s.whiteLevel},
      {"raw_encoding", "16-bit PNG/TIFF codes equal to the digital numbers (not rescaled)"},
      {"exposure", s.exposure},
      {"electrons_per_irradiance", s.electronsPerIrradiance},
      {"full_well", s.fullWellElectrons},
      {"gain_dn_per_electron", s.gain()},
      {"read_noise", s.readNoiseElectrons},
      {"noise", s.noise},
      {"hot_pixels", s.hotPixelFraction},
      {"seed", s.seed}};
  if (!camera.microlenses) {
    out["microlenses"] = nullptr;
    out["mode"] = "conventional";
    return out;
  }
  out["mode"] = "light-field";
  const MicrolensArray& m = *camera.microlenses;
  const auto [columns, rows] = camera.microlensCounts();
  out["microlenses"] = {{"pitch_mm", m.pitchMm},
                        {"focal_length_mm", m.focalLengthMm},
                        {"f_number", m.fNumber()},
                        {"packing", packingName(m.packing)},
                        {"rotation_deg", m.rotationDeg},
                        {"offset_mm", {m.offsetMm[0], m.offsetMm[1]}},
                        {"to_sensor_mm", m.separationMm()},
                        {"fill_factor", m.fillFactor},
                        {"columns", columns},
                        {"rows", rows}};
  if (!m.typeFocalLengthsMm.empty()) out["microlenses"]["focal_lengths_mm"] = m.typeFocalLengthsMm;
  // The lattice of microlens image centres in the raw (turned by 180 degrees), in pixels: what a
  // calibration from the white image recovers, in grid.json's terms (lenslet_grid.hpp).
  const LensletGrid grid = gridFromCamera(camera);
  const double pitchPx = grid.pitchX, rowPx = grid.pitchY;
  const double c = std::cos(grid.rotationRad), sn = std::sin(grid.rotationRad);
  const double scale = 1.0 + m.separationMm() / l.imageDistanceMm();
  const double toPx = scale / s.pixelPitchMm;
  const std::array<double, 2> offsetPx{-m.offsetMm[0] * toPx, -m.offsetMm[1] * toPx};  // turned with the raw
  out["lattice_px"] = {{"pitch_px", pitchPx},
                       {"row_pitch_px", rowPx},
                       {"rotation_deg", m.rotationDeg},
                       {"packing", packingName(m.packing)},
                       {"offset_px", {offsetPx[0], offsetPx[1]}},
                       {"centre_px", {0.5 * s.width + offsetPx[0], 0.5 * s.height + offsetPx[1]}},
                       {"origin_px", {grid.origin[0], grid.origin[1]}},
                       {"column_step_px", {pitchPx * c, pitchPx * sn}},
                       {"row_step_px", {-rowPx * sn, rowPx * c}},
                       {"odd_row_shift", m.packing == Packing::Hexagonal ? 0.5 : 0.0},
                       {"hex_parity", grid.hexParity},
                       {"pixels_per_microlens", pitchPx},
                       {"image_diameter_px", camera.microlensImageDiameterPx()},
                       {"pixel_coordinates", "pixel (x, y) covers [x, x+1) x [y, y+1); centres at half-integers"}};
  return out;
}

}  // namespace lfcam
