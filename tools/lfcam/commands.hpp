// The lfcam subcommands. Each add*Command registers its options on `app` and, when chosen on the
// command line, stores the work to do in `job`; main runs it and turns its Status into a message
// and an exit status.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam::cli {

using Job = std::function<Status()>;

void addInfoCommand(CLI::App& app, Job& job);
void addConvertCommand(CLI::App& app, Job& job);
void addViewsCommand(CLI::App& app, Job& job);
void addRefocusCommand(CLI::App& app, Job& job);
void addStackCommand(CLI::App& app, Job& job);
void addObserverCommand(CLI::App& app, Job& job);
void addBenchCommand(CLI::App& app, Job& job);
void addAnimateCommand(CLI::App& app, Job& job);
void addSynthCommand(CLI::App& app, Job& job);
void addDemoCommand(CLI::App& app, Job& job);
void addSimulateCommand(CLI::App& app, Job& job);
void addDepthCommand(CLI::App& app, Job& job);
void addScoreCommand(CLI::App& app, Job& job);
void addEdofCommand(CLI::App& app, Job& job);
void addDenoiseCommand(CLI::App& app, Job& job);
void addExtractCommand(CLI::App& app, Job& job);
void addViewCommand(CLI::App& app, Job& job);
void addExportHtmlCommand(CLI::App& app, Job& job);
void addExperimentCommand(CLI::App& app, Job& job);
void addDecodeCommand(CLI::App& app, Job& job);
void addCalibrateCommand(CLI::App& app, Job& job);
void addBatchCommand(CLI::App& app, Job& job);
void addVolumeCommand(CLI::App& app, Job& job);
void addWhitesCommand(CLI::App& app, Job& job);
void addMemoryLimitOption(CLI::App& app);  // global: --memory-limit / LFCAM_MEMORY_LIMIT

// A light-field input as every command takes it: a path, recognised by content, and the few
// options needed for inputs that do not describe themselves.
struct InputOptions {
  std::string path;
  std::optional<int> lensletViews;
  ViewNumberOrder viewOrder = ViewNumberOrder::Auto;
  std::string white, dark, grid;     // a raw lenslet image, decoded on the way when --white is given
  std::string whites;                // ... or --whites, a white-image database choosing its white
  bool anyCamera = false;            // --any-camera: whites of another camera allowed
  std::optional<double> blackLevel;  // its --black-level, DN
  DecodeOptions decode;              // its --demosaic and --sampling (the rest is filled in on the way)
  bool decodesRaw() const { return !white.empty() || !whites.empty(); }
  LightFieldReadOptions readOptions() const { return {.lensletViews = lensletViews, .viewNumberOrder = viewOrder}; }
};
void addInputOptions(CLI::App& command, InputOptions& input);
Result<LightField> loadInput(const InputOptions& input);

}  // namespace lfcam::cli
