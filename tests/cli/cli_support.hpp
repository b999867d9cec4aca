// Running the lfcam executable from tests: its exit status, whether a signal ended it, and what it
// printed.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace lfcam::test {

struct CommandResult {
  int exitStatus = -1;  // -1 when a signal ended the process
  int signal = 0;
  std::string out, err;

  int errLines() const {
    int lines = 0;
    for (char c : err) lines += c == '\n';
    return lines;
  }
};

// Starts `lfcam args...` with stdout and stderr going to the given files; its process id, or -1.
inline pid_t startLfcam(const std::vector<std::string>& args, const std::filesystem::path& outPath,
                        const std::filesystem::path& errPath) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> all{LFCAM_EXECUTABLE};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Runs `lfcam args...` with stdout and stderr captured through files in `scratch`.
inline CommandResult runLfcam(const std::vector<std::string>& args, const std::filesystem::path& scratch) {
  const auto outPath = scratch / ".stdout", errPath = scratch / ".stderr";
  CommandResult result;
  if (const pid_t pid = startLfcam(args, outPath, errPath); pid > 0) {
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) result.exitStatus = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  }
  result.out = readBytes(outPath);
  result.err = readBytes(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return result;
}

// The example ending `lfcam COMMAND --help`, split into words (examples quote nothing), with its
// paths under ../shared/data/ pointed at the shared data; empty when the help has none.
inline std::vector<std::string> helpExample(const std::string& command, const TempDir& dir) {
  const auto help = runLfcam({command, "--help"}, dir.path());
  EXPECT_EQ(help.exitStatus, 0) << help.err;
  const std::string marker = "Example (from the repository's root):\n  ";
  const auto at = help.out.find(marker);
  if (at == std::string::npos) return {};
  const auto begin = at + marker.size();
  std::istringstream line(help.out.substr(begin, help.out.find('\n', begin) - begin));
  const std::string shared = "../shared/data/";
  std::vector<std::string> words;
  for (std::string word; line >> word;)
    words.push_back(word.rfind(shared, 0) == 0 ? (sharedDataDir() / word.substr(shared.size())).string() : word);
  return words;
}

// Runs an example's words (after "lfcam") in `dir`, where it writes its outputs.
inline CommandResult runExample(const std::vector<std::string>& words, const TempDir& dir) {
  const auto home = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  auto result = runLfcam(std::vector<std::string>(words.begin() + 1, words.end()), dir.path());
  std::filesystem::current_path(home);
  return result;
}

// A small layered-planes light field made through the CLI itself: `views` x `views` views of
// `size` x `size` pixels, in `dir`.
inline std::filesystem::path makeSynthLightField(const TempDir& dir, int views = 5, int size = 48) {
  const std::filesystem::path path = dir / "small.lf.h5";
  const auto result = runLfcam(
      {"synth", "--views", std::to_string(views), "--size", std::to_string(size), "-o", path.string()}, dir.path());
  EXPECT_EQ(result.exitStatus, 0) << result.err;
  return path;
}

}  // namespace lfcam::test
