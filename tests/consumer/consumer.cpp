// Refocuses a small layered-planes light field through the installed library.
#include <cstdio>

#include "lfcam/layered_planes.hpp"
#include "lfcam/refocus.hpp"

int main() {
  const auto planes = lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(5, 32));
  const lfcam::Image photo = lfcam::refocus(planes.lightField, 0.5);
  std::printf("refocused %dx%d\n", photo.width(), photo.height());
  return photo.width() == 32 && photo.height() == 32 ? 0 : 1;
}
