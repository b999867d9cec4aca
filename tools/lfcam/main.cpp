// lfcam: light-field photography from the command line. Exit status: 0 on success, 1 when the
// work failed (unreadable input, failed write), 2 on a usage error (unknown flag, bad value).
#include <malloc.h>

#include <cstdio>
#include <exception>
#include <new>

#include "command_help.hpp"
#include "commands.hpp"
#include "core/parallel.hpp"

int main(int argc, char** argv) {
  using namespace lfcam;
  // Freed memory kept for the next allocation, not handed back: buffers under 4 MiB (a view, a
  // photograph, a plane of scratch) come and go hundreds of times a command, and each page handed
  // back faults in again (on a virtual machine a trip to the host); larger ones are mappings of the
  // huge-page allocator's, faulted in up front. `lfcam depth` on antinous: 62 k faults -> 28 k.
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  CLI::App app{
      "lfcam: light-field photography after Ng et al. 2005, \"Light Field Photography with a "
      "Hand-held Plenoptic Camera\"",
      "lfcam"};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", "lfcam 0.1.0");
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  cli::addMemoryLimitOption(app);

  cli::Job job;
  cli::addInfoCommand(app, job);
  cli::addConvertCommand(app, job);
  cli::addViewsCommand(app, job);
  cli::addRefocusCommand(app, job);
  cli::addStackCommand(app, job);
  cli::addObserverCommand(app, job);
  cli::addBenchCommand(app, job);
  cli::addAnimateCommand(app, job);
  cli::addSynthCommand(app, job);
  cli::addDemoCommand(app, job);
  cli::addSimulateCommand(app, job);
  cli::addDepthCommand(app, job);
  cli::addScoreCommand(app, job);
  cli::addEdofCommand(app, job);
  cli::addDenoiseCommand(app, job);
  cli::addExtractCommand(app, job);
  cli::addViewCommand(app, job);
  cli::addExportHtmlCommand(app, job);
  cli::addExperimentCommand(app, job);
  cli::addDecodeCommand(app, job);
  cli::addCalibrateCommand(app, job);
  cli::addBatchCommand(app, job);
  cli::addVolumeCommand(app, job);
  cli::addWhitesCommand(app, job);

  cli::addExamples(app);

  if (const auto unknown = cli::unknownCommand(app, argc, argv)) {
    std::fprintf(stderr, "lfcam: unknown command '%s'; the nearest is '%s' (lfcam alone lists them all)\n",
                 unknown->c_str(), cli::nearestCommand(app, *unknown).c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "lfcam: %s (see lfcam --help)\n", e.what());
    return 2;
  }

  if (app.get_subcommands().empty()) {  // `lfcam` alone, or with global options only: usage, as git
    cli::printCommandList(app);
    return 2;
  }
  try {
    setThreadCount(threads);
    const Status status = job();
    if (!status) {
      std::fprintf(stderr, "lfcam: %s\n", status.error().message.c_str());
      return status.error().code == ErrorCode::Usage ? 2 : 1;
    }
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "lfcam: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lfcam: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
