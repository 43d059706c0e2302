#pragma once
// The stratified decisions of one sensor path (render.sampler "sobol"): the sensor's sky and sun
// samples, its first bounce, and the sky sample, sun sample and bounce of the vertex that bounce
// reaches. Path p of a sensor is point p / kReplicates of its replicate group's own scramble
// (replicates.h), so the paths of a group are stratified together and the groups stay independent:
// their spread is still an honest standard error. Every later decision uses the path's Rng.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>

#include "sampling/owen_sobol.h"
#include "scene/scene.h"
#include "trace/replicates.h"
#include "util/rng.h"

namespace fenestra {

class PathSamples {
 public:
  // One pair of dimensions per decision (a 1D decision takes the first of its pair).
  enum Pair : uint32_t {
    kSensorSky,
    kSensorSun,
    kSensorSunPick,
    kFirstBounce,
    kVertexSky,
    kVertexSun,
    kVertexSunPick,
    kVertexBsdf,
    kVertexLobe,
    kSensorPortal,  // the sensor's portal samples: which element (32 bits) and where on it
    kVertexPortalPick,  // an interior vertex's portal: an element (recording) or an opening (a cut)
    kVertexPortal,
    kSensorOpeningPick,  // with openings cut: which opening the sensor's sky sample goes through
  };

  // `seed` names the stream (the scene's seed, salted by the kind of pass).
  PathSamples(uint64_t seed, size_t sensor, size_t path)
      : key_(mix_seed(mix_seed(seed, sensor), 0x5AB1E5 + replicate_of(path))),
        index_(static_cast<uint32_t>(path / kReplicates)) {}

  Vec2 get2d(Pair pair) const { return owen_sobol_2d(index_, pair, key_); }
  float get1d(Pair pair) const { return get2d(pair).x(); }
  // Portal sample j of the path's `per_path`: point index * per_path + j of its own sequence, so
  // the group's portal samples, the path's few among them, are stratified together. The first
  // coordinate as a 32-bit fraction (it picks the element, PortalSelection), the second in [0, 1).
  std::pair<uint32_t, float> portal(size_t j, size_t per_path) const {
    const std::array<uint32_t, 2> bits =
        owen_sobol_bits(static_cast<uint32_t>(index_ * per_path + j), kSensorPortal, key_);
    return {bits[0], fraction_to_float(bits[1])};
  }

 private:
  uint64_t key_;
  uint32_t index_;
};

// The path's stratified samples under the scene's sampler, or none (independent random numbers).
inline std::optional<PathSamples> path_samples(const RenderSettings& render, uint64_t seed, size_t sensor,
                                               size_t path) {
  if (render.sampler != RenderSettings::Sampler::kSobol) return std::nullopt;
  return PathSamples(seed, sensor, path);
}

}  // namespace fenestra
