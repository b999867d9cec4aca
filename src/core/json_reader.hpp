// Reading JSON objects (scene, camera and grid files) with errors that name the file and the key
// ("scene.json: camera.sensor.width: expected an integer in [1, 100000]"), and unknown keys
// reported instead of ignored (a misspelt key would otherwise silently do nothing).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <set>
#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam::json_reader {

class JsonObject {
 public:
  // `path`: the key path of this object ("camera.sensor"); `where`: the file.
  JsonObject(const nlohmann::json& json, std::string where, std::string path)
      : json_(json), where_(std::move(where)), path_(std::move(path)) {}

  Status requireObject() const {
    if (!json_.is_object()) return fail(path_.empty() ? "(top level)" : path_, "expected an object");
    return {};
  }
  bool has(const char* key) const { return json_.contains(key) && !json_.at(key).is_null(); }
  const nlohmann::json& at(const char* key) const { return json_.at(key); }
  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  Status number(const char* key, double& out, double lo, double hi, bool openLow = false) const {
    seen_.insert(key);
    if (!has(key)) return {};
    const auto& value = json_.at(key);
    if (!value.is_number()) return fail(keyPath(key), "expected a number");
    const double x = value.get<double>();
    if (!(openLow ? x > lo : x >= lo) || !(x <= hi))
      return fail(keyPath(key), "expected a number " + range(lo, hi, openLow) + ", got " + value.dump());
    out = x;
    return {};
  }
  Status optionalNumber(const char* key, std::optional<double>& out, double lo, double hi, bool openLow = false) const {
    if (!has(key)) {
      seen_.insert(key);
      return {};
    }
    double x = 0;
    LFCAM_TRY(number(key, x, lo, hi, openLow));
    out = x;
    return {};
  }
  Status integer(const char* key, int& out, long long lo, long long hi) const {
    seen_.insert(key);
    if (!has(key)) return {};
    const auto& value = json_.at(key);
    if (!value.is_number_integer() && !value.is_number_unsigned()) return fail(keyPath(key), "expected an integer");
    const long long x = value.get<long long>();
    if (x < lo || x > hi)
      return fail(keyPath(key), "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                    "], got " + value.dump());
    out = int(x);
    return {};
  }
  Status unsignedInteger(const char* key, std::uint64_t& out) const {
    seen_.insert(key);
    if (!has(key)) return {};
    const auto& value = json_.at(key);
    if (!value.is_number_unsigned() && !(value.is_number_integer() && value.get<long long>() >= 0))
      return fail(keyPath(key), "expected a non-negative integer");
    out = value.get<std::uint64_t>();
    return {};
  }
  Status boolean(const char* key, bool& out) const {
    seen_.insert(key);
    if (!has(key)) return {};
    if (!json_.at(key).is_boolean()) return fail(keyPath(key), "expected true or false");
    out = json_.at(key).get<bool>();
    return {};
  }
  Status string(const char* key, std::string& out) const {
    seen_.insert(key);
    if (!has(key)) return {};
    if (!json_.at(key).is_string()) return fail(keyPath(key), "expected a string");
    out = json_.at(key).get<std::string>();
    return {};
  }
  template <std::size_t N>
  Status numbers(const char* key, std::array<double, N>& out, double lo, double hi) const {
    seen_.insert(key);
    if (!has(key)) return {};
    const auto& value = json_.at(key);
    const std::string what = "expected an array of " + std::to_string(N) + " numbers " + range(lo, hi, false);
    if (!value.is_array() || value.size() != N) return fail(keyPath(key), what);
    std::array<double, N> result{};
    for (std::size_t k = 0; k < N; ++k) {
      if (!value[k].is_number()) return fail(keyPath(key), what);
      result[k] = value[k].get<double>();
      if (!(result[k] >= lo && result[k] <= hi)) return fail(keyPath(key), what + ", got " + value.dump());
    }
    out = result;
    return {};
  }
  // A colour: one number (grey) or [r, g, b], each in [0, 1000].
  Status colour(const char* key, std::array<float, 3>& out) const {
    seen_.insert(key);
    if (!has(key)) return {};
    const auto& value = json_.at(key);
    const std::string what = "expected a radiance: a number or [r, g, b], each in [0, 1000]";
    auto ok = [](double x) { return x >= 0 && x <= 1000; };
    if (value.is_number()) {
      const double x = value.get<double>();
      if (!ok(x)) return fail(keyPath(key), what);
      out = {float(x), float(x), float(x)};
      return {};
    }
    if (!value.is_array() || value.size() != 3) return fail(keyPath(key), what);
    for (int k = 0; k < 3; ++k) {
      if (!value[k].is_number() || !ok(value[k].get<double>())) return fail(keyPath(key), what);
      out[k] = value[k].get<float>();
    }
    return {};
  }
  void markSeen(const char* key) const { seen_.insert(key); }
  // Fails on the first key that no reader asked for.
  Status noUnknownKeys() const {
    for (const auto& item : json_.items())
      if (!seen_.count(item.key())) return fail(keyPath(item.key()), "unknown key");
    return {};
  }
  Error fail(const std::string& key, const std::string& message) const {
    return makeError(ErrorCode::Format, where_ + ": " + key + ": " + message);
  }
  const std::string& where() const { return where_; }

 private:
  static std::string range(double lo, double hi, bool openLow) {
    auto text = [](double x) {
      std::string s = nlohmann::json(x).dump();
      return s;
    };
    return std::string("in ") + (openLow ? "(" : "[") + text(lo) + ", " + text(hi) + "]";
  }
  const nlohmann::json& json_;
  std::string where_, path_;
  mutable std::set<std::string> seen_;
};

}  // namespace lfcam::json_reader
