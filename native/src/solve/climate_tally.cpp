#include "solve/climate_tally.h"

#include <stdexcept>
#include <string>

namespace fenestra {
namespace {

void add_counts(std::vector<std::vector<int32_t>>* into, const std::vector<std::vector<int32_t>>& from,
                const char* what) {
  if (into->size() != from.size()) throw std::invalid_argument(std::string("climate tally: ") + what + " of another model");
  for (size_t g = 0; g < from.size(); ++g) {
    std::vector<int32_t>& a = (*into)[g];
    const std::vector<int32_t>& b = from[g];
    if (a.size() != b.size()) throw std::invalid_argument(std::string("climate tally: ") + what + " of another model");
    for (size_t i = 0; i < b.size(); ++i) a[i] += b[i];
  }
}

}  // namespace

void ClimateTally::add(const ClimateTally& other) {
  add_counts(&hours, other.hours, "hours");
  add_counts(&above_target, other.above_target, "EN 17037 counts");
  add_counts(&above_minimum, other.above_minimum, "EN 17037 counts");
  if (occupied_sum.size() != other.occupied_sum.size())
    throw std::invalid_argument("climate tally: occupied sums of another model");
  for (size_t r = 0; r < occupied_sum.size(); ++r) {
    if (other.occupied_sum[r] == 0.0) continue;
    // One shard holds each row: adding to the untallied 0 keeps its sum exact.
    if (occupied_sum[r] != 0.0)
      throw std::invalid_argument("climate tally: model row " + std::to_string(r) + " tallied twice");
    occupied_sum[r] = other.occupied_sum[r];
  }
}

}  // namespace fenestra
