#include "scene/scene.h"

#include <sstream>

namespace fenestra {

std::vector<std::string> Scene::material_names() const {
  std::vector<std::string> out;
  for (const auto& m : materials) out.push_back(m.name);
  return out;
}

const char* sampler_name(RenderSettings::Sampler sampler) {
  return sampler == RenderSettings::Sampler::kSobol ? "sobol" : "independent";
}

bool parse_sampler(const std::string& name, RenderSettings::Sampler* out) {
  if (name == "sobol") *out = RenderSettings::Sampler::kSobol;
  else if (name == "independent") *out = RenderSettings::Sampler::kIndependent;
  else return false;
  return true;
}

std::string RenderSettings::to_string() const {
  std::ostringstream s;
  s << "RenderSettings(paths_per_sensor=" << paths_per_sensor << ", max_bounces=" << max_bounces << ", seed=" << seed
    << ", threads=" << threads << ", sampler='" << sampler_name(sampler) << "')";
  return s.str();
}

std::string Scene::to_string() const {
  std::ostringstream s;
  s << "Scene('" << source << "', " << mesh.triangle_count() << " triangles, " << materials.size() << " materials, "
    << domain.panels().size() << " panels, " << domain.element_count() << " elements of " << domain.element_size()
    << " m, " << sensors.size() << " sensors, " << (sky ? sky->to_string() : "no sky");
  if (site.shifted()) s << ", local origin at " << site.to_string();
  s << ")";
  return s.str();
}

}  // namespace fenestra
