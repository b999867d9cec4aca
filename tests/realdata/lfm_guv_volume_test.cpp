// napari-LF's reconstruction of the lfm-guv capture (reference_outputs_napariLF/output_stack-10.tif,
// written by tifffile: 10 pages of 32-bit floats, no ImageJ calibration) reads as a volume.
#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/io/image_io.hpp"
#include "lfcam/io/volume_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

TEST(LfmGuvVolume, ReadsNapariLfsStack) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv/reference_outputs_napariLF/output_stack-10.tif", stack);
  auto header = readImageHeader(stack);
  ASSERT_TRUE(header) << header.error().message;
  EXPECT_EQ(header->sampleType, SampleType::Float32);
  EXPECT_EQ(header->channels, 1);

  auto volume = readVolume(stack);
  ASSERT_TRUE(volume) << volume.error().message;
  EXPECT_EQ(volume->width(), 112);
  EXPECT_EQ(volume->height(), 108);
  EXPECT_EQ(volume->depth(), 10);
  // tifffile's resolution 1/1 without a unit, and no spacing: lfcam's defaults.
  EXPECT_EQ(volume->voxelWidthUm, 1);
  EXPECT_EQ(volume->voxelDepthUm, 1);
  EXPECT_EQ(volume->firstSliceUm, 0);
  double sum = 0;
  for (float value : volume->voxels()) {
    ASSERT_TRUE(std::isfinite(value));
    sum += std::abs(value);
  }
  EXPECT_GT(sum, 0);  // a reconstruction, not an empty stack

  // And lfcam's own stack of it reads back the same.
  test::TempDir dir;
  ASSERT_TRUE(writeVolume(dir / "stack.tif", *volume));
  auto again = readVolume(dir / "stack.tif");
  ASSERT_TRUE(again) << again.error().message;
  ASSERT_EQ(again->voxels().size(), volume->voxels().size());
  for (std::size_t i = 0; i < volume->voxels().size(); ++i) ASSERT_EQ(again->voxels()[i], volume->voxels()[i]);
}

}  // namespace
}  // namespace lfcam
