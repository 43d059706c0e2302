#include "trace/contributions_origin.h"

#include <cstring>
#include <stdexcept>

#include "trace/contributions.h"

namespace fenestra {
namespace {

// FNV-1a, 64 bits.
class Hash {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  void f(float v) { bytes(&v, sizeof v); }
  void i(int64_t v) { bytes(&v, sizeof v); }
  void vec(const Vec3& v) { f(v.x()), f(v.y()), f(v.z()); }
  void d(double v) { bytes(&v, sizeof v); }
  void text(const std::string& s) { i(static_cast<int64_t>(s.size())), bytes(s.data(), s.size()); }
  uint64_t value() const { return h_ == 0 ? 1 : h_; }

 private:
  uint64_t h_ = 14695981039346656037ull;
};

}  // namespace

ContributionsOrigin contributions_origin(const Scene& scene) {
  ContributionsOrigin o;
  o.source = scene.source;
  o.sensors = scene.sensors.size();
  o.elements = scene.domain.element_count();
  Hash layout;
  // The same local layout elsewhere on the site is another scene (its outputs lie elsewhere).
  if (scene.site.shifted()) layout.d(scene.site.origin.x()), layout.d(scene.site.origin.y()), layout.d(scene.site.origin.z());
  for (size_t i = 0; i < scene.sensors.size(); ++i) layout.vec(scene.sensors.points[i]), layout.vec(scene.sensors.normals[i]);
  for (const Element& e : scene.domain.elements()) {
    layout.i(e.panel), layout.i(e.row), layout.i(e.col);
    for (const Vec3& c : e.corners) layout.vec(c);
  }
  o.layout = layout.value();
  Hash sky;
  sky.text(scene.sky ? scene.sky->to_string() : std::string());
  for (const SunLight& s : scene.suns.suns()) {
    sky.vec(s.direction);
    for (int k = 0; k < 3; ++k) sky.f(s.normal_illuminance[k]);
  }
  o.sky = sky.value();
  return o;
}

void check_contributions_match(const Scene& scene, const Contributions& c, const std::string& use) {
  const ContributionsOrigin here = contributions_origin(scene);
  const std::string from = c.origin.known() ? " (from scene '" + c.origin.source + "')" : std::string();
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument(use + ": the contributions" + from + " do not belong to scene '" + scene.source +
                                "': " + why + "; compute them for this scene");
  };
  if (c.sensor_count() != here.sensors || c.element_count() != here.elements)
    fail("they have " + std::to_string(c.sensor_count()) + " sensors x " + std::to_string(c.element_count()) +
         " elements, the scene " + std::to_string(here.sensors) + " sensors x " + std::to_string(here.elements) +
         " elements");
  if (!c.origin.known()) return;
  if (c.origin.layout != here.layout) fail("the sensors or the element grid differ");
  if (c.origin.sky != here.sky) fail("they were computed under a different sky");
}

}  // namespace fenestra
