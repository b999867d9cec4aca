// lfcam simulate SCENE -o DIR: the physically based plenoptic camera (issue 3). SCENE is a scene
// file (docs/formats.md) or a built-in name; the flags override the camera of the scene.
#include <memory>

#include "commands.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "lfcam/simulate/simulate_setup.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addSimulateCommand(CLI::App& app, Job& job) {
  struct Options {
    std::string scene, output, noise, rawFormat = "png", container;
    std::optional<double> fNumber, imageFNumber, focusMm, pixelsPerLens, exposure;
    std::optional<int> size;
    std::optional<std::uint64_t> seed;
    int samples = 16;
    bool conventional = false, noWhite = false, noGroundTruth = false, hexagonal = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "simulate", "capture a scene with a simulated plenoptic (or conventional) camera, traced ray by ray");
  command->add_option("scene", options->scene, "scene file (.json) or built-in: people, chart, pinhole, white")
      ->required();
  command
      ->add_option("-o,--output", options->output,
                   "output folder: raw.png, white.png, camera.json, depth.pfm, ideal.lf.h5")
      ->required();
  command->add_option("--f-number", options->fNumber, "main-lens f-number (focal length / aperture)")
      ->check(CLI::Range(0.5, 1000.0));
  command
      ->add_option("--image-f-number", options->imageFNumber,
                   "set the aperture so that the image-side f-number is this (section 3.2)")
      ->check(CLI::Range(0.5, 1000.0))
      ->excludes("--f-number");
  command->add_option("--focus-mm", options->focusMm, "focus distance of the main lens, mm")
      ->check(CLI::PositiveNumber);
  command->add_option("--size", options->size, "sensor pixels across and down (the paper: 4000)")
      ->check(CLI::Range(8, 20000));
  command
      ->add_option("--pixels-per-lens", options->pixelsPerLens,
                   "microlens pitch in sensor pixels (keeps the microlens f-number)")
      ->check(CLI::Range(1.0, 1000.0));
  command->add_flag("--hexagonal", options->hexagonal, "hexagonal microlens packing");
  command->add_option("--samples", options->samples, "ray samples per pixel (rounded up to a square)")
      ->check(CLI::Range(1, 1024));
  command->add_option("--seed", options->seed, "seed of the samples, noise and hot pixels");
  command->add_option("--exposure", options->exposure, "exposure multiplier")->check(CLI::NonNegativeNumber);
  command->add_flag("--conventional", options->conventional, "no microlens array: a conventional photograph");
  command->add_option("--noise", options->noise, "photon and read noise")->check(CLI::IsMember({"on", "off"}));
  command->add_option("--raw-format", options->rawFormat, "raw and white image format")
      ->check(CLI::IsMember({"png", "tiff"}));
  command
      ->add_option("--container", options->container,
                   "also write the raw as a Lytro container: lfp (first generation: raw.lfp) or lfr (Illum: "
                   "raw.lfr, white.lfr)")
      ->check(CLI::IsMember({"lfp", "lfr"}));
  command->add_flag("--no-white", options->noWhite, "skip white.png");
  command->add_flag("--no-ground-truth", options->noGroundTruth, "skip depth.pfm and ideal.lf.h5");
  command->callback([options, &job] {
    job = [options]() -> Status {
      const Options& o = *options;
      std::optional<bool> noise;
      if (!o.noise.empty()) noise = o.noise == "on";
      LFCAM_ASSIGN_OR_RETURN(auto scene, simulationScene(o.scene, {.fNumber = o.fNumber,
                                                                   .imageFNumber = o.imageFNumber,
                                                                   .focusMm = o.focusMm,
                                                                   .size = o.size,
                                                                   .pixelsPerLens = o.pixelsPerLens,
                                                                   .hexagonal = o.hexagonal,
                                                                   .conventional = o.conventional,
                                                                   .seed = o.seed,
                                                                   .exposure = o.exposure,
                                                                   .noise = noise}));
      SimulationOptions simulation;
      simulation.samplesPerPixel = o.samples;
      CaptureOutputs outputs;
      outputs.white = !o.noWhite;
      outputs.groundTruth = !o.noGroundTruth;
      outputs.rawExtension = "." + o.rawFormat;
      ProgressBar bar("simulating " + o.scene);
      LFCAM_TRY(writeSimulation(o.output, scene, scene.camera, simulation, outputs, [&](double f) { bar(f); }));
      if (o.container.empty()) return {};
      return writeSimulationContainers(o.output,
                                       o.container == "lfp" ? LytroStyle::FirstGeneration : LytroStyle::Illum);
    };
  });
}

}  // namespace lfcam::cli
