// --memory-limit (or LFCAM_MEMORY_LIMIT): the budget every reader checks before allocating
// (lfcam/memory_budget.hpp). A bad value is a usage error (exit 2).
#include "commands.hpp"
#include "core/memory_budget.hpp"

namespace lfcam::cli {

void addMemoryLimitOption(CLI::App& app) {
  // Global options may also follow the subcommand (`lfcam convert in out --memory-limit 2G`):
  // subcommands created after this inherit it.
  app.fallthrough();
  app.add_option_function<std::string>(
         "--memory-limit",
         [](const std::string& text) {
           auto bytes = parseMemorySize(text);
           if (!bytes) throw CLI::ValidationError("--memory-limit/LFCAM_MEMORY_LIMIT", bytes.error().message);
           setMemoryLimit(*bytes);
         },
         "the most memory one input may need, e.g. 4G, 512M or 75% (default: half the physical memory)")
      ->envname("LFCAM_MEMORY_LIMIT");
}

}  // namespace lfcam::cli
