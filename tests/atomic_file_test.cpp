#include "core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

Status writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  return out ? Status{} : makeError(ErrorCode::Io, path.string() + ": cannot write");
}

TEST(AtomicFile, FailureKeepsTheOldFileAndLeavesNoTemporary) {
  test::TempDir dir;
  const fs::path target = dir / "out.txt";
  ASSERT_TRUE(writeText(target, "old"));
  Status status = writeFileAtomically(target, [](const fs::path& tmp) -> Status {
    EXPECT_EQ(tmp.extension(), ".txt");
    LFCAM_TRY(writeText(tmp, "partial"));
    return makeError(ErrorCode::Format, "failed half way");
  });
  EXPECT_FALSE(status);
  EXPECT_EQ(readText(target), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(AtomicFile, SuccessReplaces) {
  test::TempDir dir;
  const fs::path target = dir / "out.txt";
  ASSERT_TRUE(writeText(target, "old"));
  ASSERT_TRUE(writeFileAtomically(target, [](const fs::path& tmp) { return writeText(tmp, "new"); }));
  EXPECT_EQ(readText(target), "new");
}

TEST(AtomicFile, FolderAppearsOnlyOnSuccess) {
  test::TempDir dir;
  const fs::path target = dir / "views";
  EXPECT_FALSE(writeFolderAtomically(target, [](const fs::path& tmp) -> Status {
    LFCAM_TRY(writeText(tmp / "a.txt", "a"));
    return makeError(ErrorCode::Format, "no");
  }));
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 0);
  ASSERT_TRUE(writeFolderAtomically(target, [](const fs::path& tmp) { return writeText(tmp / "a.txt", "a"); }));
  EXPECT_EQ(readText(target / "a.txt"), "a");
  // Into an existing folder: new files arrive, others stay.
  ASSERT_TRUE(writeText(target / "keep.txt", "k"));
  ASSERT_TRUE(writeFolderAtomically(target, [](const fs::path& tmp) { return writeText(tmp / "b.txt", "b"); }));
  EXPECT_EQ(readText(target / "b.txt"), "b");
  EXPECT_EQ(readText(target / "keep.txt"), "k");
}

}  // namespace
}  // namespace lfcam
