// What lfcam says about its commands: the list printed by `lfcam` alone, the nearest command to a
// mistyped one, and the example ending every command's --help, each of which is run here on the
// real data (so an example that stops working fails a test).
#include <gtest/gtest.h>

#include <sstream>

#include "cli/cli_support.hpp"

namespace lfcam::test {
namespace {

const std::vector<std::string> kCommands{"info",       "convert", "views",     "refocus", "stack",    "observer",
                                         "bench",      "animate", "synth",     "demo",    "simulate", "depth",
                                         "score",      "edof",    "denoise",   "extract", "view",     "export-html",
                                         "experiment", "decode",  "calibrate", "batch"};

TEST(CommandHelp, AloneListsEveryCommandOnOneLineEach) {
  TempDir dir;
  const auto result = runLfcam({}, dir.path());
  EXPECT_EQ(result.exitStatus, 2) << "no command is a usage error, as in git";
  EXPECT_EQ(result.err, "");
  for (const auto& command : kCommands)
    EXPECT_NE(result.out.find("\n  " + command + " "), std::string::npos) << command;
}

TEST(CommandHelp, UnknownCommandNamesTheNearest) {
  TempDir dir;
  const auto result = runLfcam({"--threads", "2", "refcous", "x.lf.h5"}, dir.path());
  EXPECT_EQ(result.exitStatus, 2);
  EXPECT_EQ(result.errLines(), 1) << result.err;
  EXPECT_NE(result.err.find("unknown command 'refcous'"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("'refocus'"), std::string::npos) << result.err;
}

TEST(CommandHelp, ViewHelpDescribesThePagesControls) {
  TempDir dir;
  const auto help = runLfcam({"view", "--help"}, dir.path());
  EXPECT_EQ(help.exitStatus, 0);
  for (const char* words : {"click a point", "Tilted", "three numbered points", "two-ended slider", "Finer grid (2x)"})
    EXPECT_NE(help.out.find(words), std::string::npos) << words;
  // The example still ends it.
  EXPECT_NE(help.out.find("Example (from the repository's root):\n  lfcam view"), std::string::npos);
}

// The example line of `lfcam COMMAND --help`, split into words (examples quote nothing).
std::vector<std::string> exampleOf(const std::string& command, const TempDir& dir) {
  const auto help = runLfcam({command, "--help"}, dir.path());
  EXPECT_EQ(help.exitStatus, 0) << help.err;
  const std::string marker = "Example (from the repository's root):\n  ";
  const auto at = help.out.find(marker);
  if (at == std::string::npos) return {};
  std::istringstream line(
      help.out.substr(at + marker.size(), help.out.find('\n', at + marker.size()) - at - marker.size()));
  std::vector<std::string> words;
  for (std::string word; line >> word;) words.push_back(word);
  return words;
}

class CommandExample : public ::testing::TestWithParam<std::string> {};

TEST_P(CommandExample, HelpEndsWithAnExampleThatRuns) {
  TempDir dir;
  const auto words = exampleOf(GetParam(), dir);
  ASSERT_GE(words.size(), 2u) << GetParam() << " --help has no example";
  EXPECT_EQ(words[0], "lfcam");
  EXPECT_EQ(words[1], GetParam());
  if (GetParam() == "view") GTEST_SKIP() << "the viewer serves until stopped; its own tests run it";
  std::vector<std::string> args(words.begin() + 1, words.end());
  bool needsData = false;
  for (auto& arg : args)
    if (arg.rfind("../shared/data/", 0) == 0) {
      arg = (sharedDataDir() / arg.substr(std::string("../shared/data/").size())).string();
      needsData = true;
    }
  if (needsData && !std::filesystem::exists(sharedDataDir()))
    GTEST_SKIP() << "real data not found at " << sharedDataDir() << " (set LFCAM_DATA_DIR to run this example)";
  const auto home = std::filesystem::current_path();  // the example writes where it runs
  std::filesystem::current_path(dir.path());
  const auto result = runLfcam(args, dir.path());
  std::filesystem::current_path(home);
  EXPECT_EQ(result.exitStatus, 0) << GetParam() << ": " << result.err;
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, CommandExample, ::testing::ValuesIn(kCommands), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name) c = c == '-' ? '_' : c;
  return name;
});

}  // namespace
}  // namespace lfcam::test
