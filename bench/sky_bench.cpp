// Benchmark: building the averaged daylight environment (Preetham sky, sun list) for a full day at
// 15-minute steps, 1024 x 512 pixels. Wall-clock seconds on this machine; noisy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "daylight/daylight.h"

int main() {
  using namespace fenestra;
  DaylightSettings s;
  s.place = {37.98, 23.73, 0.0};
  s.time_zone = TimeZone::fixed(3.0);
  s.date = s.date_end = parse_date("2026-06-21");
  s.start_minutes = 0.0;
  s.end_minutes = 24 * 60.0;
  s.step_minutes = 15.0;
  s.turbidity = 3.0;
  s.width = 1024;
  s.height = 512;
  std::printf("[sky] Preetham day average, Athens 2026-06-21 00:00-24:00 every 15 min, %d x %d, %u threads\n", s.width,
              s.height, std::thread::hardware_concurrency());
  std::vector<double> seconds;
  Daylight d;
  for (int run = 0; run < 5; ++run) {
    d = make_daylight(s);
    seconds.push_back(d.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("    %zu steps, %zu with the sun up; horizontal illuminance sky %.0f lx + sun %.0f lx\n", d.steps,
              d.steps_with_sun, luminance(d.sky_horizontal), luminance(d.sun_horizontal));
  std::printf("    build time: median %.3f s (min %.3f, max %.3f over 5 runs); %.1f ms per step with the sun up\n",
              seconds[2], seconds.front(), seconds.back(), 1e3 * seconds[2] / std::max<size_t>(1, d.steps_with_sun));
  return 0;
}
