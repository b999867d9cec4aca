// ViewerSession: the viewer's state (light field, answer cache, render slots, slow layers).
#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <list>
#include <mutex>
#include <semaphore>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/viewer/viewer.hpp"
#include "viewer/image_encode.hpp"

namespace lfcam {

namespace {

using Clock = std::chrono::steady_clock;

// What a slow layer holds: the picture shown, and for the depth layer the disparity map behind its
// colours (px per view step), on which a focus range is rendered.
struct LayerImages {
  Image shown;  // linear RGB, ready to encode
  Image values;
};

// A slow layer computed once, by the first request that asks for it.
struct LazyLayer {
  enum class State { Idle, Running, Ready, Failed };
  State state = State::Idle;
  LayerImages images;
  std::string error;
  Clock::time_point started;
  double expectedSeconds = 1;
};

const char* stateName(LazyLayer::State state) {
  switch (state) {
    case LazyLayer::State::Idle: return "idle";
    case LazyLayer::State::Running: return "running";
    case LazyLayer::State::Ready: return "ready";
    case LazyLayer::State::Failed: return "failed";
  }
  return "idle";
}

// Least recently used JPEG answers, bounded in bytes.
class AnswerCache {
 public:
  explicit AnswerCache(std::size_t capacity) : capacity_(capacity) {}
  std::optional<ViewerSession::Photo> find(const std::string& key) {
    auto it = index_.find(key);
    if (it == index_.end()) return std::nullopt;
    entries_.splice(entries_.begin(), entries_, it->second);
    return it->second->photo;
  }
  void insert(const std::string& key, const ViewerSession::Photo& photo) {
    if (photo.jpeg.size() + key.size() > capacity_ || index_.count(key)) return;
    entries_.push_front({key, photo});
    index_[key] = entries_.begin();
    bytes_ += photo.jpeg.size() + key.size();
    while (bytes_ > capacity_) {
      const Entry& last = entries_.back();
      bytes_ -= last.photo.jpeg.size() + last.key.size();
      index_.erase(last.key);
      entries_.pop_back();
    }
  }
  std::size_t bytes() const { return bytes_; }

 private:
  struct Entry {
    std::string key;
    ViewerSession::Photo photo;
  };
  std::size_t capacity_, bytes_ = 0;
  std::list<Entry> entries_;
  std::unordered_map<std::string, std::list<Entry>::iterator> index_;
};

}  // namespace

struct ViewerSession::State {
  LightField lightField;
  ViewerLimits limits;
  double slopeMin = -4, slopeMax = 4, lensRadius = 1;
  double refocusSeconds = 0.05;  // measured once, for progress estimates
  std::counting_semaphore<1024> renderSlots;
  mutable std::mutex mutex;  // guards cache and layers
  AnswerCache cache;
  LazyLayer allInFocus, depth;

  State(LightField lf, ViewerLimits l)
      : lightField(std::move(lf)),
        limits(l),
        renderSlots(std::clamp(l.concurrentRenders, 1, 1024)),
        cache(l.cacheBytes) {}
};

ViewerSession::ViewerSession(LightField lightField, ViewerLimits limits)
    : state_(std::make_unique<State>(std::move(lightField), limits)) {
  State& s = *state_;
  const auto& meta = s.lightField.metadata;
  if (meta.disparityMin && meta.disparityMax && *meta.disparityMin < *meta.disparityMax) {
    s.slopeMin = *meta.disparityMin;
    s.slopeMax = *meta.disparityMax;
  }
  s.lensRadius = 0.5 * std::max(s.lightField.nu(), s.lightField.nv());
  if (!s.lightField.empty()) {
    const auto start = Clock::now();
    (void)refocus(s.lightField, 0.5 * (s.slopeMin + s.slopeMax));
    s.refocusSeconds = std::max(1e-3, std::chrono::duration<double>(Clock::now() - start).count());
  }
  // Refocus counts of depth.hpp and all_in_focus.hpp, rounded up.
  s.depth.expectedSeconds = 70 * s.refocusSeconds;
  s.allInFocus.expectedSeconds = 130 * s.refocusSeconds;
}

ViewerSession::~ViewerSession() = default;

const LightField& ViewerSession::lightField() const { return state_->lightField; }
double ViewerSession::slopeMin() const { return state_->slopeMin; }
double ViewerSession::slopeMax() const { return state_->slopeMax; }
double ViewerSession::lensRadius() const { return state_->lensRadius; }

std::size_t ViewerSession::cacheBytes() const {
  std::lock_guard lock(state_->mutex);
  return state_->cache.bytes();
}

std::string ViewerSession::infoJson() const {
  const LightField& lf = state_->lightField;
  nlohmann::json info = {{"width", lf.ns()},
                         {"height", lf.nt()},
                         {"nu", lf.nu()},
                         {"nv", lf.nv()},
                         {"channels", lf.channels()},
                         {"slopeMin", state_->slopeMin},
                         {"slopeMax", state_->slopeMax},
                         {"lensRadius", state_->lensRadius},
                         {"refocusMs", 1000 * state_->refocusSeconds},
                         {"source", lf.metadata.source}};
  // The whole lens's f-number, image side: F over the aperture's diameter (nu du).
  if (const auto& optics = lf.metadata.optics; optics && optics->lensStepMm > 0)
    info["lensFNumber"] = optics->lensToMicrolensMm / (std::max(lf.nu(), lf.nv()) * optics->lensStepMm);
  return info.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
}

std::string ViewerSession::statusJson() const {
  std::lock_guard lock(state_->mutex);
  auto describe = [](const LazyLayer& layer) {
    double progress = layer.state == LazyLayer::State::Ready ? 1.0 : 0.0;
    if (layer.state == LazyLayer::State::Running)
      progress =
          std::min(0.95, std::chrono::duration<double>(Clock::now() - layer.started).count() / layer.expectedSeconds);
    nlohmann::json j = {{"state", stateName(layer.state)}, {"progress", progress}};
    if (layer.state == LazyLayer::State::Failed) j["error"] = layer.error;
    return j;
  };
  return nlohmann::json{{"allInFocus", describe(state_->allInFocus)}, {"depth", describe(state_->depth)}}.dump(
      -1, ' ', true, nlohmann::json::error_handler_t::replace);
}

FocusSearch ViewerSession::focusSearch() const {
  FocusSearch search;
  search.minSlope = state_->slopeMin;
  search.maxSlope = state_->slopeMax;
  return search;
}

Result<double> ViewerSession::focusAt(double x, double y) const {
  const LightField& lf = state_->lightField;
  LFCAM_TRY(checkImagePoint(lf, "focus-at", {x, y}));
  return slopeAtPixel(lf, x, y, focusSearch());
}

namespace {

// Computes a slow layer for the caller that finds it idle; others see Running (Resource error).
Result<const LayerImages*> lazyLayer(std::mutex& mutex, LazyLayer& layer,
                                     const std::function<Result<LayerImages>()>& compute) {
  {
    std::lock_guard lock(mutex);
    switch (layer.state) {
      case LazyLayer::State::Ready: return &layer.images;
      case LazyLayer::State::Failed: return makeError(ErrorCode::Format, layer.error);
      case LazyLayer::State::Running: return makeError(ErrorCode::Resource, "running");
      case LazyLayer::State::Idle: layer.state = LazyLayer::State::Running; layer.started = Clock::now();
    }
  }
  Result<LayerImages> images = compute();
  std::lock_guard lock(mutex);
  if (!images) {
    layer.state = LazyLayer::State::Failed;
    layer.error = images.error().message;
    return images.error();
  }
  layer.images = std::move(*images);
  layer.state = LazyLayer::State::Ready;
  return &layer.images;
}

std::string cacheKey(const ViewerView& view) {
  std::string key = std::to_string(int(view.layer)) + "|" + std::to_string(view.quality);
  for (const auto& [name, text] : view.photo) key += "|" + name + "=" + text;
  return key;
}

}  // namespace

Result<ViewerSession::Photo> ViewerSession::render(const ViewerView& request) {
  State& s = *state_;
  const LightField& lf = s.lightField;
  if (lf.empty()) return makeError(ErrorCode::Usage, "empty light field");
  ViewerView view = request;
  PhotoRequest photoRequest;
  for (const auto& [name, text] : view.photo) LFCAM_TRY(setPhotoField(photoRequest, name, text));
  // A click is answered, and cached, as the slope it chose (a tilt about it keeps its point).
  if (view.layer == ViewerLayer::Photo && photoRequest.focusAt && !photoRequest.tilt) {
    LFCAM_ASSIGN_OR_RETURN(auto slope, focusAt((*photoRequest.focusAt)[0], (*photoRequest.focusAt)[1]));
    char text[32];
    std::snprintf(text, sizeof text, "%.4f", slope);
    view.photo.erase("focus-at");
    view.photo["slope"] = text;
    photoRequest.focusAt.reset();
    photoRequest.slope = slope;
  }
  const std::string key = cacheKey(view);
  {
    std::lock_guard lock(s.mutex);
    if (auto hit = s.cache.find(key)) {
      hit->cached = true;
      return std::move(*hit);
    }
  }

  Photo photo;
  Image computed;
  const Image* image = nullptr;
  auto depthLayer = [&] {
    return lazyLayer(s.mutex, s.depth, [&]() -> Result<LayerImages> {
      DepthOptions options;
      options.disparityMin = s.slopeMin;
      options.disparityMax = s.slopeMax;
      LFCAM_ASSIGN_OR_RETURN(auto result, estimateDepth(lf, options));
      Image shown = colorMap(result.disparity, result.disparityMin, result.disparityMax);
      return LayerImages{std::move(shown), std::move(result.disparity)};
    });
  };
  if (view.layer == ViewerLayer::AllInFocus) {
    auto compute = [&]() -> Result<LayerImages> {
      AllInFocusOptions options;
      options.disparityMin = s.slopeMin;
      options.disparityMax = s.slopeMax;
      LFCAM_ASSIGN_OR_RETURN(auto result, allInFocus(lf, options));
      return LayerImages{std::move(result.photo), {}};
    };
    LFCAM_ASSIGN_OR_RETURN(const LayerImages* layer, lazyLayer(s.mutex, s.allInFocus, compute));
    image = &layer->shown;
  } else if (view.layer == ViewerLayer::Depth) {
    LFCAM_ASSIGN_OR_RETURN(const LayerImages* layer, depthLayer());
    image = &layer->shown;
  } else {
    // A focus range waits for the depth layer's map (202 while another request computes it).
    if (photoRequest.focusRange) {
      LFCAM_ASSIGN_OR_RETURN(const LayerImages* layer, depthLayer());
      photoRequest.depth = std::shared_ptr<const Image>(std::shared_ptr<const Image>(), &layer->values);  // held by s
    }
    // A render slot, or 503 after waiting: bounds the memory and CPU of concurrent renders.
    if (!s.renderSlots.try_acquire_for(std::chrono::duration<double>(s.limits.renderWaitSeconds)))
      return makeError(ErrorCode::Resource, "busy: too many renders at once");
    struct Release {
      std::counting_semaphore<1024>& slots;
      ~Release() { slots.release(); }
    } release{s.renderSlots};
    LFCAM_ASSIGN_OR_RETURN(auto resolved, resolvePhoto(photoRequest, lf, {.search = focusSearch()}));
    photo.slope = resolved.film.plane.slope;
    if (photoRequest.focusPlane || photoRequest.tilt) photo.plane = resolved.film.plane;
    LFCAM_ASSIGN_OR_RETURN(computed, renderPhoto(lf, resolved));
    image = &computed;
  }
  LFCAM_ASSIGN_OR_RETURN(photo.jpeg, encodeImage(*image, {.format = EncodedFormat::Jpeg, .jpegQuality = view.quality}));
  std::lock_guard lock(s.mutex);
  s.cache.insert(key, photo);
  return photo;
}

}  // namespace lfcam
