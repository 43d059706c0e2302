#pragma once
// What the benchmarks of fenestra_bench share: wall-clock timing, the process's peak memory and
// load, the runs' seeds, and the JSON report's writing.
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace bench {

using Clock = std::chrono::steady_clock;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using fenestra::Scene;
using nlohmann::json;

// Distinct seeds: ladder and baseline runs must be independent of the reference.
inline constexpr uint64_t kLadderSeed = 1, kBaselineSeed = 2, kPilotSeed = 3, kReferenceSeed = 1000;

// Wall-clock seconds since `start`.
double seconds_since(Clock::time_point start);
// The process's peak resident memory so far, MiB.
double peak_rss_mib();

// Other work on the machine slows every timing; the reader should see how busy it was.
double load_average();
double mib(double bytes);

// The scene traced with `paths` per sensor from `seed`.
Scene with_paths(const Scene& base, int paths, uint64_t seed);

// Extra paths needed to bring `error` down to `target` when error falls as 1/sqrt(paths).
double path_factor(double error, double target);

// The report written whole (or not at all), and a line saying so.
void write_json(const std::string& path, const json& report);

}  // namespace bench
