// Simulated Lytro calibration data for the white-image database's tests: white images traced by the
// simulator, one lattice offset for each zoom and focus setting (as a real lens's setting moves the
// microlens images), packed as the cameras pack them (Illum: 10-bit little-endian, F01: 12-bit
// big-endian), each with a .TXT made from the real metadata in ../shared/data/lytro-metadata
// (MOD_0015.json for the Illum, the F01 raw frame's IMG_0001__frame.json wrapped as white images'
// .TXT are), and captures of a chart as Lytro containers whose metadata names serial and setting.
#pragma once

#include <archive.h>
#include <archive_entry.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "raw_io/raw_packing.hpp"
#include "test_support.hpp"

namespace lfcam::test {

struct LytroSetting {
  std::string serial;
  double zoomStep = 0, focusStep = 0;
  int lattice = 0;          // which lattice offset the simulated white and capture have
  double exposureS = 0.01;  // of the white
  int width = 160, height = 128;
};

// A small Lytro-like camera: hexagonal microlenses 10 px apart (the F01's are 9.9), its lattice shifted by `lattice`.
inline CameraModel lytroLikeCamera(bool illum, const LytroSetting& setting) {
  const int lattice = setting.lattice;
  CameraModel camera = CameraModel::paperPrototype(setting.width, setting.height);
  camera.microlenses->pitchMm = 10 * camera.sensor.pixelPitchMm;
  camera.microlenses->focalLengthMm = 4 * camera.microlenses->pitchMm;
  camera.microlenses->packing = Packing::Hexagonal;
  camera.microlenses->offsetMm = {lattice * 1.7 * camera.sensor.pixelPitchMm,
                                  -lattice * 1.1 * camera.sensor.pixelPitchMm};
  camera.sensor.noise = false;
  camera.sensor.colorFilter = illum ? ColorFilter::GRBG : ColorFilter::BGGR;  // as the real metadata say
  camera.sensor.bitDepth = illum ? 10 : 12;
  camera.sensor.blackLevel = illum ? 64 : 168;
  camera.sensor.whiteLevel = illum ? 1023 : 4095;
  return camera;
}

// The real .TXT of a white image of that generation, as the model; null when the data is absent.
inline nlohmann::json realWhiteDescription(bool illum) {
  const auto folder = sharedDataDir() / "lytro-metadata";
  std::ifstream in(folder / (illum ? "MOD_0015.json" : "IMG_0001__frame.json"));
  if (!in) return nullptr;
  nlohmann::json model = nlohmann::json::parse(in);
  if (illum) return model;
  // The F01's white images wrap the frame metadata as the Illum's do (LFToolbox reads both alike).
  return {{"master", {{"picture", {{"frameArray", {{{"frame", {{"metadata", model}, {"imageRef", "unknown"}}}}}}}}}}};
}

// MOD_*.RAW and MOD_*.TXT bytes of one simulated white.
inline std::pair<std::string, std::string> lytroWhiteFiles(bool illum, const LytroSetting& setting) {
  const CameraModel camera = lytroLikeCamera(illum, setting);
  auto scene = builtinScene("white", camera);
  EXPECT_TRUE(scene.ok());
  const Image white = simulateCapture(*scene, camera, {.samplesPerPixel = 4}).raw;
  std::vector<std::uint16_t> samples(white.planeSize());
  for (std::size_t k = 0; k < samples.size(); ++k) samples[k] = std::uint16_t(white.plane(0)[k]);
  const auto packed = packRaw(illum ? RawPacking::Bits10LittleEndian : RawPacking::Bits12BigEndian, samples);

  nlohmann::json description = realWhiteDescription(illum);
  nlohmann::json& frame = description["master"]["picture"]["frameArray"][0]["frame"];
  nlohmann::json& metadata = frame["metadata"];
  metadata["image"]["width"] = white.width();
  metadata["image"]["height"] = white.height();
  metadata["devices"]["lens"]["zoomStep"] = setting.zoomStep;
  metadata["devices"]["lens"]["focusStep"] = setting.focusStep;
  metadata["devices"]["shutter"]["frameExposureDuration"] = setting.exposureS;
  const double pixelPitchM = metadata["devices"]["sensor"]["pixelPitch"].get<double>();
  metadata["devices"]["mla"]["lensPitch"] = 10 * pixelPitchM;
  metadata["devices"]["mla"]["rotation"] = 0.0;
  frame["privateMetadata"]["camera"]["serialNumber"] = setting.serial;
  const auto* bytes = reinterpret_cast<const char*>(packed.data());
  return {std::string(bytes, bytes + packed.size()), description.dump(1)};
}

inline void writeLytroWhite(const std::filesystem::path& folder, const std::string& stem, bool illum,
                            const LytroSetting& setting) {
  const auto [raw, txt] = lytroWhiteFiles(illum, setting);
  writeBytes(folder / (stem + ".RAW"), raw);
  writeBytes(folder / (stem + ".TXT"), txt);
}

// A tar archive of (name, bytes) members, as an Illum's caldata-SERIAL.tar.
inline void writeTar(const std::filesystem::path& path,
                     const std::vector<std::pair<std::string, std::string>>& members) {
  archive* writer = archive_write_new();
  archive_write_set_format_pax_restricted(writer);
  archive_write_open_filename(writer, path.c_str());
  for (const auto& [name, bytes] : members) {
    archive_entry* entry = archive_entry_new();
    archive_entry_set_pathname(entry, name.c_str());
    archive_entry_set_size(entry, la_int64_t(bytes.size()));
    archive_entry_set_filetype(entry, AE_IFREG);
    archive_entry_set_perm(entry, 0644);
    archive_write_header(writer, entry);
    archive_write_data(writer, bytes.data(), bytes.size());
    archive_entry_free(entry);
  }
  archive_write_close(writer);
  archive_write_free(writer);
}

// A chart captured with the camera of `setting`, as a Lytro container (.lfr for the Illum, .lfp for
// the F01) whose metadata names the setting's serial, zoom and focus steps.
inline void writeLytroCapture(const std::filesystem::path& path, bool illum, const LytroSetting& setting) {
  const CameraModel camera = lytroLikeCamera(illum, setting);
  const std::filesystem::path scratch = path.parent_path() / (path.filename().string() + ".simulation");
  auto scene = builtinScene("chart", camera);
  ASSERT_TRUE(scene.ok());
  ASSERT_TRUE(writeSimulation(scratch, *scene, camera, {.samplesPerPixel = 4}, {.white = false, .groundTruth = false}));
  auto raw = readRaw(scratch / "raw.png");
  std::filesystem::remove_all(scratch);
  ASSERT_TRUE(raw.ok()) << raw.error().message;
  LytroWriteOptions options{.style = illum ? LytroStyle::Illum : LytroStyle::FirstGeneration,
                            .pixelPitchMm = camera.sensor.pixelPitchMm};
  options.setting = {.serial = setting.serial, .zoomStep = setting.zoomStep, .focusStep = setting.focusStep};
  ASSERT_TRUE(writeLytroRaw(path, *raw, options));
}

}  // namespace lfcam::test
