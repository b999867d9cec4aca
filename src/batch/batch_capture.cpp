// runBatchCapture (batch_run.hpp): one capture's steps, its outputs and its done-marker. A focused
// plenoptic capture (its calibration beside it) takes the steps that apply to it, as the commands
// do: edof its total focus, depth its virtual depth, page its living picture.
#include "lfcam/batch/batch_run.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/parallel.hpp"
#include "lfcam/decode/decode_files.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/focused/focused_capture.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/io/volume_io.hpp"
#include "lfcam/lfm/volume_request.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "photo/focal_stack_output.hpp"

namespace lfcam {
namespace fs = std::filesystem;

namespace {

constexpr const char* kBatchDoneMarker = ".batch-done.json";

// Size and latest modification of a file, or of every file in a folder: what says "changed".
nlohmann::json inputFingerprint(const fs::path& input) {
  std::uintmax_t bytes = 0;
  fs::file_time_type latest = fs::file_time_type::min();  // the file clock's epoch may lie after today
  const auto add = [&](const fs::path& file) {
    std::error_code ec;
    bytes += fs::file_size(file, ec);
    latest = std::max(latest, fs::last_write_time(file, ec));
  };
  if (fs::is_directory(input)) {
    for (const auto& entry : fs::recursive_directory_iterator(input))
      if (entry.is_regular_file()) add(entry.path());
  } else {
    add(input);
    if (const auto calibration = focusedCalibrationBeside(input)) add(*calibration);
  }
  return {{"bytes", bytes}, {"modified_ns", std::int64_t(latest.time_since_epoch().count())}};
}

nlohmann::json doneMarker(const BatchCapture& capture, const std::vector<BatchStep>& steps, const BatchWhite& white) {
  nlohmann::json stepTexts = nlohmann::json::array();
  for (const BatchStep& step : steps) stepTexts.push_back(step.text);
  nlohmann::json marker{{"steps", stepTexts}};
  marker["fingerprint"] = inputFingerprint(capture.input);
  if (!white.image.empty()) marker["white"] = inputFingerprint(white.image);
  if (!white.database.empty()) marker["whites"] = inputFingerprint(white.database);
  // A volume's settings file edited in place changes the volume as much as the input would.
  for (const BatchStep& step : steps)
    if (step.kind == BatchStep::Kind::Volume) marker["settings"].push_back(inputFingerprint(step.settings));
  return marker;
}

bool completeAlready(const fs::path& folder, const nlohmann::json& marker, const std::vector<std::string>& outputs) {
  std::ifstream in(folder / kBatchDoneMarker);
  if (!in) return false;
  const nlohmann::json recorded = nlohmann::json::parse(in, nullptr, false);
  if (recorded != marker) return false;
  for (const std::string& output : outputs)
    if (!fs::is_regular_file(folder / output)) return false;
  return true;
}

Status runStep(const BatchStep& step, const LightField& lightField, const fs::path& input, const fs::path& outputFolder,
               const fs::path& folder) {
  switch (step.kind) {
    case BatchStep::Kind::Refocus: {
      LFCAM_ASSIGN_OR_RETURN(auto photo,
                             renderPhoto(lightField, PhotoRequest{.slope = step.slope}, {.inputName = input.string()}));
      return writeImage(folder / step.outputs().front(), photo);
    }
    case BatchStep::Kind::Photo: {
      LFCAM_ASSIGN_OR_RETURN(auto photo, renderPhoto(lightField, step.photo, {.inputName = input.string()}));
      return writeImage(folder / step.outputs().front(), photo);
    }
    case BatchStep::Kind::Stack: {
      LFCAM_ASSIGN_OR_RETURN(auto camera,
                             resolvePhoto(PhotoRequest{.slope = 0.0}, lightField, {.inputName = input.string()}));
      return writeFocalStack(folder / "stack", lightField, camera, step.slopes, "png", {}, [](double) {});
    }
    case BatchStep::Kind::Edof: {
      LFCAM_ASSIGN_OR_RETURN(auto result, allInFocus(lightField));
      return writeImage(folder / "all-in-focus.png", result.photo);
    }
    case BatchStep::Kind::Depth: {
      LFCAM_ASSIGN_OR_RETURN(auto depth, estimateDepth(lightField));
      LFCAM_TRY(writeImage(folder / "depth.pfm", depth.disparity));
      return writeImage(folder / "depth.png", colorMap(depth.disparity, depth.disparityMin, depth.disparityMax));
    }
    case BatchStep::Kind::Page: return writeLivingPicture(folder / "page.html", lightField);
    case BatchStep::Kind::Volume: {
      LfmVolumeRequest request = step.volume;
      request.psfPath = batchPsfPath(step, outputFolder).string();  // prepareBatch wrote it: only read here
      LFCAM_ASSIGN_OR_RETURN(auto result, reconstructVolume(lightField, request, input.string()));
      return writeVolume(folder / step.outputs().front(), result.reconstruction.volume);
    }
  }
  return {};
}

Status runFocusedStep(const BatchStep& step, const FocusedCapture& capture, const fs::path& folder) {
  const double pixelsPerLens = defaultPixelsPerLens(capture.calibration);
  switch (step.kind) {
    case BatchStep::Kind::Edof: {
      LFCAM_ASSIGN_OR_RETURN(auto photo, renderTotalFocus(capture.image, capture.calibration, pixelsPerLens));
      return writeImage(folder / "all-in-focus.png", photo);
    }
    case BatchStep::Kind::Depth: {
      FocusedDepthRequest request;
      request.pixelsPerLens = pixelsPerLens;
      LFCAM_ASSIGN_OR_RETURN(auto depth, estimateFocusedDepth(capture.image, capture.calibration, request));
      LFCAM_TRY(writeImage(folder / "depth.pfm", depth.virtualDepth));
      // The candidates' range, as a light field's map is coloured over its search range: one scale for every capture.
      return writeImage(folder / "depth.png",
                        colorMap(depth.virtualDepth, request.minVirtualDepth, request.maxVirtualDepth));
    }
    case BatchStep::Kind::Page:
      return writeFocusedLivingPicture(folder / "page.html", capture.image, capture.calibration, pixelsPerLens);
    default:
      return makeError(ErrorCode::Usage, "is for light fields; a focused plenoptic capture takes edof, depth and page");
  }
}

Status runSteps(const BatchCapture& capture, const std::vector<BatchStep>& steps, const BatchWhite& white,
                const fs::path& outputFolder, const fs::path& folder, const nlohmann::json& marker) {
  std::error_code ec;
  fs::remove(folder / kBatchDoneMarker, ec);  // half-done until every step has written again
  removeStaleTemporaries(folder);             // of a run killed mid-write
  // A hexagonal microscope's raw is decoded into the bricks its PSF is computed on; other steps
  // take the ordinary light field. Each is decoded only when a step needs it.
  const bool raw = !white.image.empty() || !white.database.empty();
  const auto onBricks = [&](const BatchStep& step) {
    return raw && step.kind == BatchStep::Kind::Volume && step.volume.optics.array == MicrolensLayout::Hexagonal;
  };
  std::optional<FocusedCapture> focused;
  std::optional<LightField> lightField, bricks;
  if (focusedCalibrationBeside(capture.input)) {
    if (!white.database.empty())
      return makeError(ErrorCode::Usage, "a focused plenoptic capture takes --white, not --whites");
    LFCAM_ASSIGN_OR_RETURN(focused, readFocusedCapture(capture.input, {.white = white.image}));
  } else {
    if (!std::all_of(steps.begin(), steps.end(), onBricks)) {
      LFCAM_ASSIGN_OR_RETURN(lightField, loadCapture(capture.input, white));
    }
    if (std::any_of(steps.begin(), steps.end(), onBricks)) {
      LFCAM_ASSIGN_OR_RETURN(
          bricks, loadCapture(capture.input, white, {.sampling = Sampling::Bricks, .packing = Packing::Hexagonal}));
    }
  }
  fs::create_directories(folder, ec);  // only now, so that an unreadable input leaves no folder
  if (ec) return makeError(ErrorCode::Io, folder.string() + ": cannot create the folder: " + ec.message());
  for (const BatchStep& step : steps) {
    const Status status =
        focused ? runFocusedStep(step, *focused, folder)
                : runStep(step, onBricks(step) ? *bricks : *lightField, capture.input, outputFolder, folder);
    if (!status) return makeError(status.error().code, step.text + ": " + status.error().message);
    // A cancelled step's outputs are meaningless (parallel.hpp): no marker, so a rerun redoes them.
    if (cancellationRequested()) return makeError(ErrorCode::Io, "cancelled");
  }
  return writeFileAtomically(folder / kBatchDoneMarker, [&](const fs::path& temporary) -> Status {
    std::ofstream out(temporary);
    out << marker.dump(2) << "\n";
    if (!out) return makeError(ErrorCode::Io, (folder / kBatchDoneMarker).string() + ": cannot write");
    return {};
  });
}

}  // namespace

Result<LightField> loadCapture(const fs::path& input, const BatchWhite& white, const DecodeOptions& decode) {
  if (white.image.empty() && white.database.empty()) return readLightField(input);
  return decodeRawFiles({.raw = input.string(),
                         .white = white.image.string(),
                         .whites = white.database.string(),
                         .anyCamera = white.anyCamera,
                         .decode = decode});
}

BatchOutcome runBatchCapture(const BatchCapture& capture, const std::vector<BatchStep>& steps, const BatchWhite& white,
                             const fs::path& outputFolder) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path folder = outputFolder / capture.name;
  BatchOutcome outcome;
  std::vector<std::string> outputs;
  for (const BatchStep& step : steps)
    for (const std::string& output : step.outputs()) outputs.push_back(output);
  for (const std::string& output : outputs) outcome.outputs.push_back((fs::path(capture.name) / output).string());
  try {
    const nlohmann::json marker = doneMarker(capture, steps, white);
    if (completeAlready(folder, marker, outputs)) {
      outcome.status = BatchOutcome::Status::Skipped;
    } else if (const Status status = runSteps(capture, steps, white, outputFolder, folder, marker); status) {
      outcome.status = BatchOutcome::Status::Done;
    } else {
      const std::string& message = status.error().message;
      outcome.error =
          message.find(capture.input.string()) == std::string::npos ? capture.input.string() + ": " + message : message;
    }
  } catch (const std::bad_alloc&) {
    outcome.error = capture.input.string() + ": out of memory";
  } catch (const std::exception& e) {
    outcome.error = capture.input.string() + ": " + e.what();
  }
  if (outcome.status == BatchOutcome::Status::Failed) outcome.outputs.clear();
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace lfcam
