// napari-LF's own metadata.txt beside its GUV sample (../shared/data/lfm-guv): lfcam reads the
// microscope it describes, and that microscope's PSF window is one lfcam can sample.
#include <gtest/gtest.h>

#include "lfcam/lfm/optics.hpp"
#include "lfcam/lfm/psf.hpp"
#include "lfcam/lfm/volume_request.hpp"
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

TEST(LfmGuvOptics, ReadsNapariLfsCalibrationFileAsItsMetadata) {
  // The .lfc napari-LF made for its 10-slice reference volume: the same microscope as the
  // metadata.txt beside it, and the slices it was made for.
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  const auto fromLfc = volumeRequestFrom(
      {.opticsFile = (folder / "reference_outputs_napariLF" / "Calibration_GUVExperim1-10.lfc").string()});
  ASSERT_TRUE(fromLfc) << fromLfc.error().message;
  const auto fromText =
      volumeRequestFrom({.opticsFile = (folder / "reference_outputs_napariLF" / "metadata.txt").string()});
  ASSERT_TRUE(fromText) << fromText.error().message;
  const LfmOptics &a = fromLfc->optics, &b = fromText->optics;
  EXPECT_EQ(a.magnification, b.magnification);
  EXPECT_EQ(a.numericalAperture, b.numericalAperture);
  EXPECT_EQ(a.immersionIndex, b.immersionIndex);
  EXPECT_EQ(a.wavelengthNm, b.wavelengthNm);
  EXPECT_EQ(a.tubeFocalLengthMm, b.tubeFocalLengthMm);
  EXPECT_EQ(a.microlensPitchUm, b.microlensPitchUm);
  EXPECT_EQ(a.microlensFocalLengthUm, b.microlensFocalLengthUm);
  EXPECT_EQ(a.microlensFillFactor, b.microlensFillFactor);
  EXPECT_EQ(a.pixelSizeUm, b.pixelSizeUm);
  EXPECT_EQ(fromLfc->slices, 10);
  EXPECT_EQ(fromLfc->umPerSlice, 1);
  EXPECT_EQ(fromLfc->zCenterUm, 0);
}

}  // namespace lfcam
