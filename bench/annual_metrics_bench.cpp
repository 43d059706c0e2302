// Benchmark: every climate-based metric (mean, DA, cDA, UDI, sDA, ASE, EN 17037) for 100 sensors x
// 8760 hours of single-precision illuminance, with direct-sun illuminance and daylight hours chosen
// from external illuminance. Milliseconds on this machine, one thread: wall clock (noisy when other
// jobs share the cores) and the thread's own CPU time (what the computation costs).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "daylight/annual_metrics.h"

int main() {
  using namespace fenestra;
  const int sensors = 100, hours = 8760;
  static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  Eigen::MatrixXf total(sensors, hours), direct(sensors, hours);
  AnnualMetricInputs in;
  int j = 0;
  for (int month = 1; month <= 12; ++month)
    for (int day = 1; day <= kDays[month - 1]; ++day)
      for (int h = 0; h < 24; ++h, ++j) {
        in.hours.push_back({month, day, h + 0.5});
        // A daily arc scaled by a season and a pseudo-random cloudiness.
        const double arc = std::max(0.0, std::sin(3.14159265358979 * (h + 0.5 - 6.0) / 12.0));
        const double season = 0.6 + 0.4 * std::sin(2.0 * 3.14159265358979 * (j / 24 - 80) / 365.0);
        const double cloud = 0.3 + 0.7 * std::fabs(std::sin(j * 0.618));
        in.external_horizontal_illuminance.push_back(100000.0 * arc * season * cloud);
        for (int i = 0; i < sensors; ++i) {
          total(i, j) = static_cast<float>((50.0 + 40.0 * i) * arc * season * cloud);
          direct(i, j) = i % 4 == 0 ? static_cast<float>(5000.0 * arc * season * cloud * cloud) : 0.0f;
        }
      }
  std::printf("[annual metrics] %d sensors x %d hours (float), with ASE and EN 17037\n", sensors, hours);
  const auto cpu_ms = [] {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * t.tv_sec + 1e-6 * t.tv_nsec;
  };
  std::vector<double> wall, cpu;
  AnnualMetrics m;
  for (int run = 0; run < 21; ++run) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = cpu_ms();
    m = annual_metrics(total, in, {}, &direct);
    cpu.push_back(cpu_ms() - cpu_start);
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  std::printf("[annual metrics] over %zu runs: wall median %.2f ms (fastest %.2f), CPU median %.2f ms (fastest %.2f)\n",
              wall.size(), wall[wall.size() / 2], wall.front(), cpu[cpu.size() / 2], cpu.front());
  std::printf("[annual metrics] %s\n", m.to_string().c_str());
  return 0;
}
