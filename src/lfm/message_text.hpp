// The numbers and usage errors of the lfm module's one-line messages.
#pragma once

#include <cstdio>
#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam::lfm {

// `x` as printf's `format` writes it: "%g" for settings, fewer or more digits where a message
// needs them.
inline std::string number(double x, const char* format = "%g") {
  char text[40];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

inline Error usage(std::string message) { return makeError(ErrorCode::Usage, std::move(message)); }

}  // namespace lfcam::lfm
