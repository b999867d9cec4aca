#include "command_help.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

namespace lfcam::cli {
namespace {

// Each an actual run on ../shared/data (the real light fields beside the repository, see README).
// tests/cli/command_help_test.cpp runs them all.
const std::map<std::string, std::string>& examples() {
  static const std::map<std::string, std::string> table{
      {"info", "lfcam info ../shared/data/hci-antinous --json"},
      {"convert", "lfcam convert ../shared/data/lytro-f01-flower -o flower.lf.h5"},
      {"views", "lfcam views ../shared/data/lytro-f01-flower -o flower-views --mosaic flower-sheet.png"},
      {"refocus", "lfcam refocus ../shared/data/hci-antinous --slope 1.2 -o near.png"},
      {"stack", "lfcam stack ../shared/data/hci-antinous --slopes -2:2:16 -o antinous-stack"},
      {"observer", "lfcam observer ../shared/data/hci-antinous --u 2 --v -1 -o moved.png"},
      {"bench", "lfcam bench ../shared/data/lytro-f01-flower"},
      {"animate", "lfcam animate ../shared/data/lytro-f01-flower --focus-pull -o flower-pull.gif"},
      {"synth", "lfcam synth -o planes.lf.h5 --disparity planes-disparity.pfm"},
      {"demo", "lfcam demo -o lfcam-demo"},
      {"simulate", "lfcam simulate people --size 1000 -o people-capture"},
      {"depth", "lfcam depth ../shared/data/hci-antinous -o antinous.pfm --png antinous-depth.png"},
      {"score",
       "lfcam score ../shared/data/hci-antinous/gt_disp_lowres.pfm "
       "../shared/data/hci-antinous/gt_disp_lowres.pfm --json"},
      {"edof", "lfcam edof ../shared/data/lytro-f01-flower -o flower-all-in-focus.png"},
      {"denoise", "lfcam denoise ../shared/data/lytro-f01-flower --depth-range -1:1 -o flower-denoised.lf.h5"},
      {"extract", "lfcam extract ../shared/data/lytro-lfp/IMG_0002-dm.lfp -o img0002-dm"},
      {"view", "lfcam view ../shared/data/lytro-f01-flower --port 8080"},
      {"export-html", "lfcam export-html ../shared/data/lytro-f01-flower -o flower.html"},
      {"experiment", "lfcam experiment sharpness-vs-n --quick -o sharpness-report"},
      {"decode",
       "lfcam decode ../shared/data/lfm-guv/Lightfield_GUVExperim1.tif "
       "--white ../shared/data/lfm-guv/Radiometry_GUVExperim1.tif "
       "--dark ../shared/data/lfm-guv/DarkFrame_GUVExperim1.tif -o guv.lf.h5"},
      {"calibrate", "lfcam calibrate ../shared/data/lfm-guv/Radiometry_GUVExperim1.tif -o guv-grid.json"},
      {"volume",
       "lfcam volume ../shared/data/lfm-guv/Lightfield_GUVExperim1.tif "
       "--white ../shared/data/lfm-guv/Radiometry_GUVExperim1.tif "
       "--dark ../shared/data/lfm-guv/DarkFrame_GUVExperim1.tif "
       "--optics ../shared/data/lfm-guv/metadata.txt --slices 5 --iterations 4 -o guv-volume.tif"},
      {"whites", "lfcam whites index caldata-B5143909630.tar -o whites.json"},
      {"batch",
       "lfcam batch ../shared/data/hci-antinous ../shared/data/lytro-f01-flower -o two-captures "
       "--steps refocus:0.5,stack:-1:1:5"},
  };
  return table;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

void printCommandList(const CLI::App& app) {
  std::printf("%s\n\nusage: lfcam [--threads N] [--memory-limit SIZE] COMMAND [ARGS]\n\ncommands:\n",
              app.get_description().c_str());
  for (const CLI::App* command : app.get_subcommands({}))
    std::printf("  %-12s %s\n", command->get_name().c_str(), command->get_description().c_str());
  std::printf("\n'lfcam COMMAND --help' tells more about one, with an example.\n");
}

std::optional<std::string> unknownCommand(const CLI::App& app, int argc, const char* const* argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string argument = argv[k];
    if (argument.rfind("-", 0) == 0) {
      // A global option: skip its value too unless given as --name=value or it takes none.
      const CLI::Option* option = app.get_option_no_throw(argument.substr(0, argument.find('=')));
      if (option && option->get_type_size() > 0 && argument.find('=') == std::string::npos) ++k;
      continue;
    }
    const auto commands = app.get_subcommands({});
    const bool known = std::any_of(commands.begin(), commands.end(),
                                   [&](const CLI::App* command) { return command->check_name(argument); });
    if (known) return std::nullopt;
    return argument;
  }
  return std::nullopt;
}

std::string nearestCommand(const CLI::App& app, const std::string& name) {
  std::string best;
  std::size_t bestDistance = SIZE_MAX;
  for (const CLI::App* command : app.get_subcommands({})) {
    const std::size_t distance = editDistance(name, command->get_name());
    if (distance < bestDistance) bestDistance = distance, best = command->get_name();
  }
  return best;
}

void addExamples(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands({})) {
    const auto example = examples().find(command->get_name());
    // After what the command's own footer says, if anything.
    if (example != examples().end())
      command->footer(command->get_footer() + "\nExample (from the repository's root):\n  " + example->second);
  }
}

}  // namespace lfcam::cli
