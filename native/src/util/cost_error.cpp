#include "util/cost_error.h"

#include <sstream>

#include "util/byte_size.h"

namespace fenestra {

std::string memory_refusal(const std::string& what, double bytes, double total_bytes, const MemoryLimit& limit,
                           const std::string& setting) {
  std::ostringstream s;
  s << what << " needs " << format_bytes(bytes);
  if (total_bytes > 1.05 * bytes) s << " (" << format_bytes(total_bytes) << " in all)";
  s << ", " << format_bytes(static_cast<double>(limit.bytes)) << " " << limit.source << ": use " << setting
    << ", or raise the limit with --max-memory (max_memory= in Python)";
  return s.str();
}

}  // namespace fenestra
