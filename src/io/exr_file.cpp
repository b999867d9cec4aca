#include "io/exr_file.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <tuple>
#include <vector>

#include "io/io_support.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kDescriptionAttribute = "comments";  // the standard attribute, where OpenImageIO kept it

// Colour channels first, alpha next, the rest by name with a trailing number compared as a number.
auto channelOrder(const std::string& name) {
  static const std::vector<std::string> colour = {"R", "G", "B", "Y"};
  const auto at = std::find(colour.begin(), colour.end(), name);
  const int rank = at != colour.end() ? int(at - colour.begin()) : name == "A" ? 4 : 5;
  std::size_t digits = name.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
  const std::string stem = name.substr(0, digits), number = name.substr(digits);
  return std::make_tuple(rank, stem, number.size(), number);
}

std::vector<std::string> orderedChannels(const Imf::Header& header) {
  std::vector<std::string> names;
  for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel)
    names.emplace_back(channel.name());
  std::sort(names.begin(), names.end(),
            [](const std::string& a, const std::string& b) { return channelOrder(a) < channelOrder(b); });
  return names;
}

ExrHeader headerOf(const Imf::Header& header) {
  const Imath::Box2i window = header.dataWindow();
  ExrHeader out{window.max.x - window.min.x + 1, window.max.y - window.min.y + 1, 0, {}};
  for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel) ++out.channels;
  if (const auto* text = header.findTypedAttribute<Imf::StringAttribute>(kDescriptionAttribute))
    out.description = text->value();
  return out;
}

}  // namespace

Result<ExrHeader> readExrHeader(const fs::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    return headerOf(file.header());
  } catch (const std::exception& e) {
    return fileError(ErrorCode::Format, path, std::string("not a readable OpenEXR file: ") + e.what());
  }
}

Result<Image> readExr(const fs::path& path, const std::function<Status(const ExrHeader&)>& checkHeader) {
  try {
    Imf::InputFile file(path.c_str());
    const ExrHeader header = headerOf(file.header());
    if (header.width <= 0 || header.height <= 0 || header.channels <= 0)
      return fileError(ErrorCode::Format, path, "not a readable image: no pixels");
    LFCAM_TRY(checkHeader(header));
    Image image(header.width, header.height, header.channels);
    Imf::FrameBuffer frame;
    const Imath::Box2i window = file.header().dataWindow();
    const std::vector<std::string> names = orderedChannels(file.header());
    for (int c = 0; c < header.channels; ++c)
      frame.insert(names[std::size_t(c)], Imf::Slice::Make(Imf::FLOAT, image.plane(c), window));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    return fileError(ErrorCode::Format, path, std::string("not a readable OpenEXR file: ") + e.what());
  }
}

Status writeExr(const fs::path& temporary, const fs::path& path, const Image& image, const std::string& description) {
  try {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    if (!description.empty()) header.insert(kDescriptionAttribute, Imf::StringAttribute(description));
    const std::vector<std::string> names = channelNames(image.channels());
    Imf::FrameBuffer frame;
    for (int c = 0; c < image.channels(); ++c) {
      header.channels().insert(names[std::size_t(c)], Imf::Channel(Imf::FLOAT));
      frame.insert(names[std::size_t(c)], Imf::Slice::Make(Imf::FLOAT, image.plane(c), header.dataWindow()));
    }
    Imf::OutputFile file(temporary.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height());
    return {};
  } catch (const std::exception& e) {
    return fileError(ErrorCode::Io, path, std::string("cannot write: ") + e.what());
  }
}

}  // namespace lfcam::io
