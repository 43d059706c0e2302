#include "util/memory_limit.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <thread>

#include "util/cost_context.h"

namespace fenestra {
namespace {

// A "Key:   123 kB" line of a /proc file, in bytes; 0 when absent.
uint64_t proc_kb(const char* path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
    std::istringstream s(line.substr(key.size() + 1));
    uint64_t kb = 0;
    s >> kb;
    return kb * 1024;
  }
  return 0;
}

// A number in a cgroup file; 0 when absent or "max".
uint64_t cgroup_number(const char* path) {
  std::ifstream in(path);
  uint64_t v = 0;
  if (!(in >> v)) return 0;
  return v;
}

void consider(MemoryLimit* best, uint64_t bytes, const std::string& source) {
  if (best->source.empty() || bytes < best->bytes) *best = {bytes, source};
}

// Address space the worker threads will map when they start: an 8 MB stack and a 64 MB malloc
// arena reservation each (glibc), at most 16 counted.
uint64_t thread_reservations() {
  const uint64_t threads = std::min(16u, std::max(1u, std::thread::hardware_concurrency()));
  return threads * (uint64_t{72} << 20);
}

// Headroom under a resource limit, given what the process already uses against it.
void consider_rlimit(MemoryLimit* best, int resource, uint64_t used, const std::string& source) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
  const uint64_t cap = static_cast<uint64_t>(limit.rlim_cur);
  consider(best, cap > used ? cap - used : 0, source);
}

}  // namespace

MemoryLimit detect_available_memory() {
  MemoryLimit best;
  uint64_t available = proc_kb("/proc/meminfo", "MemAvailable");
  if (available > 0) {
    consider(&best, available, "available (MemAvailable)");
  } else {
    const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) consider(&best, static_cast<uint64_t>(pages) * page, "free (physical pages)");
  }
  // Address space: everything mapped counts (libraries, thread stacks, malloc's reservations,
  // also those of the worker threads still to start).
  consider_rlimit(&best, RLIMIT_AS, proc_kb("/proc/self/status", "VmSize") + thread_reservations(),
                  "left under the address-space limit (ulimit -v)");
  consider_rlimit(&best, RLIMIT_DATA, proc_kb("/proc/self/status", "VmData"),
                  "left under the data-size limit (ulimit -d)");
  // A container's memory limit (cgroup v2, then v1); "unlimited" reads as a huge number or "max".
  for (const auto& [limit_file, usage_file] :
       {std::pair<const char*, const char*>{"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"},
        {"/sys/fs/cgroup/memory/memory.limit_in_bytes", "/sys/fs/cgroup/memory/memory.usage_in_bytes"}}) {
    const uint64_t cap = cgroup_number(limit_file);
    if (cap == 0 || cap >= (uint64_t{1} << 60)) continue;
    const uint64_t used = cgroup_number(usage_file);
    consider(&best, cap > used ? cap - used : 0, "left under the cgroup memory limit");
  }
  if (best.source.empty()) best = {uint64_t{1} << 62, "unknown (no limit found)"};
  return best;
}

MemoryLimit memory_limit() {
  const CostContext context = cost_context();
  if (context.max_memory > 0) return {context.max_memory, "allowed by --max-memory (max_memory=)"};
  return detect_available_memory();
}

}  // namespace fenestra
