#pragma once
// Flip effects (trace/flip_effects.h) kept by the set of open elements they were taken about. The
// solver linearises about the same sets again and again (the constraint costs search from the
// free answer and from the kept openings once per family of limits, and the local searches often
// end where an earlier one did), and each linearisation reads every path of every sensor. The
// least recently used matrices go first once the kept ones would pass the budget.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

namespace fenestra {

// Flip effects kept at most: matrices, and bytes (the cost model's flip_effects_kept).
constexpr size_t kFlipEffectsKept = 16;
constexpr size_t kFlipEffectsCacheBytes = size_t{128} << 20;

class FlipEffectsCache {
 public:
  explicit FlipEffectsCache(size_t byte_budget = kFlipEffectsCacheBytes, size_t max_kept = kFlipEffectsKept)
      : budget_(byte_budget), max_kept_(max_kept) {}

  // The flip effects about `about`: kept ones, or compute()'s, kept when `keep` (false for an
  // answer a cancelled computation left partly filled) and when they fit the budget.
  Eigen::MatrixXd about(const std::vector<uint8_t>& about, const std::function<Eigen::MatrixXd()>& compute,
                        const std::function<bool()>& keep = nullptr);

  size_t hits() const { return hits_; }
  size_t misses() const { return misses_; }
  size_t memory_bytes() const { return bytes_; }

 private:
  struct Kept {
    Eigen::MatrixXd effects;
    size_t last_use = 0;
  };
  void make_room(size_t bytes);

  size_t budget_, max_kept_;
  std::map<std::vector<uint8_t>, Kept> kept_;
  size_t bytes_ = 0, uses_ = 0, hits_ = 0, misses_ = 0;
};

}  // namespace fenestra
