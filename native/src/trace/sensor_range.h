#pragma once
// A block of consecutive sensors, by their indices in the scene: a shard of a study that runs on
// several processes. Paths keep the scene's sensor indices (their random numbers are seeded by
// them), so a sensor's results are the same whichever block computes it.
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace fenestra {

struct SensorRange {
  size_t begin = 0;
  size_t end = std::numeric_limits<size_t>::max();  // past the last; clamped to the scene's sensors

  // The range within a scene of `sensors` sensors; throws std::invalid_argument when it is empty
  // or starts past the last sensor.
  SensorRange within(size_t sensors) const {
    const size_t last = end < sensors ? end : sensors;
    if (begin >= last)
      throw std::invalid_argument("sensor range " + std::to_string(begin) + ".." +
                                  (end == std::numeric_limits<size_t>::max() ? std::string("end") : std::to_string(end)) +
                                  " holds no sensor of the scene's " + std::to_string(sensors));
    return {begin, last};
  }
  size_t size() const { return end - begin; }
  bool whole(size_t sensors) const { return begin == 0 && end >= sensors; }
};

}  // namespace fenestra
