// White images of calibration data (lytro_caldata.hpp).
#include "raw_io/lytro_caldata.hpp"

#include <archive.h>
#include <archive_entry.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "io/io_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/lytro_container.hpp"
#include "raw_io/lytro_metadata.hpp"
#include "raw_io/lytro_raw.hpp"
#include "raw_io/lytro_setting.hpp"

namespace lfcam {

namespace {

namespace fs = std::filesystem;
using Holder = CaldataFile::Holder;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// A member's name with / for \ (Lytro's backups name files C:\T1CALIB\MOD_0000.RAW).
std::string slashed(std::string name) {
  std::replace(name.begin(), name.end(), '\\', '/');
  return name;
}

using Archive = std::unique_ptr<archive, decltype(&archive_read_free)>;

Result<Archive> openTar(const fs::path& path) {
  Archive reader(archive_read_new(), archive_read_free);
  archive_read_support_format_tar(reader.get());
  archive_read_support_filter_all(reader.get());
  if (archive_read_open_filename(reader.get(), path.c_str(), 1 << 16) != ARCHIVE_OK)
    return makeError(ErrorCode::Format,
                     path.string() + ": not a tar archive (" + std::string(archive_error_string(reader.get())) + ")");
  return reader;
}

Status tarError(const fs::path& path, archive* reader) {
  const char* why = archive_error_string(reader);
  return makeError(ErrorCode::Format,
                   path.string() + ": damaged or truncated tar archive (" + (why ? why : "unknown error") + ")");
}

// Every member of a tar archive, or the bytes of one (`wanted`, into `bytes`), reading it through.
Status scanTar(const fs::path& path, const std::string& wanted, std::vector<std::string>* names,
               std::vector<std::uint8_t>* bytes) {
  LFCAM_ASSIGN_OR_RETURN(auto reader, openTar(path));
  archive_entry* entry = nullptr;
  int status = ARCHIVE_OK;
  while ((status = archive_read_next_header(reader.get(), &entry)) == ARCHIVE_OK) {
    const std::string name = archive_entry_pathname(entry) ? archive_entry_pathname(entry) : "";
    const bool regular = archive_entry_filetype(entry) == AE_IFREG;
    if (regular && names) names->push_back(name);
    if (regular && bytes && name == wanted) {
      const la_int64_t size = archive_entry_size(entry);
      if (size < 0 || std::uint64_t(size) > kMaxLytroFileBytes)
        return makeError(ErrorCode::Format,
                         path.string() + ":" + name + ": member of " + std::to_string(size) + " bytes");
      bytes->resize(std::size_t(size));
      // libarchive may hand a member over in several pieces; none before the end is a truncation.
      for (std::size_t done = 0; done < bytes->size();) {
        const la_ssize_t got = archive_read_data(reader.get(), bytes->data() + done, bytes->size() - done);
        if (got <= 0) return tarError(path, reader.get());
        done += std::size_t(got);
      }
      return {};
    }
    if (archive_read_data_skip(reader.get()) != ARCHIVE_OK) return tarError(path, reader.get());
  }
  if (status != ARCHIVE_EOF) return tarError(path, reader.get());
  if (bytes) return makeError(ErrorCode::Format, path.string() + ": no member " + wanted);
  return {};
}

bool isTar(const fs::path& path) {
  const std::string ext = io::lowerExtension(path);
  if (ext == ".tar" || ext == ".tgz") return true;
  std::ifstream in(path, std::ios::binary);
  char magic[5] = {};
  return in.seekg(257) && in.read(magic, 5) && std::string(magic, 5) == "ustar";
}

bool hasWhiteSideCar(const fs::path& path) {
  fs::path sideCar = path;
  sideCar.replace_extension(".json");
  std::ifstream in(sideCar);
  if (!in) return false;
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  return json.is_object() && json.contains("serial");
}

bool isModulationFrame(const nlohmann::json& toc) {
  for (const char* pointer : {"/picture/frameArray/0/parameters/vendorContent/com.lytro.tags/modulationFrame",
                              "/frames/0/parameters/vendorContent/com.lytro.tags/modulationFrame"}) {
    const nlohmann::json::json_pointer p(pointer);
    if (toc.contains(p) && toc.at(p) == true) return true;
  }
  return false;
}

// What one source holds, before .RAW and .TXT are paired.
struct Found {
  std::vector<CaldataFile> frames, descriptions;  // .RAW, .TXT members
  std::vector<CaldataWhite> whites;               // whites of one file
  std::vector<std::string> warnings;
};

// One file of the source. `direct`: the user named it, so a file holding no white is an error.
Status examine(const fs::path& path, bool direct, Found& found) {
  const std::string ext = io::lowerExtension(path);
  const auto pass = [&](const std::string& why) -> Status {
    if (direct) return makeError(ErrorCode::Format, path.string() + ": " + why);
    found.warnings.push_back(path.string() + ": " + why + ", passed over");
    return {};
  };
  if (ext == ".raw") {
    found.frames.push_back({Holder::Disk, path, "", path.string()});
  } else if (ext == ".txt") {
    found.descriptions.push_back({Holder::Disk, path, "", path.string()});
  } else if (looksLikeLytroContainer(path)) {
    LFCAM_ASSIGN_OR_RETURN(auto container, readLytroContainer(path));
    const nlohmann::json& toc = container.tableOfContents;
    if (toc.is_object() && toc.contains("files") && toc["files"].is_array()) {
      // A backup volume: files by name, each a section.
      for (const nlohmann::json& file : toc["files"]) {
        if (!file.is_object() || !file.value("name", nlohmann::json()).is_string() ||
            !file.value("dataRef", nlohmann::json()).is_string())
          continue;
        const std::string name = slashed(file["name"].get<std::string>());
        const CaldataFile member{Holder::Backup, path, file["dataRef"].get<std::string>(), path.string() + ":" + name};
        const std::string memberExt = io::lowerExtension(name);
        if (memberExt == ".raw") found.frames.push_back(member);
        if (memberExt == ".txt") found.descriptions.push_back(member);
      }
    } else if (isModulationFrame(toc)) {
      found.whites.push_back({{Holder::Disk, path, "", path.string()}, {}});
    } else {
      return pass("a Lytro container of a picture, not of a white image");
    }
  } else if (isTar(path)) {
    std::vector<std::string> names;
    LFCAM_TRY(scanTar(path, "", &names, nullptr));
    const std::size_t before = found.frames.size() + found.descriptions.size();
    for (const std::string& name : names) {
      const CaldataFile member{Holder::Tar, path, name, path.string() + ":" + slashed(name)};
      if (io::lowerExtension(slashed(name)) == ".raw") found.frames.push_back(member);
      if (io::lowerExtension(slashed(name)) == ".txt") found.descriptions.push_back(member);
    }
    if (found.frames.size() + found.descriptions.size() == before)
      return makeError(ErrorCode::Format,
                       path.string() + ": holds no Lytro calibration data (no MOD_*.RAW or .TXT member)");
  } else if (looksLikeImageFile(path)) {
    if (!hasWhiteSideCar(path))
      return pass("an image without a side-car " + path.stem().string() + ".json naming its serial");
    found.whites.push_back({{Holder::Disk, path, "", path.string()}, {}});
  } else if (direct) {
    return pass(
        "not calibration data lfcam reads (MOD_*.RAW with .TXT, a tar archive, a Lytro container, or a "
        "PNG/TIFF white with a side-car .json)");
  }
  return {};
}

// A member's path less its extension, where it sits: what pairs a .RAW with its .TXT.
std::string pairingKey(const CaldataFile& file) {
  if (file.holder == Holder::Disk) return lower((file.file.parent_path() / file.file.stem()).string());
  const fs::path name =
      slashed(file.holder == Holder::Backup ? file.name.substr(file.file.string().size() + 1) : file.member);
  const std::string prefix = file.holder == Holder::Tar ? file.file.string() + ":" : "backup:";
  return lower(prefix + (name.parent_path() / name.stem()).string());
}

}  // namespace

Result<CaldataListing> findCaldataWhites(const fs::path& source) {
  std::error_code ec;
  if (!fs::exists(source, ec)) return makeError(ErrorCode::Io, source.string() + ": no such file or folder");
  Found found;
  if (fs::is_directory(source, ec)) {
    std::vector<fs::path> files;
    for (auto it = fs::recursive_directory_iterator(source, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
      if (it->is_regular_file(ec) && io::lowerExtension(it->path()) != ".json") files.push_back(it->path());
    if (ec) return makeError(ErrorCode::Io, source.string() + ": cannot list: " + ec.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) LFCAM_TRY(examine(file, false, found));
  } else {
    LFCAM_TRY(examine(source, true, found));
    // A .RAW or .TXT named alone brings its partner.
    const std::string ext = io::lowerExtension(source);
    for (const char* partner : {".RAW", ".raw", ".TXT", ".txt"}) {
      fs::path other = source;
      other.replace_extension(partner);
      if ((ext == ".raw" || ext == ".txt") && io::lowerExtension(other) != ext && fs::is_regular_file(other))
        LFCAM_TRY(examine(other, false, found));
    }
  }
  std::map<std::string, CaldataFile> descriptions;
  for (const CaldataFile& file : found.descriptions) descriptions.emplace(pairingKey(file), file);
  CaldataListing listing{.whites = std::move(found.whites), .warnings = std::move(found.warnings)};
  for (const CaldataFile& frame : found.frames) {
    auto partner = descriptions.find(pairingKey(frame));
    if (partner == descriptions.end()) {
      listing.warnings.push_back(frame.name + ": no .TXT of the same name describes it, passed over");
      continue;
    }
    listing.whites.push_back({frame, partner->second});
    descriptions.erase(partner);
  }
  if (listing.whites.empty())
    return makeError(ErrorCode::Format, source.string() +
                                            ": holds no white image (MOD_*.RAW with its .TXT, a "
                                            "Lytro white container, or a PNG/TIFF with a side-car)");
  return listing;
}

Result<std::vector<std::uint8_t>> readCaldataFile(const CaldataFile& file) {
  switch (file.holder) {
    case Holder::Disk: return readFileBytes(file.file, kMaxLytroFileBytes);
    case Holder::Tar: {
      std::vector<std::uint8_t> bytes;
      LFCAM_TRY(scanTar(file.file, file.member, nullptr, &bytes));
      return bytes;
    }
    case Holder::Backup: {
      LFCAM_ASSIGN_OR_RETURN(auto container, readLytroContainer(file.file));
      const LytroSection* section = container.find(file.member);
      if (!section) return makeError(ErrorCode::Format, file.name + ": its section " + file.member + " is missing");
      return section->payload;
    }
  }
  return makeError(ErrorCode::Format, file.name + ": unknown holder");
}

namespace {

Result<nlohmann::json> readDescription(const CaldataFile& file) {
  LFCAM_ASSIGN_OR_RETURN(auto text, readCaldataFile(file));
  nlohmann::json description = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (description.is_discarded()) return makeError(ErrorCode::Format, file.name + ": not JSON");
  return description;
}

}  // namespace

Result<CaldataDescription> describeCaldataWhite(const CaldataWhite& white) {
  if (white.description.file.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto raw, readRaw(white.pixels.file));
    return CaldataDescription{raw.setting, raw.mosaic.width(), raw.mosaic.height()};
  }
  LFCAM_ASSIGN_OR_RETURN(auto description, readDescription(white.description));
  const nlohmann::json* frame = findLytroFrameMetadata(description);
  if (!frame) return makeError(ErrorCode::Format, white.description.name + ": no frame metadata (\"image\") in it");
  LFCAM_ASSIGN_OR_RETURN(auto format, parseLytroFrameMetadata(*frame, white.description.name));
  return CaldataDescription{lytroCameraSetting(description, nullptr), format.width, format.height};
}

Result<RawImage> readCaldataWhite(const CaldataWhite& white) {
  if (white.description.file.empty()) return readRaw(white.pixels.file);
  LFCAM_ASSIGN_OR_RETURN(auto description, readDescription(white.description));
  LFCAM_ASSIGN_OR_RETURN(auto pixels, readCaldataFile(white.pixels));
  return rawFromLytroCaldata(pixels, description, white.pixels.name);
}

}  // namespace lfcam
