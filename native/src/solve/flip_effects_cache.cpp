#include "solve/flip_effects_cache.h"

#include <algorithm>

namespace fenestra {
namespace {

size_t bytes_of(const Eigen::MatrixXd& m) { return static_cast<size_t>(m.size()) * sizeof(double); }

}  // namespace

Eigen::MatrixXd FlipEffectsCache::about(const std::vector<uint8_t>& about,
                                        const std::function<Eigen::MatrixXd()>& compute,
                                        const std::function<bool()>& keep) {
  ++uses_;
  if (auto it = kept_.find(about); it != kept_.end()) {
    ++hits_;
    it->second.last_use = uses_;
    return it->second.effects;
  }
  ++misses_;
  Eigen::MatrixXd effects = compute();
  const size_t bytes = bytes_of(effects);
  if (bytes > budget_ || max_kept_ == 0 || (keep && !keep())) return effects;
  make_room(bytes);
  kept_.emplace(about, Kept{effects, uses_});
  bytes_ += bytes;
  return effects;
}

void FlipEffectsCache::make_room(size_t bytes) {
  while (!kept_.empty() && (bytes_ + bytes > budget_ || kept_.size() >= max_kept_)) {
    auto oldest = std::min_element(kept_.begin(), kept_.end(),
                                   [](const auto& a, const auto& b) { return a.second.last_use < b.second.last_use; });
    bytes_ -= bytes_of(oldest->second.effects);
    kept_.erase(oldest);
  }
}

}  // namespace fenestra
