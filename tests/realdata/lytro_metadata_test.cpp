// Real Lytro metadata (../shared/data/lytro-metadata) and processed containers
// (../shared/data/lytro-lfp): the values lfcam extracts, checked against the files' own numbers,
// and their refocus stacks as living pictures.
#include <gtest/gtest.h>

#include <fstream>

#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "raw_io/lytro_contents.hpp"
#include "raw_io/lytro_metadata.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

nlohmann::json load(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(LytroMetadataRealData, FirstGenerationFrame) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", dir);
  const nlohmann::json doc = load(dir / "IMG_0001__frame.json");
  const nlohmann::json* meta = findLytroFrameMetadata(doc);
  ASSERT_NE(meta, nullptr);
  auto f = parseLytroFrameMetadata(*meta, "IMG_0001__frame.json");
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_EQ(f->width, 3280);
  EXPECT_EQ(f->height, 3280);
  EXPECT_EQ(f->packing, RawPacking::Bits12BigEndian);
  EXPECT_EQ(f->colorFilter, ColorFilter::BGGR);
  EXPECT_EQ(f->blackLevel, 168);
  EXPECT_EQ(f->whiteLevel, 4095);
  ASSERT_TRUE(f->lenslet);
  EXPECT_NEAR(f->lenslet->pitchPx, 13.8986 / 1.4, 1e-4);
  EXPECT_NEAR(f->lenslet->rotationRad, 0.0019290975760668516, 1e-15);
  EXPECT_NEAR(f->lenslet->offsetPx[0], -2.7138671874999998e-6 / 1.3999999761581417e-6, 1e-9);
  EXPECT_EQ(f->lenslet->packing, Packing::Hexagonal);
  ASSERT_TRUE(f->whiteBalance && f->colorMatrix);
  EXPECT_NEAR((*f->whiteBalance)[1], 1.1171875, 1e-12);
  EXPECT_NEAR((*f->whiteBalance)[2], 1.72265625, 1e-12);
  EXPECT_NEAR((*f->colorMatrix)[0], 3.1115827560424805, 1e-12);
  EXPECT_EQ(f->camera, "Lytro, Inc. F01");
}

TEST(LytroMetadataRealData, IllumWhiteImages) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", dir);
  for (const char* name : {"MOD_0015.json", "MOD_0015.TXT", "lenslet_whiteimage.TXT"}) {
    const nlohmann::json doc = load(dir / name);
    const nlohmann::json* meta = findLytroFrameMetadata(doc);
    ASSERT_NE(meta, nullptr) << name;
    auto f = parseLytroFrameMetadata(*meta, name);
    ASSERT_TRUE(f) << f.error().message;
    EXPECT_EQ(f->width, 7728) << name;
    EXPECT_EQ(f->height, 5368) << name;
    EXPECT_EQ(f->packing, RawPacking::Bits10LittleEndian) << name;
    EXPECT_EQ(f->colorFilter, ColorFilter::GRBG) << name;
    EXPECT_EQ(f->blackLevel, 64) << name;
    EXPECT_EQ(f->whiteLevel, 1023) << name;
    ASSERT_TRUE(f->lenslet);
    EXPECT_NEAR(f->lenslet->pitchPx, 20.0 / 1.4, 1e-4) << name;
    EXPECT_EQ(f->lenslet->packing, Packing::Hexagonal);
  }
  const nlohmann::json mod = load(dir / "MOD_0015.json");
  auto f = parseLytroFrameMetadata(*findLytroFrameMetadata(mod), "MOD_0015.json");
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->lenslet->rotationRad, 0.0009425521711818874, 1e-15);
}

TEST(LytroMetadataRealData, IllumPictureMetadataLightningLayout) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-metadata", dir);
  for (const char* name : {"books.json", "toy.json"}) {
    const nlohmann::json doc = load(dir / name);
    auto f = parseLytroFrameMetadata(doc, name);  // the document itself has "image"
    ASSERT_TRUE(f) << f.error().message;
    EXPECT_EQ(f->width, 7728);
    EXPECT_EQ(f->packing, RawPacking::Bits10LittleEndian);
    EXPECT_EQ(f->colorFilter, ColorFilter::GRBG);
    EXPECT_EQ(f->blackLevel, 66);
    EXPECT_EQ(f->whiteLevel, 1023);
    ASSERT_TRUE(f->whiteBalance);
    EXPECT_NEAR((*f->whiteBalance)[0], 1.5122205018997192, 1e-12);
  }
}

TEST(LytroContainerRealData, ProcessedFilesAreDescribed) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-lfp", dir);
  struct Expect {
    const char* file;
    int sections, jpegs, h264, depth;
  };
  for (const Expect& e : {Expect{"IMG_0001-stk.lfp", 15, 12, 0, 1}, Expect{"IMG_0002-stk.lfp", 5, 0, 2, 1},
                          Expect{"IMG_0002-dm.lfp", 4, 0, 0, 1}, Expect{"demo.LFP", 13, 10, 0, 1}}) {
    auto container = readLytroContainer(dir / e.file);
    ASSERT_TRUE(container) << container.error().message;
    EXPECT_EQ(int(container->sections.size()), e.sections) << e.file;
    // The table of contents matches the JSON extracted by python-lfp-reader.
    const std::string stem = std::filesystem::path(e.file).stem().string();
    EXPECT_EQ(container->tableOfContents, load(dir / (stem + "_LFM_metadata.json"))) << e.file;
    const LytroContents contents = describeLytroContainer(*container);
    int jpegs = 0, h264 = 0, depth = 0;
    for (const LytroItem& item : contents.items) {
      jpegs += item.kind == LytroItemKind::Jpeg;
      h264 += item.kind == LytroItemKind::H264;
      depth += item.kind == LytroItemKind::DepthMap;
    }
    EXPECT_EQ(jpegs, e.jpegs) << e.file;
    EXPECT_EQ(h264, e.h264) << e.file;
    EXPECT_EQ(depth, e.depth) << e.file;
  }
  auto demo = readLytroContainer(dir / "demo.LFP");
  ASSERT_TRUE(demo);
  const LytroContents contents = describeLytroContainer(*demo);
  ASSERT_TRUE(contents.summary.contains("frame"));
  EXPECT_EQ(contents.summary["frame"]["sensor"], nlohmann::json({7728, 5368}));
  EXPECT_EQ(contents.summary["frame"]["bayer"], "GRBG");
}

// The refocus stacks of the processed containers: every JPEG slice with its lambda, in order, and
// the depth map; the H.264 stack is refused in one line.
TEST(LytroContainerRealData, RefocusStacksBecomeLivingPictures) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-lfp", dir);
  struct Expected {
    const char* file;
    std::size_t slices;
    int depthWidth, depthHeight;
  };
  for (const Expected& expected : {Expected{"IMG_0001-stk.lfp", 12, 20, 20}, Expected{"demo.LFP", 10, 88, 60}}) {
    auto stack = readLytroRefocusStack(dir / expected.file);
    ASSERT_TRUE(stack) << stack.error().message;
    EXPECT_EQ(stack->slices.size(), expected.slices) << expected.file;
    for (std::size_t i = 1; i < stack->slices.size(); ++i)
      EXPECT_LT(stack->slices[i - 1].lambda, stack->slices[i].lambda) << expected.file;
    for (const LytroRefocusSlice& slice : stack->slices)
      ASSERT_TRUE(slice.jpeg.size() > 2 && slice.jpeg[0] == 0xFF && slice.jpeg[1] == 0xD8) << expected.file;
    EXPECT_EQ(stack->depth.width(), expected.depthWidth) << expected.file;
    EXPECT_EQ(stack->depth.height(), expected.depthHeight) << expected.file;
    auto page = makeLytroLivingPicture(*stack, "test");
    ASSERT_TRUE(page) << page.error().message;
    EXPECT_NE(page->find("\"positions\""), std::string::npos);
    EXPECT_EQ(page->find("{{LFCAM_DATA}}"), std::string::npos);
  }
  auto h264 = readLytroRefocusStack(dir / "IMG_0002-stk.lfp");
  ASSERT_FALSE(h264);
  EXPECT_EQ(h264.error().message.find('\n'), std::string::npos);
  EXPECT_NE(h264.error().message.find("IMG_0002-stk.lfp"), std::string::npos);
}

}  // namespace
}  // namespace lfcam
