// Refocuses a small layered-planes light field through the installed library, and writes it as an
// MP4 through the installed module that loads FFmpeg on first use (found through the run path
// that the package's link options give this program).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/render/animation.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"

int main() {
  const auto planes = lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(5, 32));
  const lfcam::Image photo = lfcam::refocus(planes.lightField, 0.5);
  std::printf("refocused %dx%d\n", photo.width(), photo.height());
  const auto video = std::filesystem::temp_directory_path() / ("lfcam-consumer-" + std::to_string(getpid()) + ".mp4");
  std::vector<lfcam::Image> frames;
  frames.push_back(photo.copy());
  frames.push_back(photo.copy());
  const lfcam::Status written = lfcam::writeMp4Video(video, frames, 10);
  if (!written) {
    std::printf("%s\n", written.error().message.c_str());
    return 1;
  }
  const auto summary = lfcam::readVideoSummary(video);
  std::filesystem::remove(video);
  if (!summary) return 1;
  std::printf("wrote and read back an MP4 of %d frames\n", summary->frames);
  return photo.width() == 32 && photo.height() == 32 && summary->frames == 2 ? 0 : 1;
}
