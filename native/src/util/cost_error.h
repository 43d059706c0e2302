#pragma once
// A refusal by the memory budget or the cost model, and the words it says it in.
#include <stdexcept>
#include <string>

#include "util/memory_limit.h"

namespace fenestra {

// A refusal by the cost model (a std::invalid_argument: Python's ValueError, the CLI's status 1).
class CostError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The message for `bytes` needed by `what` against `limit`: "... needs 11.5 GB, 3.2 GB available
// (MemAvailable): use a larger element_size, or raise the limit with --max-memory (max_memory=)".
std::string memory_refusal(const std::string& what, double bytes, double total_bytes, const MemoryLimit& limit,
                           const std::string& setting);

}  // namespace fenestra
