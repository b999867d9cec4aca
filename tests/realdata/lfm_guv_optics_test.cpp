// napari-LF's own metadata.txt beside its GUV sample (../shared/data/lfm-guv): lfcam reads the
// microscope it describes, and that microscope's PSF window is one lfcam can sample.
#include <gtest/gtest.h>

#include "lfcam/lfm/optics.hpp"
#include "lfcam/lfm/psf.hpp"
#include "test_support.hpp"

namespace lfcam {

TEST(LfmGuvOptics, ReadsNapariLfsMetadataAndPlansItsPsfWindow) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  const auto optics = parseNapariLfOptics(test::readBytes(folder / "metadata.txt"), "metadata.txt");
  ASSERT_TRUE(optics) << optics.error().message;
  EXPECT_EQ(optics->magnification, 60);
  EXPECT_EQ(optics->numericalAperture, 1.2);
  EXPECT_EQ(optics->immersionIndex, 1.35);
  EXPECT_EQ(optics->wavelengthNm, 593);
  EXPECT_EQ(optics->microlensPitchUm, 100);
  EXPECT_EQ(optics->microlensFocalLengthUm, 2500);
  EXPECT_EQ(optics->pixelSizeUm, 6.5);
  EXPECT_EQ(optics->supersample, 3);
  // Its 15 slices a micrometre apart reach 7 um from focus: a blur 815 um in radius, 9 lenslets a
  // side of the centre one, and one of margin on each side.
  const int lenslets = LfmPsf::lensletsFor(optics.value(), 7);
  EXPECT_EQ(lenslets, 21);
  EXPECT_TRUE(LfmPsf::create(optics.value(), lenslets));
}

}  // namespace lfcam
