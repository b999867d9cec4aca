// Lytro containers (lytro_container.hpp): scanning, SHA-1 checks, writing.
#include "raw_io/lytro_container.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"

namespace lfcam {

namespace {

constexpr std::size_t kHeaderBytes = 16, kNameBytes = 80, kAlignment = 16;
constexpr std::uint8_t kMagicTail[4] = {'\r', '\n', 0x1a, '\n'};

std::uint32_t readBigEndian32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

void appendBigEndian32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

// The kind named by the 8-byte magic at p, or false.
bool magicKind(const std::uint8_t* p, LytroSectionKind& kind) {
  if (p[0] != 0x89 || p[1] != 'L' || p[2] != 'F' || std::memcmp(p + 4, kMagicTail, 4) != 0) return false;
  switch (p[3]) {
    case 'P': kind = LytroSectionKind::Package; return true;
    case 'M': kind = LytroSectionKind::Metadata; return true;
    case 'C': kind = LytroSectionKind::Component; return true;
    default: return false;
  }
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// "sha1-" + 40 hex digits (either case).
bool isSha1Name(std::string_view name) {
  if (name.size() != 45 || lower(name.substr(0, 5)) != "sha1-") return false;
  return std::all_of(name.begin() + 5, name.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

void collectReferences(const nlohmann::json& json, const std::string& pointer, std::vector<LytroReference>& out) {
  if (json.is_object()) {
    for (auto it = json.begin(); it != json.end(); ++it) collectReferences(it.value(), pointer + "/" + it.key(), out);
  } else if (json.is_array()) {
    for (std::size_t k = 0; k < json.size(); ++k) collectReferences(json[k], pointer + "/" + std::to_string(k), out);
  } else if (json.is_string()) {
    const std::string& s = json.get_ref<const std::string&>();
    if (isSha1Name(s)) out.push_back({pointer, s});
  }
}

}  // namespace

const char* lytroSectionKindName(LytroSectionKind kind) {
  switch (kind) {
    case LytroSectionKind::Package: return "LFP";
    case LytroSectionKind::Metadata: return "LFM";
    case LytroSectionKind::Component: return "LFC";
  }
  return "?";
}

std::string sha1Name(std::span<const std::uint8_t> bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha1(), nullptr);
  static const char* hex = "0123456789abcdef";
  std::string name = "sha1-";
  for (unsigned k = 0; k < length; ++k) {
    name += hex[digest[k] >> 4];
    name += hex[digest[k] & 15];
  }
  return name;
}

LytroSection makeLytroSection(LytroSectionKind kind, std::vector<std::uint8_t> payload) {
  LytroSection section;
  section.kind = kind;
  section.name = sha1Name(payload);
  section.payload = std::move(payload);
  return section;
}

LytroSection makeLytroSection(LytroSectionKind kind, std::string_view payload) {
  return makeLytroSection(kind, std::vector<std::uint8_t>(payload.begin(), payload.end()));
}

const LytroSection* LytroContainer::find(std::string_view name) const {
  const std::string wanted = lower(name);
  for (const LytroSection& section : sections)
    if (!section.name.empty() && lower(section.name) == wanted) return &section;
  return nullptr;
}

std::vector<LytroReference> LytroContainer::references() const {
  std::vector<LytroReference> out;
  if (!tableOfContents.is_null()) collectReferences(tableOfContents, "", out);
  return out;
}

bool looksLikeLytroContainer(std::span<const std::uint8_t> bytes) {
  LytroSectionKind kind;
  return bytes.size() >= 8 && magicKind(bytes.data(), kind) && kind == LytroSectionKind::Package;
}

bool looksLikeLytroContainer(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint8_t head[8] = {};
  if (!in.read(reinterpret_cast<char*>(head), 8)) return false;
  return looksLikeLytroContainer(std::span<const std::uint8_t>(head, 8));
}

Result<std::vector<std::uint8_t>> readFileBytes(const std::filesystem::path& path, std::uint64_t maxBytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return makeError(ErrorCode::Usage, path.string() + ": is a folder, expected a file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return makeError(ErrorCode::Io, path.string() + ": cannot read: " + ec.message());
  if (size > maxBytes)
    return makeError(ErrorCode::Resource, path.string() + ": " + std::to_string(size) + " bytes, more than the " +
                                              std::to_string(maxBytes) + " this kind of file may have");
  // The whole file, then a copy of its sections.
  LFCAM_TRY(checkMemory(path.string(), checkedProduct({size, 2}), "the file's contents"));
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorCode::Io, path.string() + ": cannot open");
  std::vector<std::uint8_t> bytes(size);
  if (size && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    return makeError(ErrorCode::Io, path.string() + ": read failed");
  return bytes;
}

Result<LytroContainer> parseLytroContainer(std::span<const std::uint8_t> bytes, const std::string& where) {
  if (!looksLikeLytroContainer(bytes))
    return makeError(ErrorCode::Format, where + ": not a Lytro container (no \\x89LFP magic at the start)");
  LytroContainer container;
  const std::size_t total = bytes.size();
  std::size_t pos = 0;
  while (pos < total) {
    const std::string at = where + ": section at byte " + std::to_string(pos);
    LytroSectionKind kind;
    if (total - pos < kHeaderBytes || !magicKind(bytes.data() + pos, kind)) {
      // Zero padding may end a file; anything else is damage.
      if (std::all_of(bytes.begin() + std::ptrdiff_t(pos), bytes.end(), [](std::uint8_t b) { return b == 0; })) break;
      return makeError(ErrorCode::Format, at + ": no section header (expected \\x89LFP, \\x89LFM or \\x89LFC)");
    }
    LytroSection section;
    section.kind = kind;
    section.offset = pos;
    section.version = readBigEndian32(bytes.data() + pos + 8);
    const std::uint64_t length = readBigEndian32(bytes.data() + pos + 12);
    std::size_t payloadAt = pos + kHeaderBytes;
    if (kind != LytroSectionKind::Package) {
      if (total - payloadAt < kNameBytes)
        return makeError(ErrorCode::Format, at + ": truncated: the 80-byte name runs past the end of the file");
      const char* name = reinterpret_cast<const char*>(bytes.data() + payloadAt);
      section.name.assign(name, strnlen(name, kNameBytes));
      payloadAt += kNameBytes;
    }
    if (length > total - payloadAt)
      return makeError(ErrorCode::Format, at + ": truncated: " + lytroSectionKindName(kind) + " payload of " +
                                              std::to_string(length) + " bytes, only " +
                                              std::to_string(total - payloadAt) + " left in the file");
    section.payload.assign(bytes.begin() + std::ptrdiff_t(payloadAt),
                           bytes.begin() + std::ptrdiff_t(payloadAt + length));
    if (isSha1Name(section.name)) {
      const std::string actual = sha1Name(section.payload);
      if (lower(section.name) != actual)
        return makeError(ErrorCode::Format, at + ": damaged: its name is " + section.name +
                                                " but the SHA-1 of its payload is " + actual.substr(5));
    }
    if (kind == LytroSectionKind::Metadata && container.tableOfContents.is_null()) {
      container.tableOfContents = nlohmann::json::parse(section.payload.begin(), section.payload.end(), nullptr, false);
      if (container.tableOfContents.is_discarded())
        return makeError(ErrorCode::Format, at + ": the table of contents (LFM) is not valid JSON");
    }
    container.sections.push_back(std::move(section));
    pos = payloadAt + length;
    pos = pos + (kAlignment - pos % kAlignment) % kAlignment;
  }
  return container;
}

Result<LytroContainer> readLytroContainer(const std::filesystem::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto bytes, readFileBytes(path, kMaxLytroFileBytes));
  return parseLytroContainer(bytes, path.string());
}

std::vector<std::uint8_t> serializeLytroContainer(const LytroContainer& container) {
  std::vector<std::uint8_t> out;
  for (const LytroSection& section : container.sections) {
    const char letter = section.kind == LytroSectionKind::Package    ? 'P'
                        : section.kind == LytroSectionKind::Metadata ? 'M'
                                                                     : 'C';
    const std::uint8_t magic[8] = {0x89, 'L', 'F', std::uint8_t(letter), '\r', '\n', 0x1a, '\n'};
    out.insert(out.end(), magic, magic + 8);
    appendBigEndian32(out, section.version);
    appendBigEndian32(out, std::uint32_t(section.payload.size()));
    if (section.kind != LytroSectionKind::Package) {
      std::string name = section.name.substr(0, kNameBytes);
      name.resize(kNameBytes, '\0');
      out.insert(out.end(), name.begin(), name.end());
    }
    out.insert(out.end(), section.payload.begin(), section.payload.end());
    out.resize(out.size() + (kAlignment - out.size() % kAlignment) % kAlignment, 0);
  }
  return out;
}

Status writeLytroContainer(const std::filesystem::path& path, const LytroContainer& container) {
  for (const LytroSection& section : container.sections)
    if (section.payload.size() > 0xffffffffu)
      return makeError(ErrorCode::Usage, path.string() + ": a section of " + std::to_string(section.payload.size()) +
                                             " bytes does not fit a Lytro container (4 GiB at most)");
  const std::vector<std::uint8_t> bytes = serializeLytroContainer(container);
  return writeFileAtomically(path, [&](const std::filesystem::path& temporary) -> Status {
    std::ofstream out(temporary, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot write");
    return {};
  });
}

LytroContainer makeLytroContainer(const nlohmann::json& tableOfContents, std::vector<LytroSection> components) {
  LytroContainer container;
  LytroSection header;
  header.kind = LytroSectionKind::Package;
  header.version = 1;
  container.sections.push_back(std::move(header));
  container.sections.push_back(makeLytroSection(LytroSectionKind::Metadata, tableOfContents.dump(1)));
  for (LytroSection& section : components) container.sections.push_back(std::move(section));
  container.tableOfContents = tableOfContents;
  return container;
}

}  // namespace lfcam
