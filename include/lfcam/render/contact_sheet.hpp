// The contact sheet of a light field (the paper's Figure 4 shows two of its tiles): every
// sub-aperture image, laid out in a grid as the views sit on the lens (u across, v down).
#pragma once

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam {

struct ContactSheetOptions {
  int gap = 2;           // pixels between views, filled with `background`
  float background = 0;  // linear value
  int maxWidth = 2400;   // views are shrunk by a whole factor (box filter) to fit
};

Image contactSheet(const LightField& lightField, const ContactSheetOptions& options = {});

}  // namespace lfcam
