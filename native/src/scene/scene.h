#pragma once
// Everything a computation needs: geometry, materials, opening domain, sensors, sky, settings.
#include <memory>
#include <string>
#include <vector>

#include "daylight/sky.h"
#include "daylight/sun_lights.h"
#include "scene/climate_goals.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/opening_domain.h"
#include "scene/site_frame.h"
#include "scene/solver_settings.h"

namespace fenestra {

struct Daylight;  // daylight/daylight.h
struct Climate;   // daylight/sky_matrix.h
class Progress;   // util/progress.h

struct Sensors {
  std::vector<Vec3> points;   // meters
  std::vector<Vec3> normals;  // unit
  std::vector<double> goals;  // empty when the scene gives none; NaN: this sensor has no goal
  std::vector<double> weights;  // empty: all 1
  std::vector<UniformGoal> uniform_goals;  // levels over sets of sensors, in goal_units
  std::string goal_units = "normalized";  // "normalized", "lux" or "daylight_factor" (percent)
  // Climate-based goals (sDA, ASE, EN 17037, UDI, annual mean) over sets of sensors; a climate sky only.
  ClimateGoals climate_goals;
  size_t size() const { return points.size(); }
};

struct RenderSettings {
  int paths_per_sensor = 4096;
  int max_bounces = 8;  // surface interactions after the sensor, inside and outside
  uint64_t seed = 1;
  int threads = 0;      // 0: all hardware threads
  // How a sensor path draws its first decisions (the sensor's sky and sun samples, its first bounce,
  // and those of the vertex it reaches): Owen-scrambled Sobol points, stratified over the paths of
  // each replicate group, or independent random numbers (the estimator before stratification).
  enum class Sampler { kSobol, kIndependent };
  Sampler sampler = Sampler::kSobol;
  std::string to_string() const;
};

// "sobol" or "independent" (render.sampler); parse_sampler returns false for any other name.
const char* sampler_name(RenderSettings::Sampler sampler);
bool parse_sampler(const std::string& name, RenderSettings::Sampler* out);

struct Scene {
  std::string source;  // scene file, for messages
  // Every position below (mesh, domain, sensors, openings) is in this local frame, meters; files and
  // the Python API speak the input's (site) coordinates, converted on the way in and out.
  SiteFrame site;
  Mesh mesh;
  std::vector<Material> materials;
  OpeningDomain domain;
  Sensors sensors;
  std::shared_ptr<const Sky> sky;
  SunLights suns;  // a daylight sky's sun, one disk per time step (empty for other skies)
  std::shared_ptr<const Daylight> daylight;  // how a daylight sky was built (null for others)
  // A "climate" sky: its settings, weather and hourly sky matrix, for annual studies. `sky` and
  // `suns` then hold the cumulative sky of its occupied hours (null for other skies).
  std::shared_ptr<const Climate> climate;
  RenderSettings render;
  SolverSettings solver;
  // Files the scene was read from: the scene file (when loaded from one), the OBJ, an
  // environment map, a weather file. Outputs must not overwrite them.
  std::vector<std::string> input_files;

  std::vector<std::string> material_names() const;
  std::string to_string() const;
};

// Reads a scene file (JSON + OBJ, see docs/scene-format.md). Throws std::invalid_argument
// naming the file and the offending key or value. With `progress`, a daylight sky's build
// reports its steps and polls cancellation (throws Cancelled).
Scene load_scene(const std::string& path, Progress* progress = nullptr);
// Same from JSON text; relative paths resolve against `base_dir`.
Scene parse_scene(const std::string& json_text, const std::string& base_dir, const std::string& source_name,
                  Progress* progress = nullptr);

}  // namespace fenestra
