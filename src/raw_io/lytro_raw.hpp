// Raw frames in Lytro containers, on parsed containers (readRaw and writeLytroRaw in raw_io.hpp
// are the file-level entry points).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/lytro_container.hpp"

namespace lfcam {

// The raw frame of a parsed container (Unsupported when it holds only processed pictures).
Result<RawImage> rawFromLytroContainer(const LytroContainer& container, const std::string& where);

// A white image of a camera's calibration data: a bare packed frame (MOD_*.RAW) and its description
// (MOD_*.TXT, the frame metadata wrapped in master.picture.frameArray[0].frame), setting included.
Result<RawImage> rawFromLytroCaldata(std::span<const std::uint8_t> pixels, const nlohmann::json& description,
                                     const std::string& where);

// The container writeLytroRaw writes.
Result<LytroContainer> makeLytroRawContainer(const RawImage& raw, const LytroWriteOptions& options,
                                             const std::string& where);

}  // namespace lfcam
