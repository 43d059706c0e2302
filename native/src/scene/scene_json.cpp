#include "scene/scene_json.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

#include "format/json_keys.h"
#include "util/quoted_text.h"

namespace fenestra::scene_json {

void check_known_keys(const ScenePath& sp, const json& obj, const std::string& key,
                      const std::vector<std::string>& known) {
  if (const auto unknown = find_unknown_key(obj, known))
    sp.fail((key.empty() ? "" : key + ".") + quoted_text(unknown->key), unknown->message);
}

void check_misspelt(const ScenePath& sp, const json& obj, const std::string& key, const std::string& name) {
  if (!obj.is_object() || obj.contains(name)) return;
  for (const auto& item : obj.items())
    if (closest_word(item.key(), {name}) == name)
      sp.fail(key + "." + quoted_text(item.key()), "unknown key; did you mean `" + name + "`?");
}

double number(const ScenePath& sp, const json& j, const std::string& key) {
  if (!j.is_number()) sp.fail(key, "expected a number, got " + quoted_json(j));
  const double v = j.get<double>();
  if (!std::isfinite(v)) sp.fail(key, "must be finite");
  return v;
}

double number_or(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key, double fallback) {
  return obj.contains(name) ? number(sp, obj.at(name), key + "." + name) : fallback;
}

std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

double number_in(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                 double fallback, double lo, double hi, const std::string& unit) {
  if (!obj.contains(name)) return fallback;
  const double v = number(sp, obj.at(name), key + "." + name);
  if (!(v >= lo && v <= hi))
    sp.fail(key + "." + name, "must lie in [" + show(lo) + ", " + show(hi) + "]" + unit + ", got " + quoted_json(obj.at(name)));
  return v;
}

long long integer_in(const ScenePath& sp, const json& j, const IntegerRange& range, const std::string& key) {
  const double v = number(sp, j, key);
  if (v != std::floor(v) || v < static_cast<double>(range.lo) || v > static_cast<double>(range.hi))
    sp.fail(key, range.requirement() + ", got " + quoted_json(j));
  return static_cast<long long>(v);
}

std::vector<double> numbers(const ScenePath& sp, const json& j, const std::string& key, size_t count) {
  if (!j.is_array() || j.size() != count)
    sp.fail(key, "expected a list of " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (size_t i = 0; i < j.size(); ++i) out.push_back(number(sp, j[i], key + "[" + std::to_string(i) + "]"));
  return out;
}

std::string text(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key) {
  if (!obj.contains(name)) sp.fail(key + "." + name, "missing");
  if (!obj.at(name).is_string()) sp.fail(key + "." + name, "expected a string, got " + quoted_json(obj.at(name)));
  return obj.at(name).get<std::string>();
}

std::string text_or(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                    const std::string& fallback) {
  if (!obj.contains(name)) return fallback;
  if (!obj.at(name).is_string()) sp.fail(key + "." + name, "expected a string, got " + quoted_json(obj.at(name)));
  return obj.at(name).get<std::string>();
}

std::vector<std::string> names(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key) {
  std::vector<std::string> out;
  if (!obj.contains(name)) return out;
  const json& j = obj.at(name);
  if (!j.is_array()) sp.fail(key + "." + name, "expected a list of names");
  for (const auto& e : j) {
    if (!e.is_string()) sp.fail(key + "." + name, "expected names, got " + quoted_json(e));
    out.push_back(e.get<std::string>());
  }
  return out;
}

Rgb colour(const ScenePath& sp, const json& j, const std::string& key) {
  Rgb c;
  if (j.is_number())
    c = Rgb::Constant(static_cast<float>(number(sp, j, key)));
  else if (j.is_array() && j.size() == 3)
    c = Rgb(number(sp, j[0], key), number(sp, j[1], key), number(sp, j[2], key));
  else
    sp.fail(key, "expected a number or [r, g, b], got " + quoted_json(j));
  if (!c.isFinite().all()) sp.fail(key, "is too large for a float (beyond 3.4e38), got " + quoted_json(j));
  return c;
}

void check_range(const ScenePath& sp, const Rgb& c, float lo, float hi, const std::string& key) {
  if ((c < lo).any() || (c > hi).any()) {
    std::ostringstream s;
    s << "must lie in [" << lo << ", " << hi << "], got [" << c.transpose() << "]";
    sp.fail(key, s.str());
  }
}

Vec3 point(const ScenePath& sp, const json& j, const std::string& key, const SiteFrame& frame) {
  if (!j.is_array() || j.size() != 3) sp.fail(key, "expected [x, y, z], got " + quoted_json(j));
  const double x = number(sp, j[0], key), y = number(sp, j[1], key), z = number(sp, j[2], key);
  if (!coordinate_in_range(x) || !coordinate_in_range(y) || !coordinate_in_range(z))
    sp.fail(key, "coordinates " + coordinate_requirement() + ", got " + quoted_json(j));
  const Vec3d site(x, y, z);
  if (!local_coordinates_in_range(frame.to_local_exact(site))) sp.fail(key, quoted_json(j) + " " + local_range_problem(frame.origin));
  return frame.to_local(site);
}

Vec3 direction(const ScenePath& sp, const json& j, const std::string& key) {
  if (!j.is_array() || j.size() != 3) sp.fail(key, "expected [x, y, z], got " + quoted_json(j));
  const double x = number(sp, j[0], key), y = number(sp, j[1], key), z = number(sp, j[2], key);
  if (Vec3d(x, y, z).cwiseAbs().maxCoeff() > limits::kMaxNormalComponent)
    sp.fail(key, "components of a normal must lie within +-" + show(limits::kMaxNormalComponent) + ", got " + quoted_json(j));
  const double n = std::sqrt(x * x + y * y + z * z);
  if (!(n > 1e-6)) sp.fail(key, "a normal must not be zero (length at least 1e-6), got " + quoted_json(j));
  return Vec3(x / n, y / n, z / n);
}

}  // namespace fenestra::scene_json
