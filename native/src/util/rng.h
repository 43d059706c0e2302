#pragma once
// PCG32 (O'Neill 2014): small state, so every path can own a stream derived from
// (seed, sensor, path) and results do not depend on how paths are spread over threads.
#include <cstdint>

namespace fenestra {

class Rng {
 public:
  Rng(uint64_t seed, uint64_t stream) {
    inc_ = (stream << 1u) | 1u;
    state_ = 0;
    next_u32();
    state_ += seed;
    next_u32();
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
  }

  // Uniform in [0, 1).
  float uniform() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0;
  uint64_t inc_ = 1;
};

// SplitMix64 finaliser: decorrelates neighbouring (sensor, path) indices.
inline uint64_t mix_seed(uint64_t a, uint64_t b) {
  uint64_t z = a * 0x9E3779B97F4A7C15ULL + b + 0x632BE59BD9B4E019ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Generator of path `path` of sensor `sensor`: PCG streams that share a start state are
// correlated, so both the state and the stream are hashed from all three indices.
inline Rng path_rng(uint64_t seed, uint64_t sensor, uint64_t path) {
  const uint64_t key = mix_seed(mix_seed(seed, sensor), path);
  return Rng(key, mix_seed(key, 0x5EED));
}

// Uniform in [0, n) by multiply-shift (bias below n / 2^32).
inline int uniform_int(Rng& rng, int n) {
  return static_cast<int>((uint64_t{rng.next_u32()} * static_cast<uint64_t>(n)) >> 32);
}

}  // namespace fenestra
