// LfmOptics: its validation's one-line refusals and napari-LF's metadata.txt.
#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/lfm/optics.hpp"

namespace lfcam {
namespace lfm_optics_test {

std::string refusal(const LfmOptics& optics) {
  const Status status = validateLfmOptics(optics);
  return status ? std::string() : status.error().message;
}

// The "calibrate" section of ../shared/data/lfm-guv/metadata.txt (napari-LF's GUV sample), trimmed.
const char* kNapariMetadata = R"({
  "main": {"comments": "GUV"},
  "calibrate": {
    "ulens_pitch": 100.0, "pixel_size": 6.5, "ulens_focal_length": 2500.0, "ulens_focal_distance": 2500.0,
    "objective_magnification": 60, "objective_na": 1.2, "tubelens_focal_length": 200.0,
    "center_wavelength": 593.0, "medium_index": 1.35, "ulens_fill_factor": 1.0, "pixel_fill_factor": 1.0,
    "ulens_profile": "rect", "num_slices": 15, "um_per_slice": 1.0, "supersample": 3
  }
})";

}  // namespace lfm_optics_test

using namespace lfm_optics_test;

TEST(LfmOptics, DefaultsAreValid) { EXPECT_EQ(refusal(LfmOptics{}), ""); }

TEST(LfmOptics, RefusesInOneLine) {
  EXPECT_EQ(refusal(LfmOptics{.numericalAperture = 1.4, .immersionIndex = 1.33}),
            "NA 1.4 above the immersion index 1.33: no light reaches the objective");
  EXPECT_EQ(refusal(LfmOptics{.microlensFocalLengthUm = 0}), "microlens focal length must be positive, got 0");
  EXPECT_EQ(refusal(LfmOptics{.microlensFocalLengthUm = -2500}), "microlens focal length must be positive, got -2500");
  EXPECT_EQ(refusal(LfmOptics{.magnification = std::nan("")}), "magnification must be positive, got nan");
  EXPECT_EQ(refusal(LfmOptics{.immersionIndex = 0.9}),
            "immersion index 0.9 below 1: no medium is less dense than vacuum");
  EXPECT_EQ(refusal(LfmOptics{.microlensFillFactor = 1.5}), "microlens fill factor 1.5 outside (0, 1]");
  EXPECT_EQ(refusal(LfmOptics{.supersample = 0}), "supersample 0 outside [1, 64]");
  EXPECT_EQ(validateLfmOptics(LfmOptics{.pixelSizeUm = 0}).error().code, ErrorCode::Usage);
}

TEST(LfmOptics, ReadsNapariLfMetadata) {
  // Defaults other than napari's sample, so every value read is seen to be read.
  const LfmOptics other{.magnification = 1,
                        .numericalAperture = 0.1,
                        .immersionIndex = 1,
                        .wavelengthNm = 1,
                        .tubeFocalLengthMm = 1,
                        .microlensPitchUm = 1,
                        .microlensFocalLengthUm = 1,
                        .microlensFillFactor = 0.5,
                        .pixelSizeUm = 1,
                        .supersample = 1};
  const Result<LfmOptics> optics = parseNapariLfOptics(kNapariMetadata, "metadata.txt", other);
  ASSERT_TRUE(optics) << optics.error().message;
  EXPECT_EQ(optics->magnification, 60);
  EXPECT_EQ(optics->numericalAperture, 1.2);
  EXPECT_EQ(optics->immersionIndex, 1.35);
  EXPECT_EQ(optics->wavelengthNm, 593);
  EXPECT_EQ(optics->tubeFocalLengthMm, 200);
  EXPECT_EQ(optics->microlensPitchUm, 100);
  EXPECT_EQ(optics->microlensFocalLengthUm, 2500);
  EXPECT_EQ(optics->microlensFillFactor, 1);
  EXPECT_EQ(optics->pixelSizeUm, 6.5);
  // napari-LF's supersample is the volume's voxels a lenslet, not the field's samples a pixel.
  EXPECT_EQ(optics->supersample, 1);
  EXPECT_DOUBLE_EQ(optics->objectiveFocalLengthUm(), 200e3 / 60);
}

TEST(LfmOptics, ReadsAHexagonalArray) {
  const Result<LfmOptics> optics = parseNapariLfOptics(R"({"calibrate": {"ulens_array": "hexagonal"}})", "optics.json");
  ASSERT_TRUE(optics) << optics.error().message;
  EXPECT_EQ(optics->array, MicrolensLayout::Hexagonal);
  EXPECT_EQ(optics->rowsPerPeriod(), 2);
  EXPECT_DOUBLE_EQ(optics->rowPitchUm(), 100 * std::sqrt(3.0) / 2);
  EXPECT_EQ(parseNapariLfOptics(R"({"calibrate": {}})", "optics.json")->array, MicrolensLayout::Square);
}

TEST(LfmOptics, RefusesNapariLfMetadataItDoesNotModel) {
  auto refused = [](std::string text) {
    const Result<LfmOptics> optics = parseNapariLfOptics(text, "metadata.txt");
    return optics ? std::string() : optics.error().message;
  };
  EXPECT_EQ(refused("{"), "metadata.txt: not JSON");
  EXPECT_EQ(refused(R"({"main": {}})"), "metadata.txt: no \"calibrate\" section");
  EXPECT_EQ(refused(R"({"calibrate": {"objective_na": "1.2"}})"),
            "metadata.txt: calibrate.objective_na: expected a number");
  EXPECT_EQ(refused(R"({"calibrate": {"ulens_profile": "circ"}})"),
            "metadata.txt: calibrate.ulens_profile: only \"rect\" (apertures filling their cells) is modelled");
  EXPECT_EQ(refused(R"({"calibrate": {"ulens_array": "round"}})"),
            "metadata.txt: calibrate.ulens_array: expected \"square\" or \"hexagonal\", got \"round\"");
  EXPECT_EQ(refused(R"({"calibrate": {"ulens_array": 6}})"),
            "metadata.txt: calibrate.ulens_array: expected \"square\" or \"hexagonal\", got 6");
  EXPECT_EQ(refused(R"({"calibrate": {"ulens_focal_distance": 2400}})"),
            "metadata.txt: calibrate.ulens_focal_distance 2400 differs from ulens_focal_length: only a sensor at "
            "the microlens focal plane is modelled");
  EXPECT_EQ(refused(R"({"calibrate": {"objective_na": 1.4, "medium_index": 1.33}})"),
            "metadata.txt: NA 1.4 above the immersion index 1.33: no light reaches the objective");
}

}  // namespace lfcam
