#pragma once
// Path-aware reading of the scene file's JSON: each reader takes the value and its key path
// ("sky.latitude", "sensors.points[3]") and refuses a bad value with std::invalid_argument
// "scene 'FILE': KEY: what is wrong", so every section's messages name file and key alike.
#include <nlohmann/json_fwd.hpp>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "math/vec.h"
#include "scene/input_limits.h"
#include "scene/site_frame.h"

namespace fenestra::scene_json {

using nlohmann::json;

// The scene file a value comes from, and the one way a value is refused.
class ScenePath {
 public:
  explicit ScenePath(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw std::invalid_argument("scene '" + source_ + "': " + key + ": " + message);
  }
  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

// Refuses a key of `obj` (the section `key`, "" at the top level) that is not in `known`, naming
// the closest known one. Each section lists its keys where it reads them.
void check_known_keys(const ScenePath& sp, const json& obj, const std::string& key,
                      const std::vector<std::string>& known);

// When `name` (a key that chooses which others apply, such as "type") is missing, a key one typo
// away from it is named as such, rather than as unknown to the default it then falls back on.
void check_misspelt(const ScenePath& sp, const json& obj, const std::string& key, const std::string& name);

// A finite number.
double number(const ScenePath& sp, const json& j, const std::string& key);
// obj[name], read at "key.name", or the fallback when it is not given.
double number_or(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                 double fallback);
// obj[name] (or the fallback) within [lo, hi], `unit` for the message (e.g. " m").
double number_in(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                 double fallback, double lo, double hi, const std::string& unit);
// A whole number within `range`, checked before it is converted to the integer it lands in.
long long integer_in(const ScenePath& sp, const json& j, const IntegerRange& range, const std::string& key);
// A list of `count` numbers, each read at "key[i]".
std::vector<double> numbers(const ScenePath& sp, const json& j, const std::string& key, size_t count);
// A number as the messages show it (the stream's default: 6 significant digits).
std::string show(double v);

// obj[name], a string: required, or with a fallback when it is not given.
std::string text(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key);
std::string text_or(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                    const std::string& fallback);
// obj[name], a list of names (materials, groups); empty when it is not given.
std::vector<std::string> names(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key);

// A colour: one number for grey or [r, g, b], each finite in float.
Rgb colour(const ScenePath& sp, const json& j, const std::string& key);
// Refuses a colour with a channel outside [lo, hi].
void check_range(const ScenePath& sp, const Rgb& c, float lo, float hi, const std::string& key);

// A position in meters, finite and within +-limits::kMaxCoordinate, read in double and returned in
// the scene's local frame (within +-limits::kMaxLocalCoordinate of its origin).
Vec3 point(const ScenePath& sp, const json& j, const std::string& key, const SiteFrame& frame);
// A direction, normalized in double precision: components within +-limits::kMaxNormalComponent, not zero.
Vec3 direction(const ScenePath& sp, const json& j, const std::string& key);

}  // namespace fenestra::scene_json
