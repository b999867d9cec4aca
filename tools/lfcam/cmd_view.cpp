// lfcam view INPUT [--port N] [--host ADDR]: the interactive viewer, a local web server whose page
// refocuses where it is clicked (viewer.hpp, viewer_server.hpp); of a processed Lytro container, its
// living picture over the container's own slices; of a focused plenoptic capture, its living picture
// (living_picture.hpp: rendered once, then served).
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "focused_input.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "lfcam/viewer/viewer.hpp"
#include "lfcam/viewer/viewer_server.hpp"
#include "raw_io/lytro_container.hpp"

namespace lfcam::cli {

namespace {

Status serve(ViewerServer& server, const ViewerServerOptions& options, const std::string& input) {
  LFCAM_TRY(server.bind(options));
  std::printf("lfcam view: serving %s on http://%s:%d/ (Ctrl-C to stop)\n", input.c_str(), options.host.c_str(),
              server.port());
  std::fflush(stdout);
  return server.run();
}

}  // namespace

void addViewCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    FocusedOptions focused;
    ViewerServerOptions server;
    int cacheMb = 64;
    int renders = 2;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "view",
      "serve an interactive viewer on a local web page: click to focus, aperture, viewpoint, tilt, focus range");
  command->footer(
      "\nThe page:\n"
      "  click a point       focus where it is sharpest; the sliders set the focus and the aperture;\n"
      "                      drag to move the eye within the lens\n"
      "  Focus: Tilted       three clicks place three numbered points; the photograph is focused on the plane\n"
      "                      through them, each where it is sharpest (refocus --focus-plane); a click on a\n"
      "                      point removes it\n"
      "  Focus: A range      a two-ended slider keeps everything between its far and near slopes in focus\n"
      "                      (refocus --focus-range; the first waits for the depth map, with a progress bar)\n"
      "  Finer grid (2x)     the photograph on a grid twice as fine (refocus --upsample 2)\n"
      "  Tilt, range and the finer grid use the whole lens from its centre.\n");
  addInputOptions(*command, options->input);
  addFocusedOptions(*command, options->focused);
  command->add_option("--port", options->server.port, "TCP port (0: any free port; the address is printed)")
      ->check(CLI::Range(0, 65535));
  command->add_option("--host", options->server.host,
                      "address to listen on (default 127.0.0.1: this machine only; 0.0.0.0 exposes it to the network)");
  command->add_option("--cache-mb", options->cacheMb, "memory for already rendered photographs, MB")
      ->check(CLI::Range(0, 4096));
  command->add_option("--max-renders", options->renders, "photographs rendered at once")->check(CLI::Range(1, 64));
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (isFocusedInput(options->input, options->focused)) {
        LFCAM_ASSIGN_OR_RETURN(auto capture, loadFocusedInput(options->input, options->focused));
        LFCAM_ASSIGN_OR_RETURN(auto page,
                               makeFocusedLivingPicture(capture.image, capture.calibration,
                                                        pixelsPerLens(options->focused, capture.calibration)));
        ViewerServer server(servePage(std::move(page)));
        return serve(server, options->server, options->input.path);
      }
      // A processed Lytro container: its living picture over its own slices (living_picture.hpp).
      if (!options->input.decodesRaw() && looksLikeLytroContainer(options->input.path)) {
        LFCAM_ASSIGN_OR_RETURN(auto stack, readLytroRefocusStack(options->input.path));
        LFCAM_ASSIGN_OR_RETURN(auto page, makeLytroLivingPicture(stack, options->input.path));
        ViewerServer server(servePage(std::move(page)));
        return serve(server, options->server, options->input.path);
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      ViewerLimits limits;
      limits.cacheBytes = std::size_t(options->cacheMb) << 20;
      limits.concurrentRenders = options->renders;
      ViewerSession session(std::move(lightField), limits);
      ViewerServer server(session);
      return serve(server, options->server, options->input.path);
    };
  });
}

}  // namespace lfcam::cli
