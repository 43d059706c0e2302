#pragma once
// [4] Memory: the contributions' path records at the time-to-accuracy path count, against the
// layout they had before compaction, and the bench's peak resident memory.
#include <cstddef>

#include "accuracy_ladder.h"
#include "trace/contributions.h"

namespace bench {

// Contributions::memory_bytes() had the same records been laid out as before they were compacted:
// a 16-byte event and an 8-byte panel point each, every condition (light through one element's
// too) 4 bytes and an 8-byte point, one 4-byte offset per path. The baseline of the memory target.
size_t bytes_in_previous_layout(const fenestra::Contributions& c);

// The report: JSON ("memory") and printed lines; `top` is the ladder's last rung.
json memory_json(const TimeToAccuracy& t, double peak_rss);
void print_memory(const TimeToAccuracy& t, const Rung& top, double peak_rss);

}  // namespace bench
