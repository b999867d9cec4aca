// Lytro containers: first-generation .lfp files and Illum .lfr/.LFR/.LFP files share one layout
// (docs/formats.md, "Lytro containers"): a sequence of sections, each a 16-byte header (8-byte
// magic \x89LFP / \x89LFM / \x89LFC + \r\n\x1a\n, 4 bytes of version, 4-byte big-endian
// payload length), for LFM and LFC an 80-byte NUL-padded name ("sha1-" + the SHA-1 of the
// payload in hex), the payload, and zero padding to the next multiple of 16 bytes.
//
// The reader scans every section without assuming their order or count, checks each "sha1-"
// name against the payload's SHA-1 (OpenSSL), keeps sections it does not understand, and parses
// the first LFM section as the JSON table of contents, whose "...Ref" strings name other
// sections. Every length is checked against the file before anything is allocated.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/core/result.hpp"

namespace lfcam {

enum class LytroSectionKind { Package, Metadata, Component };  // LFP, LFM, LFC
const char* lytroSectionKindName(LytroSectionKind kind);       // "LFP", "LFM", "LFC"

struct LytroSection {
  LytroSectionKind kind = LytroSectionKind::Component;
  std::string name;           // "sha1-..." (empty for the LFP header)
  std::uint32_t version = 0;  // the 4 bytes after the magic, big-endian (1 in the LFP header)
  std::uint64_t offset = 0;   // of its header in the file (set by the reader)
  std::vector<std::uint8_t> payload;
};

// A section holding `payload` named by its SHA-1 (lower-case hex, as first-generation files).
LytroSection makeLytroSection(LytroSectionKind kind, std::vector<std::uint8_t> payload);
LytroSection makeLytroSection(LytroSectionKind kind, std::string_view payload);
// "sha1-" + 40 lower-case hex digits.
std::string sha1Name(std::span<const std::uint8_t> bytes);

// A string value of the table of contents that names a section, with where it sits in the JSON
// (a JSON pointer such as /picture/accelerationArray/0/vendorContent/imageArray/3/imageRef).
struct LytroReference {
  std::string pointer;
  std::string name;
};

struct LytroContainer {
  std::vector<LytroSection> sections;  // in file order, the LFP header included
  nlohmann::json tableOfContents;      // the first LFM section's JSON; null when there is none

  // The section with this name (hex digits compared without case), or nullptr.
  const LytroSection* find(std::string_view name) const;
  // Every "sha1-..." string of the table of contents (object keys in sorted order, arrays in order).
  std::vector<LytroReference> references() const;
};

// Largest container accepted: no Lytro camera wrote files near this size (an Illum raw is
// ~55 MB); larger inputs are refused before being read.
inline constexpr std::uint64_t kMaxLytroFileBytes = std::uint64_t(1) << 31;

// True when the file starts with the LFP magic.
bool looksLikeLytroContainer(const std::filesystem::path& path);
bool looksLikeLytroContainer(std::span<const std::uint8_t> bytes);

// `where` starts every error message (the file's name).
Result<LytroContainer> parseLytroContainer(std::span<const std::uint8_t> bytes, const std::string& where);
Result<LytroContainer> readLytroContainer(const std::filesystem::path& path);

// Serialises the sections as given (the first must be the LFP header; makeLytroContainer adds
// it); written atomically.
std::vector<std::uint8_t> serializeLytroContainer(const LytroContainer& container);
Status writeLytroContainer(const std::filesystem::path& path, const LytroContainer& container);
// An LFP header, then an LFM section holding `tableOfContents`, then `components`.
LytroContainer makeLytroContainer(const nlohmann::json& tableOfContents, std::vector<LytroSection> components);

// Reads a whole file, refusing more than `maxBytes` (Resource) before allocating.
Result<std::vector<std::uint8_t>> readFileBytes(const std::filesystem::path& path, std::uint64_t maxBytes);

}  // namespace lfcam
