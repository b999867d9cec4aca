// White images where cameras and users keep them, found for `lfcam whites index`:
//   - Lytro calibration data: MOD_*.RAW frames with the .TXT describing each (white_database.hpp),
//     loose in a folder, members of a tar archive (an Illum's caldata-SERIAL.tar), or files inside a
//     first-generation camera's backup volumes (data.C.0, data.C.1, ...: Lytro containers whose
//     table of contents lists files by name and section);
//   - Lytro containers of a white frame (.LFR, .LFP: "modulationFrame" in their table of contents);
//   - PNG/TIFF white images with a side-car <stem>.json naming serial, zoom and focus steps
//     (docs/formats.md, "White images").
// A .RAW and a .TXT pair by name (folders and case ignored) within one source, across its archives
// and volumes. Tar archives are read by libarchive, one pass to list and one per white read.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

// One file of calibration data: a file on disk, or a member of an archive or a backup volume.
struct CaldataFile {
  enum class Holder { Disk, Tar, Backup } holder = Holder::Disk;
  std::filesystem::path file;  // on disk: the file itself, the tar archive or the backup volume
  std::string member;          // Tar: the member's path; Backup: the section's name ("sha1-...")
  std::string name;            // for people: the path, or "ARCHIVE:MEMBER"
};

struct CaldataWhite {
  CaldataFile pixels;       // the frame (Disk: any white readRaw reads)
  CaldataFile description;  // its .TXT; holder Disk with an empty file when `pixels` says it all
};

struct CaldataListing {
  std::vector<CaldataWhite> whites;
  std::vector<std::string> warnings;  // files of a folder passed over, each naming the file and why
};

// Every white in `source` (a folder, searched recursively, or one file). A file given directly
// that holds no white, an archive that is damaged, truncated or holds no Lytro white: Format errors
// naming the file.
Result<CaldataListing> findCaldataWhites(const std::filesystem::path& source);

// A white's camera setting and size from its description alone (a PNG/TIFF's or a container's
// from the whole file).
struct CaldataDescription {
  CameraSetting setting;
  int width = 0, height = 0;
};
Result<CaldataDescription> describeCaldataWhite(const CaldataWhite& white);

Result<RawImage> readCaldataWhite(const CaldataWhite& white);
// The bytes of one file of calibration data (to copy a white out of its archive).
Result<std::vector<std::uint8_t>> readCaldataFile(const CaldataFile& file);

}  // namespace lfcam
