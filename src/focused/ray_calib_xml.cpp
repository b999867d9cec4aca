// Raytrix's calibration XML (<RayCalibData>), read and written with pugixml.
#include <pugixml.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string_view>

#include "focused/ray_calib_document.hpp"
#include "io/io_support.hpp"

namespace lfcam {

namespace {

using focused_detail::RayCalibDocument;

class XmlReader {
 public:
  explicit XmlReader(std::string where) : where_(std::move(where)) {}

  Error fail(const std::string& key, const std::string& what) const {
    return makeError(ErrorCode::Format, where_ + ": " + key + ": " + what);
  }
  // The number in element `name` of `parent`; `key` names it in errors.
  Result<double> number(const pugi::xml_node& parent, const char* name, const std::string& key) const {
    const pugi::xml_node node = parent.child(name);
    if (!node) return fail(key, "missing");
    const std::string text = node.child_value();
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    const bool whole =
        end != text.c_str() && std::string_view(end).find_first_not_of(" \t\r\n") == std::string_view::npos;
    if (!whole || !std::isfinite(value)) return fail(key, "expected a number, got \"" + io::oneLine(text) + "\"");
    return value;
  }
  Result<std::array<double, 2>> pair(const pugi::xml_node& parent, const char* name, const std::string& key) const {
    const pugi::xml_node node = parent.child(name);
    if (!node) return fail(key, "missing");
    LFCAM_ASSIGN_OR_RETURN(const double x, number(node, "x", key + ".x"));
    LFCAM_ASSIGN_OR_RETURN(const double y, number(node, "y", key + ".y"));
    return std::array<double, 2>{x, y};
  }

 private:
  std::string where_;
};

}  // namespace

Result<FocusedCalibration> parseRayCalibXml(const std::string& text, const std::string& where, int width, int height) {
  pugi::xml_document xml;
  const pugi::xml_parse_result parsed = xml.load_buffer(text.data(), text.size());
  if (!parsed)
    return makeError(ErrorCode::Format,
                     where + ": not valid XML: " + parsed.description() + " at byte " + std::to_string(parsed.offset));
  const pugi::xml_node root = xml.child("RayCalibData");
  if (!root) return makeError(ErrorCode::Format, where + ": not a Raytrix calibration (no <RayCalibData> element)");
  const XmlReader reader(where);
  RayCalibDocument d;
  LFCAM_ASSIGN_OR_RETURN(d.offset, reader.pair(root, "offset", "offset"));
  LFCAM_ASSIGN_OR_RETURN(d.diameter, reader.number(root, "diameter", "diameter"));
  if (root.child("rotation")) {
    LFCAM_ASSIGN_OR_RETURN(d.rotation, reader.number(root, "rotation", "rotation"));
  }
  if (root.child("lens_border")) {
    LFCAM_ASSIGN_OR_RETURN(d.lensBorder, reader.number(root, "lens_border", "lens_border"));
  }
  if (root.child("tcp")) {
    LFCAM_ASSIGN_OR_RETURN(d.tcp, reader.number(root, "tcp", "tcp"));
  }
  if (root.child("lens_base_x")) {
    LFCAM_ASSIGN_OR_RETURN(d.lensBaseX, reader.pair(root, "lens_base_x", "lens_base_x"));
  }
  if (root.child("lens_base_y")) {
    LFCAM_ASSIGN_OR_RETURN(d.lensBaseY, reader.pair(root, "lens_base_y", "lens_base_y"));
  }
  if (root.child("sub_grid_base")) {
    LFCAM_ASSIGN_OR_RETURN(d.subGridBase, reader.pair(root, "sub_grid_base", "sub_grid_base"));
  }
  if (const pugi::xml_node distortion = root.child("distortion")) {
    for (const pugi::xml_node parameter : distortion.children("parameter")) {
      std::istringstream values(parameter.child_value());
      for (double value = 0; values >> value;)
        if (value != 0)
          return makeError(ErrorCode::Unsupported,
                           where + ": distortion: a lens distortion is not supported (its parameters are not all 0)");
    }
  }
  // Lens types by their id, 0, 1, 2, ... in order.
  for (int id = 0;; ++id) {
    const pugi::xml_node node = root.find_child_by_attribute("lens_type", "id", std::to_string(id).c_str());
    if (!node) break;
    const std::string key = "lens_type " + std::to_string(id);
    LensType type;
    LFCAM_ASSIGN_OR_RETURN(type.offset, reader.pair(node, "offset", key + " offset"));
    const pugi::xml_node range = node.child("depth_range");
    if (!range) return reader.fail(key + " depth_range", "missing");
    LFCAM_ASSIGN_OR_RETURN(type.minVirtualDepth, reader.number(range, "min", key + " depth_range.min"));
    LFCAM_ASSIGN_OR_RETURN(type.maxVirtualDepth, reader.number(range, "max", key + " depth_range.max"));
    d.lensTypes.push_back(type);
  }
  if (d.lensTypes.empty() && root.child("lens_type"))
    return reader.fail("lens_type", "expected ids 0, 1, 2 (the first is not id 0)");
  if (const pugi::xml_node node = root.child("lfcam_micro_images")) {
    const auto orientation = focused_detail::orientationFromName(node.child_value());
    if (!orientation)
      return reader.fail("lfcam_micro_images",
                         "expected \"upright\" or \"inverted\", got \"" + io::oneLine(node.child_value()) + "\"");
    d.orientation = *orientation;
  }
  if (const pugi::xml_node node = root.child("lfcam_optics")) {
    FocusedOptics optics;
    LFCAM_ASSIGN_OR_RETURN(optics.mainFocalLengthMm,
                           reader.number(node, "main_focal_length", "lfcam_optics.main_focal_length"));
    LFCAM_ASSIGN_OR_RETURN(optics.mainLensToMicrolensesMm,
                           reader.number(node, "main_to_microlenses", "lfcam_optics.main_to_microlenses"));
    LFCAM_ASSIGN_OR_RETURN(optics.microlensesToSensorMm,
                           reader.number(node, "microlenses_to_sensor", "lfcam_optics.microlenses_to_sensor"));
    d.optics = optics;
  }
  return focused_detail::calibrationFromDocument(d, where, width, height);
}

std::string rayCalibXml(const FocusedCalibration& calibration) {
  const RayCalibDocument d = focused_detail::documentFromCalibration(calibration);
  auto number = [](double value) {
    std::ostringstream out;
    out.precision(12);
    out << std::fixed << value;
    return out.str();
  };
  std::ostringstream out;
  auto pair = [&](const char* name, const char* units, const std::array<double, 2>& value, const char* indent) {
    out << indent << "<" << name << " units=\"" << units << "\">\n"
        << indent << "  <x>" << number(value[0]) << "</x>\n"
        << indent << "  <y>" << number(value[1]) << "</y>\n"
        << indent << "</" << name << ">\n";
  };
  out << "<RayCalibData version=\"1.0\">\n";
  pair("offset", "pix", d.offset, "  ");
  out << "  <diameter units=\"pix\">" << number(d.diameter) << "</diameter>\n";
  out << "  <rotation units=\"rad\">" << number(d.rotation) << "</rotation>\n";
  out << "  <lens_border units=\"pix\">" << number(d.lensBorder) << "</lens_border>\n";
  if (d.tcp) out << "  <tcp units=\"virtual_depth\">" << number(*d.tcp) << "</tcp>\n";
  pair("lens_base_x", "lens", d.lensBaseX, "  ");
  pair("lens_base_y", "lens", d.lensBaseY, "  ");
  if (d.subGridBase) pair("sub_grid_base", "lens", *d.subGridBase, "  ");
  for (std::size_t t = 0; t < d.lensTypes.size(); ++t) {
    out << "  <lens_type id=\"" << t << "\">\n";
    pair("offset", "lens", d.lensTypes[t].offset, "    ");
    out << "    <depth_range units=\"virtual_depth\">\n"
        << "      <min>" << number(d.lensTypes[t].minVirtualDepth) << "</min>\n"
        << "      <max>" << number(d.lensTypes[t].maxVirtualDepth) << "</max>\n"
        << "    </depth_range>\n"
        << "  </lens_type>\n";
  }
  out << "  <lfcam_micro_images>" << focused_detail::orientationName(d.orientation) << "</lfcam_micro_images>\n";
  if (d.optics)
    out << "  <lfcam_optics units=\"mm\">\n"
        << "    <main_focal_length>" << number(d.optics->mainFocalLengthMm) << "</main_focal_length>\n"
        << "    <main_to_microlenses>" << number(d.optics->mainLensToMicrolensesMm) << "</main_to_microlenses>\n"
        << "    <microlenses_to_sensor>" << number(d.optics->microlensesToSensorMm) << "</microlenses_to_sensor>\n"
        << "  </lfcam_optics>\n";
  out << "</RayCalibData>\n";
  return out.str();
}

}  // namespace lfcam
