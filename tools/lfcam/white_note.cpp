#include "white_note.hpp"

#include "lfcam/calibrate/white_database.hpp"
#include "lfcam/raw_io/raw_io.hpp"

namespace lfcam::cli {

Result<std::optional<WhiteNote>> whiteNote(const InputOptions& input, bool container) {
  if (!input.decodesRaw() && !container) return std::optional<WhiteNote>();
  if (!input.white.empty())
    return std::optional(WhiteNote{"--white " + input.white, {{"choice", "given"}, {"white", input.white}}});
  auto raw = readRaw(input.path);
  if (!raw)
    return std::optional(
        WhiteNote{"none needed (not a raw frame: " + raw.error().message + ")", {{"choice", "none-needed"}}});
  if (input.whites.empty())
    return std::optional(
        WhiteNote{"none given: --whites DATABASE would choose one; decoding without finds the grid in the raw itself",
                  {{"choice", "none-given"}}});
  LFCAM_ASSIGN_OR_RETURN(auto choice, chooseWhite(input.whites, *raw, input.anyCamera, input.path));
  return std::optional(WhiteNote{choice.reason,
                                 {{"choice", "database"},
                                  {"database", input.whites},
                                  {"name", choice.white.name},
                                  {"white", choice.white.white.string()},
                                  {"grid", choice.white.grid.string()},
                                  {"reason", choice.reason}}});
}

}  // namespace lfcam::cli
