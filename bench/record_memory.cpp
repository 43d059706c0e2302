#include "record_memory.h"

#include <cstdint>
#include <cstdio>

namespace bench {

size_t bytes_in_previous_layout(const fenestra::Contributions& c) {
  size_t bytes = c.memory_bytes();
  for (const fenestra::SensorRecord& r : c.records) {
    size_t conditions = 0;
    for (size_t p = 0; p < r.path_count(); ++p)
      r.walk(p, [&](uint32_t, const fenestra::PathEvent&, const fenestra::EventConditions& ec) {
        conditions += ec.count();
        return true;
      });
    bytes -= r.memory_bytes();
    bytes += r.events.size() * 24 + conditions * 12 + r.path_count() * 4 +
             r.event_sources.size() * sizeof(uint16_t) + r.event_coefficients.size() * sizeof(float);
  }
  return bytes;
}

json memory_json(const TimeToAccuracy& t, double peak_rss) {
  return {{"contributions_memory_bytes", t.memory_bytes},
          {"contributions_memory_measured", t.measured},
          {"peak_rss_mib", peak_rss}};
}

void print_memory(const TimeToAccuracy& t, const Rung& top, double peak_rss) {
  std::printf("[4] Memory\n");
  if (t.measured)
    std::printf("    Contributions::memory_bytes() of the time-to-accuracy run: %.1f MiB\n", mib(t.memory_bytes));
  else
    std::printf("    Contributions::memory_bytes(): %.1f MiB at the top rung (%d paths); EXTRAPOLATED to the\n"
                "    time-to-accuracy path count: ~%.0f MiB (path records grow linearly with paths)\n",
                mib(top.memory_bytes), top.paths, mib(t.memory_bytes));
  std::printf("    peak RSS of this process: %.1f MiB (its largest run: a %d-path rung or reference chunk)\n\n",
              peak_rss, top.paths);
}

}  // namespace bench
