// napari-LF's reconstruction of the lfm-guv capture (reference_outputs_napariLF/output_stack-10.tif,
// written by tifffile: 10 pages of 32-bit floats, no ImageJ calibration) reads as a volume, and
// lfcam's own reconstruction of the capture with napari-LF's settings agrees with it.
#include <gtest/gtest.h>

#include <cmath>

#include <algorithm>
#include <cstdio>
#include <functional>

#include "lfcam/decode/decode_files.hpp"
#include "lfcam/io/image_io.hpp"
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

TEST(LfmGuvVolume, AgreesWithNapariLfOnItsOwnSettings) {
  // The raw decoded by lfcam with the radiometry frame as its white image and the dark frame (16
  // views, as napari-LF rectifies it), reconstructed with napari-LF's own settings (10 slices 1 um
  // apart, 4 voxels a lenslet, 15 Richardson-Lucy iterations), against its output_stack-10.tif.
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  RawFiles files{.raw = (folder / "Lightfield_GUVExperim1.tif").string(),
                 .white = (folder / "Radiometry_GUVExperim1.tif").string(),
                 .dark = (folder / "DarkFrame_GUVExperim1.tif").string()};
  files.decode.views = 16;
  auto frame = decodeRawFiles(files);
  ASSERT_TRUE(frame) << frame.error().message;
  const auto napari = folder / "reference_outputs_napariLF";
  auto request = parseLfmSettings(test::readBytes(napari / "metadata.txt"), "metadata.txt");
  ASSERT_TRUE(request) << request.error().message;
  EXPECT_EQ(request->slices, 10);
  EXPECT_EQ(request->supersample, 4);
  EXPECT_EQ(request->reconstruct.iterations, 15);
  auto ours = reconstructVolume(frame.value(), request.value(), "Lightfield_GUVExperim1.tif");
  ASSERT_TRUE(ours) << ours.error().message;
  auto theirs = readVolume(napari / "output_stack-10.tif");
  ASSERT_TRUE(theirs) << theirs.error().message;
  const Volume& a = ours->reconstruction.volume;
  const Volume& b = theirs.value();
  ASSERT_EQ(a.depth(), b.depth());
  // The two decodes crop different lenslets (lfcam 28 x 28, napari-LF 28 x 27): the voxels of
  // napari-LF's volume shifted by (dx, dy) within two lenslets, the best shift reported.
  const int d = a.depth();
  // The conventions the two could differ in: the slices' order, the lateral axes' directions.
  struct Match {
    double whole = -2;
    int dx = 0, dy = 0;
    bool reversed = false, flipped = false;
  } best;
  auto reader = [&](const Match& m) {
    return [&, m](int x, int y, int z) {
      if (m.flipped) x = a.width() - 1 - x, y = a.height() - 1 - y;
      const int bx = x + m.dx, by = y + m.dy, bz = m.reversed ? d - 1 - z : z;
      return bx >= 0 && by >= 0 && bx < b.width() && by < b.height() ? b.at(bx, by, bz) : 0.0f;
    };
  };
  for (bool reversed : {false, true})
    for (bool flipped : {false, true})
      for (int dy = -8; dy <= 8; ++dy)
        for (int dx = -8; dx <= 8; ++dx) {
          const Match m{.dx = dx, .dy = dy, .reversed = reversed, .flipped = flipped};
          const double whole = crossCorrelation(a, 0, d, reader(m));
          if (whole > best.whole) best = m, best.whole = whole;
        }
  const auto at = reader(best);
  std::printf("[ napari ] whole volume NCC %.3f at voxel shift (%d, %d)%s%s; per slice:", best.whole, best.dx, best.dy,
              best.reversed ? ", slices reversed" : "", best.flipped ? ", x and y flipped" : "");
  for (int z = 0; z < d; ++z) std::printf(" %.2f", crossCorrelation(a, z, z + 1, at));
  std::printf("\n[ napari ] brightest slice: lfcam %d, napari-LF %d (of %d, %g um apart)\n", brightestSlice(a),
              brightestSlice(b), d, a.voxelDepthUm);
  EXPECT_FALSE(best.reversed);  // the slices run the same way
  EXPECT_FALSE(best.flipped);
  EXPECT_EQ(brightestSlice(a), brightestSlice(b));
  EXPECT_GT(best.whole, 0.5);
}

}  // namespace
}  // namespace lfcam
