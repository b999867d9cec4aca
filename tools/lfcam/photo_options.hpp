// The photograph request's fields (photo_request.hpp) as command-line options: one --NAME per field
// of the groups a command takes, its help and syntax from the table, its text parsed by the table,
// so that every command and every front end accept and refuse the same requests.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/photo/photo_request.hpp"

namespace lfcam::cli {

struct PhotoOptions {
  std::map<std::string, std::string> text;  // field name -> the text given
  std::vector<std::pair<std::string, CLI::Option*>> options;
};

// --NAME for every field whose group is in `groups` (focus, aperture, lens, sampling), and
// --aperture-center for --aperture-centre (the spelling of earlier versions).
inline void addPhotoOptions(CLI::App& command, PhotoOptions& photo, const std::vector<std::string>& groups,
                            const std::vector<std::string>& leaveOut = {}) {
  for (const PhotoField& field : photoFields()) {
    if (std::find(groups.begin(), groups.end(), field.group) == groups.end()) continue;
    if (std::find(leaveOut.begin(), leaveOut.end(), field.name) != leaveOut.end()) continue;
    std::string names = std::string("--") + field.name;
    if (names == "--aperture-centre") names += ",--aperture-center";
    std::string& storage = photo.text[field.name];
    CLI::Option* option = *field.syntax ? command.add_option(names, storage, field.help)->type_name(field.syntax)
                                        : command.add_flag(names, field.help);
    photo.options.emplace_back(field.name, option);
  }
}

// The request the options given describe; errors in the table's words, as Python and the viewer
// give them.
inline Result<PhotoRequest> photoRequestFrom(const PhotoOptions& photo, PhotoRequest request = {}) {
  for (const auto& [name, option] : photo.options)
    if (option->count()) LFCAM_TRY(setPhotoField(request, name, photo.text.at(name)));
  return request;
}

}  // namespace lfcam::cli
