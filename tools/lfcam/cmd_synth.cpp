// lfcam synth -o OUT: the layered-planes light field, with its exact ground-truth disparity.
#include <memory>
#include <vector>

#include "commands.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addSynthCommand(CLI::App& app, Job& job) {
  struct Options {
    std::string output, disparity;
    int views = 9;
    std::vector<int> size = {256};  // width [height]
    std::uint64_t seed = 1;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command =
      app.add_subcommand("synth", "make a layered-planes light field with exact ground-truth disparity");
  command->add_option("-o,--output", options->output, "output light field (.lf.h5, folder, lenslet image)")->required();
  command->add_option("--views", options->views, "views across and down")->check(CLI::Range(1, 64));
  command->add_option("--size", options->size, "pixels across and down each view: W (square) or W H")
      ->expected(1, 2)
      ->check(CLI::Range(8, 8192));
  command->add_option("--seed", options->seed, "seed of the textures");
  command->add_option("--disparity", options->disparity, "also write the ground-truth disparity (.pfm)");
  command->callback([options, &job] {
    job = [options]() -> Status {
      const LayeredPlanesScene scene =
          defaultLayeredPlanesScene(options->views, options->size.front(), options->seed, options->size.back());
      LayeredPlanesLightField result = [&] {
        ProgressBar bar("making the light field");
        return renderLayeredPlanes(scene, [&](double f) { bar(f); });
      }();
      ProgressBar bar("writing " + options->output);
      LFCAM_TRY(writeLightField(options->output, result.lightField, {}, [&](double f) { bar(f); }));
      if (!options->disparity.empty()) LFCAM_TRY(writeImage(options->disparity, result.disparity));
      return {};
    };
  });
}

}  // namespace lfcam::cli
