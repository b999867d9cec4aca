// MP4 videos through FFmpeg's libraries, the module liblfcam_mp4.so (render/mp4_codec.hpp): frames
// converted to YUV 4:2:0 by libswscale, encoded by libavcodec (libx264 when Debian's build has it,
// else MPEG-4 part 2), muxed by libavformat; and the summary of a video, decoded back the same way.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "render/mp4_codec.hpp"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

// FFmpeg objects freed by their own functions when they go out of scope.
struct FormatOutputDeleter {
  void operator()(AVFormatContext* context) const {
    if (context->pb) avio_closep(&context->pb);
    avformat_free_context(context);
  }
};
struct FormatInputDeleter {
  void operator()(AVFormatContext* context) const { avformat_close_input(&context); }
};
struct CodecDeleter {
  void operator()(AVCodecContext* context) const { avcodec_free_context(&context); }
};
struct FrameDeleter {
  void operator()(AVFrame* frame) const { av_frame_free(&frame); }
};
struct PacketDeleter {
  void operator()(AVPacket* packet) const { av_packet_free(&packet); }
};
struct ScaleDeleter {
  void operator()(SwsContext* context) const { sws_freeContext(context); }
};

std::string reason(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

// The library never prints: FFmpeg's (and x264's) log lines are switched off.
void silenceFfmpeg() { av_log_set_level(AV_LOG_QUIET); }

// Sends `frame` (null: flush) and writes every packet the encoder gives back.
int encodeFrame(AVCodecContext* codec, AVFrame* frame, AVPacket* packet, AVFormatContext* format, AVStream* stream) {
  int status = avcodec_send_frame(codec, frame);
  while (status >= 0) {
    status = avcodec_receive_packet(codec, packet);
    if (status == AVERROR(EAGAIN) || status == AVERROR_EOF) return 0;
    if (status < 0) return status;
    // Each frame lasts one tick: without a duration the MP4 muxer ends the track (and its edit
    // list) at the last frame's start, and decoders drop that frame.
    if (packet->duration == 0) packet->duration = 1;
    av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
    packet->stream_index = stream->index;
    status = av_interleaved_write_frame(format, packet);  // takes the packet's data
  }
  return status;
}

Status encode(const fs::path& temporary, const Mp4Frames& frames) {
  silenceFfmpeg();
  const auto failed = [](ErrorCode code, const std::string& what) { return makeError(code, what); };
  const int width = frames.width, height = frames.height, framesPerSecond = frames.framesPerSecond;

  const AVCodec* encoder = avcodec_find_encoder_by_name("libx264");
  if (!encoder) encoder = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  if (!encoder) return failed(ErrorCode::Unsupported, "this FFmpeg has neither an H.264 nor an MPEG-4 encoder");

  AVFormatContext* rawFormat = nullptr;
  if (avformat_alloc_output_context2(&rawFormat, nullptr, "mp4", temporary.c_str()) < 0 || !rawFormat)
    return failed(ErrorCode::Unsupported, "this FFmpeg cannot write MP4");
  std::unique_ptr<AVFormatContext, FormatOutputDeleter> format(rawFormat);
  AVStream* stream = avformat_new_stream(format.get(), nullptr);
  std::unique_ptr<AVCodecContext, CodecDeleter> codec(avcodec_alloc_context3(encoder));
  if (!stream || !codec) return failed(ErrorCode::Resource, "cannot set up the encoder");

  codec->width = width;
  codec->height = height;
  codec->pix_fmt = AV_PIX_FMT_YUV420P;  // what every player decodes
  codec->time_base = AVRational{1, framesPerSecond};
  codec->framerate = AVRational{framesPerSecond, 1};
  codec->gop_size = framesPerSecond;
  // BT.709, limited range: what players assume for video; tagged so that none has to guess.
  codec->color_primaries = AVCOL_PRI_BT709;
  codec->color_trc = AVCOL_TRC_BT709;
  codec->colorspace = AVCOL_SPC_BT709;
  codec->color_range = AVCOL_RANGE_MPEG;
  codec->thread_count = 1;  // threads belong to parallelFor; a short clip encodes fast on one
  if (format->oformat->flags & AVFMT_GLOBALHEADER) codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (encoder->id == AV_CODEC_ID_H264) {
    av_opt_set(codec->priv_data, "preset", "medium", 0);
    av_opt_set(codec->priv_data, "crf", "18", 0);  // visually lossless for photographs
  } else {
    codec->flags |= AV_CODEC_FLAG_QSCALE;
    codec->global_quality = FF_QP2LAMBDA * 2;
  }
  if (int status = avcodec_open2(codec.get(), encoder, nullptr); status < 0)
    return failed(ErrorCode::Unsupported,
                  std::string("cannot open the ") + encoder->name + " encoder: " + reason(status));
  if (avcodec_parameters_from_context(stream->codecpar, codec.get()) < 0)
    return failed(ErrorCode::Resource, "cannot set up the video stream");
  stream->time_base = codec->time_base;

  if (int status = avio_open(&format->pb, temporary.c_str(), AVIO_FLAG_WRITE); status < 0)
    return failed(ErrorCode::Io, "cannot write: " + reason(status));
  if (int status = avformat_write_header(format.get(), nullptr); status < 0)
    return failed(ErrorCode::Io, "cannot write: " + reason(status));

  std::unique_ptr<AVFrame, FrameDeleter> frame(av_frame_alloc());
  std::unique_ptr<AVPacket, PacketDeleter> packet(av_packet_alloc());
  std::unique_ptr<SwsContext, ScaleDeleter> scale(sws_getContext(
      width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr));
  if (!frame || !packet || !scale) return failed(ErrorCode::Resource, "cannot set up the encoder");
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  sws_setColorspaceDetails(scale.get(), bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);  // full-range RGB in, limited out
  frame->format = codec->pix_fmt;
  frame->width = width;
  frame->height = height;
  if (av_frame_get_buffer(frame.get(), 0) < 0) return failed(ErrorCode::Resource, "cannot allocate a video frame");

  for (std::size_t i = 0; i < frames.count; ++i) {
    const std::vector<std::uint8_t> pixels = frames.rgb(i);
    if (av_frame_make_writable(frame.get()) < 0) return failed(ErrorCode::Resource, "cannot allocate a video frame");
    const std::uint8_t* source[1] = {pixels.data()};
    const int sourceStride[1] = {3 * width};
    sws_scale(scale.get(), source, sourceStride, 0, height, frame->data, frame->linesize);
    frame->pts = std::int64_t(i);
    if (int status = encodeFrame(codec.get(), frame.get(), packet.get(), format.get(), stream); status < 0)
      return failed(ErrorCode::Io, "cannot encode frame " + std::to_string(i) + ": " + reason(status));
  }
  if (int status = encodeFrame(codec.get(), nullptr, packet.get(), format.get(), stream); status < 0)
    return failed(ErrorCode::Io, "cannot finish the video: " + reason(status));
  if (int status = av_write_trailer(format.get()); status < 0)
    return failed(ErrorCode::Io, "cannot write: " + reason(status));
  if (int status = avio_closep(&format->pb); status < 0)
    return failed(ErrorCode::Io, "cannot write: " + reason(status));
  return {};
}

Result<VideoSummary> summarise(const fs::path& path) {
  silenceFfmpeg();
  AVFormatContext* rawFormat = nullptr;
  if (int status = avformat_open_input(&rawFormat, path.c_str(), nullptr, nullptr); status < 0)
    return makeError(ErrorCode::Format, "not a readable video: " + reason(status));
  std::unique_ptr<AVFormatContext, FormatInputDeleter> format(rawFormat);
  if (avformat_find_stream_info(format.get(), nullptr) < 0)
    return makeError(ErrorCode::Format, "cannot find its streams");
  const AVCodec* decoder = nullptr;
  const int streamIndex = av_find_best_stream(format.get(), AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (streamIndex < 0 || !decoder) return makeError(ErrorCode::Format, "holds no decodable video stream");
  std::unique_ptr<AVCodecContext, CodecDeleter> codec(avcodec_alloc_context3(decoder));
  if (!codec || avcodec_parameters_to_context(codec.get(), format->streams[streamIndex]->codecpar) < 0 ||
      avcodec_open2(codec.get(), decoder, nullptr) < 0)
    return makeError(ErrorCode::Unsupported, std::string("cannot open the ") + decoder->name + " decoder");

  VideoSummary summary;
  summary.codec = decoder->name;
  std::unique_ptr<AVFrame, FrameDeleter> frame(av_frame_alloc());
  std::unique_ptr<AVPacket, PacketDeleter> packet(av_packet_alloc());
  const auto receive = [&]() -> int {
    int status = 0;
    while ((status = avcodec_receive_frame(codec.get(), frame.get())) >= 0) {
      ++summary.frames;
      summary.width = frame->width;
      summary.height = frame->height;
    }
    return status == AVERROR(EAGAIN) || status == AVERROR_EOF ? 0 : status;
  };
  while (av_read_frame(format.get(), packet.get()) >= 0) {
    int status = 0;
    if (packet->stream_index == streamIndex) status = avcodec_send_packet(codec.get(), packet.get());
    av_packet_unref(packet.get());
    if (status >= 0) status = receive();
    if (status < 0) return makeError(ErrorCode::Format, "damaged video: " + reason(status));
  }
  avcodec_send_packet(codec.get(), nullptr);  // drain the decoder
  if (int status = receive(); status < 0) return makeError(ErrorCode::Format, "damaged video: " + reason(status));
  return summary;
}

}  // namespace

}  // namespace lfcam

extern "C" const lfcam::Mp4Codec lfcamMp4Codec{lfcam::encode, lfcam::summarise};
