// The small light-field microscope of the lfm tests: 20x / 0.5 water at 500 nm, 40 um lenslets at
// f/20, 4 um pixels (10 a lenslet) sampled twice each way: PSF windows of a few lenslets, quick.
#pragma once

#include "lfcam/lfm/optics.hpp"

namespace lfcam::test {

inline LfmOptics smallMicroscope() {
  return LfmOptics{.magnification = 20,
                   .numericalAperture = 0.5,
                   .immersionIndex = 1.33,
                   .wavelengthNm = 500,
                   .tubeFocalLengthMm = 200,
                   .microlensPitchUm = 40,
                   .microlensFocalLengthUm = 800,
                   .microlensFillFactor = 1,
                   .pixelSizeUm = 4,
                   .supersample = 2};
}

}  // namespace lfcam::test
