#include "bench_common.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "format/atomic_file.h"

namespace bench {

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

double load_average() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : std::nan("");
}

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

Scene with_paths(const Scene& base, int paths, uint64_t seed) {
  Scene scene = base;
  scene.render.paths_per_sensor = paths;
  scene.render.seed = seed;
  return scene;
}

double path_factor(double error, double target) { return (error / target) * (error / target); }

void write_json(const std::string& path, const json& report) {
  fenestra::write_atomically(path, [&](std::ostream& out) { out << report.dump(2) << "\n"; });
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace bench
