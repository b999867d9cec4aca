// Which codec for the native file's chunks (docs/design.md, "The native file"): the size and the
// single-thread compress and decompress times of each candidate on a real light field, cut into
// chunks as the writer cuts it (one view each, in its exact encoding, shuffled when wider than a
// byte for the byte-stream codecs; szip codes whole samples). Median of 3 passes over every view.
//   build/bench/native_codec_bench [LIGHT_FIELD]   (default: ../shared/data/hci-antinous)
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "io/hdf5_chunk_codec.hpp"
#include "io/sample_encoding.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace {

using Bytes = std::vector<unsigned char>;

struct Codec {
  const char* name;
  std::function<Bytes(const Bytes&)> compress;
  std::function<void(const Bytes&, Bytes&)> decompress;  // into a buffer of the chunk's size
  bool shuffled = true;                                  // compresses the shuffled codes (szip takes whole samples)
};

double medianSeconds(const std::function<void()>& pass) {
  std::vector<double> seconds;
  for (int i = 0; i < 3; ++i) {
    const auto start = std::chrono::steady_clock::now();
    pass();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[1];
}

Codec libdeflateCodec(const char* name, int level) {
  const lfcam::io::ChunkFilters deflate{.deflate = true};
  return {name, [=](const Bytes& in) { return lfcam::io::filterChunk(in.data(), in.size(), 1, deflate, level); },
          [=](const Bytes& in, Bytes& out) {
            lfcam::io::unfilterChunk(in.data(), in.size(), 1, deflate, out.data(), out.size());
          }};
}

// libhdf5's szip parameters for views `width` samples wide, `elementSize` bytes each.
Codec szipCodec(const char* name, std::size_t width, std::size_t elementSize) {
  const lfcam::io::ChunkFilters szip{
      .szip = lfcam::io::SzipParameters{.optionsMask = 32 | 8 | 128 | 1,  // difference coding, little-endian, raw
                                        .pixelsPerBlock = 32,
                                        .bitsPerPixel = unsigned(8 * elementSize),
                                        .pixelsPerScanline = unsigned(std::min<std::size_t>(width, 32 * 128))}};
  return {name, [=](const Bytes& in) { return lfcam::io::filterChunk(in.data(), in.size(), elementSize, szip, 0); },
          [=](const Bytes& in, Bytes& out) {
            lfcam::io::unfilterChunk(in.data(), in.size(), elementSize, szip, out.data(), out.size());
          },
          false};
}

Codec zlibCodec(const char* name, int level) {
  return {name,
          [=](const Bytes& in) {
            uLongf size = compressBound(uLong(in.size()));
            Bytes out(size);
            compress2(out.data(), &size, in.data(), uLong(in.size()), level);
            out.resize(size);
            return out;
          },
          [](const Bytes& in, Bytes& out) {
            uLongf size = uLongf(out.size());
            uncompress(out.data(), &size, in.data(), uLong(in.size()));
          }};
}

Codec zstdCodec(const char* name, int level) {
  return {name,
          [=](const Bytes& in) {
            Bytes out(ZSTD_compressBound(in.size()));
            out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), level));
            return out;
          },
          [](const Bytes& in, Bytes& out) { ZSTD_decompress(out.data(), out.size(), in.data(), in.size()); }};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string input = argc > 1 ? argv[1] : LFCAM_SHARED_DATA_DIR "/hci-antinous";
  auto lightField = lfcam::readLightField(input);
  if (!lightField) {
    std::fprintf(stderr, "native_codec_bench: %s\n", lightField.error().message.c_str());
    return 1;
  }
  const std::size_t viewValues = lightField->shape().viewPixels() * std::size_t(lightField->channels());
  const auto samples = lightField->samples();
  const lfcam::io::SampleEncoding encoding =
      lfcam::io::exactEncodingOf(samples, viewValues, lfcam::io::kColorEncodings);
  const std::size_t elementSize = lfcam::io::bytesPerSample(encoding.kind);
  std::vector<Bytes> chunks, unshuffled;
  std::size_t rawBytes = 0;
  for (std::size_t view = 0; view < lightField->shape().views(); ++view) {
    Bytes codes(viewValues * elementSize);
    lfcam::io::encodeExactly(encoding, samples.subspan(view * viewValues, viewValues), codes.data());
    chunks.push_back(lfcam::io::filterChunk(codes.data(), codes.size(), elementSize, {.shuffle = true}, 0));
    unshuffled.push_back(codes);
    rawBytes += codes.size();
  }
  std::printf("%s: %zu views, %zu bytes per sample, %.1f MB as stored without compression\n", input.c_str(),
              chunks.size(), elementSize, rawBytes / 1e6);
  std::printf("%-14s%10s%14s%16s\n", "codec", "MB", "compress s", "decompress s");
  const Codec codecs[] = {zlibCodec("zlib 1", 1),
                          zlibCodec("zlib 6", 6),
                          libdeflateCodec("libdeflate 1", 1),
                          libdeflateCodec("libdeflate 6", 6),
                          zstdCodec("zstd 1", 1),
                          zstdCodec("zstd 3", 3),
                          szipCodec("szip", std::size_t(lightField->shape().ns), elementSize)};
  for (const Codec& codec : codecs) {
    const std::vector<Bytes>& codes = codec.shuffled ? chunks : unshuffled;
    std::vector<Bytes> stored(chunks.size());
    const double compress = medianSeconds([&] {
      for (std::size_t i = 0; i < codes.size(); ++i) stored[i] = codec.compress(codes[i]);
    });
    Bytes back(chunks.front().size());
    const double decompress = medianSeconds([&] {
      for (const Bytes& chunk : stored) codec.decompress(chunk, back);
    });
    std::size_t bytes = 0;
    for (const Bytes& chunk : stored) bytes += chunk.size();
    std::printf("%-14s%10.1f%14.3f%16.3f\n", codec.name, bytes / 1e6, compress, decompress);
  }
  return 0;
}
