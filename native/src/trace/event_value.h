#pragma once
// A path event's value in 16 bits: a non-negative float's exponent (8 bits) and the top 8 bits of
// its mantissa, so the full float range at a relative step of at most 2^-8 (0.39 %).
//
// Rounding is stochastic: up with probability equal to the dropped fraction of a step, so the
// stored value's expectation is the value itself and every sum of events stays unbiased. The
// rounding adds a variance of at most (step / 2)^2 per event, under 4e-6 of its value squared,
// which no Monte Carlo estimate of the records can see. `dither` supplies the random fraction;
// it is a hash of the event (value, place in its path), so records do not depend on threads.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace fenestra {

class EventValue {
 public:
  static constexpr int kDroppedBits = 15;
  static constexpr uint32_t kDroppedMask = (1u << kDroppedBits) - 1;
  // Largest finite stored pattern: exponent 0xFE, mantissa all ones.
  static constexpr uint16_t kLargest = 0xFEFF;

  EventValue() = default;
  // `dither`'s low 15 bits are the uniform fraction that decides the rounding.
  static EventValue round(float value, uint32_t dither) {
    if (!(value >= 0.0f) || !std::isfinite(value))
      throw std::logic_error("EventValue: a path event's value must be finite and non-negative");
    uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    const uint32_t rounded = (bits + (dither & kDroppedMask)) >> kDroppedBits;
    EventValue v;
    v.bits_ = static_cast<uint16_t>(rounded > kLargest ? kLargest : rounded);
    return v;
  }
  float get() const {
    const uint32_t bits = static_cast<uint32_t>(bits_) << kDroppedBits;
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  uint16_t bits() const { return bits_; }

 private:
  uint16_t bits_ = 0;
};

// The rounding fraction of an event: a SplitMix64-style hash of its value's bits and a key (its
// place in its path and what it concerns), so fractions of different events behave as independent
// uniform numbers.
inline uint32_t event_dither(float value, uint64_t key) {
  uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  uint64_t z = (static_cast<uint64_t>(bits) << 32 | (key & 0xFFFFFFFFu)) * 0x9E3779B97F4A7C15ULL + (key >> 32);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return static_cast<uint32_t>(z ^ (z >> 31));
}

}  // namespace fenestra
