// napari-LF's reconstruction of the lfm-guv capture (reference_outputs_napariLF/output_stack-10.tif,
// written by tifffile: 10 pages of 32-bit floats, no ImageJ calibration) reads as a volume.
#include <gtest/gtest.h>

#include <cmath>

#include <algorithm>
#include <cstdio>
#include <functional>

#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/io/volume_io.hpp"
#include "lfcam/lfm/volume_request.hpp"
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

// Normalised cross-correlation of a and a volume read through bAt, over slices [zFirst, zEnd).
double crossCorrelation(const Volume& a, int zFirst, int zEnd, const std::function<float(int, int, int)>& bAt) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, count = 0;
  for (int z = zFirst; z < zEnd; ++z)
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x) {
        const double va = a.at(x, y, z), vb = bAt(x, y, z);
        sa += va, sb += vb, saa += va * va, sbb += vb * vb, sab += va * vb, ++count;
      }
  const double cov = sab - sa * sb / count, va = saa - sa * sa / count, vb = sbb - sb * sb / count;
  return cov / std::sqrt(va * vb);
}

int brightestSlice(const Volume& v) {
  int best = 0;
  float bestValue = -1;
  for (int z = 0; z < v.depth(); ++z) {
    const float* slice = v.slice(z);
    const float peak = *std::max_element(slice, slice + v.sliceSize());
    if (peak > bestValue) bestValue = peak, best = z;
  }
  return best;
}

TEST(LfmGuvVolume, ComparesWithNapariLfOnItsOwnSettings) {
  // napari-LF's rectified frame (16 pixels a lenslet) and settings (10 slices 1 um apart, 4 voxels
  // a lenslet, 15 Richardson-Lucy iterations) against its output_stack-10.tif.
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv/reference_outputs_napariLF", folder);
  auto frame = readLightField(folder / "LightfieldRectified.png", {.lensletViews = 16});
  ASSERT_TRUE(frame) << frame.error().message;
  auto request = parseLfmSettings(test::readBytes(folder / "metadata.txt"), "metadata.txt");
  ASSERT_TRUE(request) << request.error().message;
  EXPECT_EQ(request->slices, 10);
  EXPECT_EQ(request->supersample, 4);
  EXPECT_EQ(request->reconstruct.iterations, 15);
  auto ours = reconstructVolume(frame.value(), request.value(), "LightfieldRectified.png");
  ASSERT_TRUE(ours) << ours.error().message;
  auto theirs = readVolume(folder / "output_stack-10.tif");
  ASSERT_TRUE(theirs) << theirs.error().message;
  const Volume& a = ours->reconstruction.volume;
  const Volume& b = theirs.value();
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.depth(), b.depth());
  const int w = a.width(), h = a.height(), d = a.depth();
  // The conventions lfcam and napari-LF could differ in: the order of the slices and the lateral axes.
  const std::pair<const char*, std::function<float(int, int, int)>> orientations[] = {
      {"as stored", [&](int x, int y, int z) { return b.at(x, y, z); }},
      {"slices reversed", [&](int x, int y, int z) { return b.at(x, y, d - 1 - z); }},
      {"x and y flipped", [&](int x, int y, int z) { return b.at(w - 1 - x, h - 1 - y, z); }},
      {"both", [&](int x, int y, int z) { return b.at(w - 1 - x, h - 1 - y, d - 1 - z); }},
  };
  for (const auto& [name, at] : orientations) {
    const double whole = crossCorrelation(a, 0, d, at);
    std::printf("[ napari ] %-16s whole volume NCC %.3f; per slice:", name, whole);
    for (int z = 0; z < d; ++z) std::printf(" %.2f", crossCorrelation(a, z, z + 1, at));
    std::printf("\n");
  }
  std::printf("[ napari ] brightest slice: lfcam %d, napari-LF %d (of %d, %g um apart)\n", brightestSlice(a),
              brightestSlice(b), d, a.voxelDepthUm);
  // A report, not yet an agreement: lfcam's volume piles its light into one voxel a lenslet near
  // the native plane where napari-LF's shows the vesicle (NCC about 0; issue 52's open part).
  for (float value : a.voxels()) ASSERT_TRUE(std::isfinite(value) && value >= 0);
}

}  // namespace
}  // namespace lfcam
