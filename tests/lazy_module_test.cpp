// Modules loaded on first use (core/lazy_module.hpp): found through the run path, and a module or
// entry that cannot be loaded is one error naming what needed it, never a crash.
#include "core/lazy_module.hpp"

#include <gtest/gtest.h>

#include "raw_io/camera_raw_codec.hpp"
#include "render/mp4_codec.hpp"

namespace lfcam {
namespace {

TEST(LazyModule, BuiltModulesLoadAndExportTheirTables) {
  for (const auto& [name, entry] :
       {std::pair{"mp4", LFCAM_MP4_CODEC_ENTRY}, std::pair{"libraw", LFCAM_CAMERA_RAW_CODEC_ENTRY}}) {
    auto table = lazyModuleEntry(name, entry, "this test");
    ASSERT_TRUE(table) << table.error().message;
    EXPECT_NE(*table, nullptr);
  }
}

TEST(LazyModule, AMissingModuleOrEntryIsAnUnsupportedErrorSayingWhatNeededIt) {
  auto missing = lazyModuleEntry("absent", "anything", "the absent feature");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::Unsupported);
  EXPECT_NE(missing.error().message.find("the absent feature needs lfcam's module liblfcam_absent.so"),
            std::string::npos)
      << missing.error().message;
  EXPECT_EQ(missing.error().message.find('\n'), std::string::npos);

  auto noEntry = lazyModuleEntry("mp4", "noSuchEntry", "MP4 export");
  ASSERT_FALSE(noEntry);
  EXPECT_NE(noEntry.error().message.find("noSuchEntry"), std::string::npos) << noEntry.error().message;
}

}  // namespace
}  // namespace lfcam
