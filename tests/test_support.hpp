// Helpers shared by the test binaries.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace lfcam::test {

// The real-data folder: $LFCAM_DATA_DIR, else the one CMake was told (../shared/data).
inline std::filesystem::path sharedDataDir() {
  if (const char* env = std::getenv("LFCAM_DATA_DIR")) return env;
#ifdef LFCAM_SHARED_DATA_DIR
  return LFCAM_SHARED_DATA_DIR;
#else
  return {};
#endif
}

inline std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// A fresh, empty folder for one test, removed with it.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "lfcam";
    path_ = std::filesystem::temp_directory_path() / ("lfcam-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace lfcam::test

// Skips the current test, with a visible message, when ../shared/data/<sub> is absent.
#define LFCAM_REQUIRE_SHARED_DATA(sub, var)                                 \
  const std::filesystem::path var = ::lfcam::test::sharedDataDir() / (sub); \
  if (!std::filesystem::exists(var))                                        \
  GTEST_SKIP() << "real data not found at " << var << " (set LFCAM_DATA_DIR to the shared data folder to run this test)"
