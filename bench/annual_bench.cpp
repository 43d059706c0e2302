// Benchmark of annual studies on the paper-scale scene (100 sensors x 200 elements): contributions
// under a climate sky (Chicago, sky patches and sun clusters) against the same pass under one
// Preetham sky (time and the all-open values' relative standard error, measured in one run), and a
// year of one configuration after them (100 sensors x 8760 hours: coefficients, the product with the
// sky matrix, the sun, and every metric). Ratios are what to read: timings on a shared machine are noisy.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "annual/annual_contributions.h"
#include "annual/annual_study.h"
#include "scene/scene.h"
#include "trace/contributions.h"

namespace {

using namespace fenestra;
using json = nlohmann::json;

const std::string kExamples = FENESTRA_EXAMPLES;

Scene paper_scale_with(const json& sky, int patches_subdivision = 1) {
  std::ifstream in(kExamples + "/paper_scale/scene.json");
  json scene = json::parse(in);
  scene["sky"] = sky;
  if (sky["type"] == "climate") scene["sky"]["patches"] = patches_subdivision;
  return parse_scene(scene.dump(), kExamples + "/paper_scale", "paper_scale (" + sky["type"].get<std::string>() + ")");
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

double mean_relative_error(const SensorValues& v) {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < v.value.size(); ++i) sum += v.standard_error[i] / std::max(1e-9, v.value[i]);
  return sum / static_cast<double>(v.value.size());
}

}  // namespace

int main() {
  const std::string epw = kExamples + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";
  const json preetham = {{"type", "preetham"}, {"latitude", 41.98}, {"longitude", -87.92}, {"utc_offset", -6},
                         {"date", "2026-06-21"}, {"start", "08:00"}, {"end", "18:00"}, {"step_minutes", 60}};
  const Scene one_sky = paper_scale_with(preetham);
  auto t = std::chrono::steady_clock::now();
  const Contributions today = compute_contributions(one_sky);
  const double today_s = seconds_since(t);
  std::printf("[annual] paper_scale: %zu sensors x %zu elements, %d paths per sensor\n", today.sensor_count(),
              today.element_count(), today.paths_per_sensor);
  std::printf("  one Preetham sky (10 hourly steps): contributions %.2f s, all-open relative standard error %.2f %%\n",
              today_s, 100.0 * mean_relative_error(today.all_open));
  for (const int mf : {1, 2}) {
    t = std::chrono::steady_clock::now();
    const Scene climate = paper_scale_with({{"type", "climate"}, {"weather", epw}, {"resolution", {256, 128}}}, mf);
    const double load_s = seconds_since(t);
    t = std::chrono::steady_clock::now();
    const Contributions year = compute_contributions(climate);
    const double year_s = seconds_since(t);
    std::printf("  climate, %d sky patches, %zu sun clusters: scene %.2f s, contributions %.2f s (%.2fx one sky), "
                "all-open relative standard error %.2f %%\n",
                year.annual->sources.patch_count - 1, year.annual->sources.suns.size(), load_s, year_s, year_s / today_s,
                100.0 * mean_relative_error(year.all_open));
    const std::vector<uint8_t> open(year.element_count(), 1);
    double best = 1e30;
    AnnualStudy study;
    for (int run = 0; run < 5; ++run) {
      t = std::chrono::steady_clock::now();
      study = annual_study(year, open);
      best = std::min(best, seconds_since(t));
    }
    std::printf("    a year of one configuration (%ld sensors x %ld hours, metrics included): %.3f s (best of 5)\n",
                static_cast<long>(study.illuminance.total.rows()), static_cast<long>(study.illuminance.total.cols()),
                best);
  }
  return 0;
}
