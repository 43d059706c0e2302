#pragma once
// How much memory a computation may still allocate: the smallest of the memory the system has
// available (MemAvailable in /proc/meminfo), the headroom left under the process's address-space
// and data limits (RLIMIT_AS, RLIMIT_DATA: `ulimit -v`, `ulimit -d`) and under a cgroup memory
// limit; or the figure the user gave (--max-memory, max_memory=), which replaces them all.
#include <cstdint>
#include <string>

namespace fenestra {

struct MemoryLimit {
  uint64_t bytes = 0;
  std::string source;  // what the figure is, for messages: "available (MemAvailable)", ...
};

// What the system allows now (no override).
MemoryLimit detect_available_memory();

// The figure in force on this thread: the override of a CostScope (util/cost_context.h) or the
// process-wide one when set, else detect_available_memory().
MemoryLimit memory_limit();

}  // namespace fenestra
