#pragma once
// What the climate goals' figures are made of: per goal sensor, its hours that count (sDA, ASE,
// UDI) and its lux summed over the occupied hours (mean goals, per-sensor goals); per EN 17037
// goal and daylight hour, how many of its sensors reach the target and the minimum target. A
// tally of some of the sensors is computed where their hours are (a shard of the hourly model);
// tallies of disjoint sensors add exactly (integers, and each sensor's sum kept in its own slot),
// so the figures of a model held in shards are those of the whole model, bit for bit, whatever
// the shards and the order they arrive in.
#include <cstdint>
#include <vector>

namespace fenestra {

struct ClimateTally {
  // Per goal, per model row (0 outside the goal or not tallied): sDA, the occupied hours at or
  // above its illuminance; ASE, the occupied hours of direct sun above it; UDI, the occupied
  // hours within its band.
  std::vector<std::vector<int32_t>> hours;
  // Per model row: lux summed over the occupied hours in the model (0 when not tallied; empty when
  // no goal needs it).
  std::vector<double> occupied_sum;
  // Per goal (empty unless EN 17037), per daylight column of the model: sensors of the goal at or
  // above its target illuminance, and at or above its minimum target.
  std::vector<std::vector<int32_t>> above_target, above_minimum;

  // Adds the tally of other sensors of the same model (the same goals and columns). Throws
  // std::invalid_argument when the two are not of the same model, or both tallied a row.
  void add(const ClimateTally& other);
};

}  // namespace fenestra
