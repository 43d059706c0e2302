#pragma once
// Owen-scrambled Sobol points, padded two dimensions at a time (Burley 2020, "Practical
// Hash-based Owen Scrambling"). Each pair of dimensions takes the first two Sobol dimensions, a
// (0,2)-sequence: any 2^m consecutive points from an aligned start put one point in every
// elementary interval of area 2^-m. Every pair has its own scramble of the point and shuffle of the
// index, so pairs are independent of one another while each is stratified on its own. Nested
// uniform scrambling keeps every point uniform on [0, 1)^2, so an estimate is unbiased, and
// independently scrambled sets give i.i.d. estimates (replicates.h).
#include <array>
#include <cstdint>

#include "math/vec.h"

namespace fenestra {

inline uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Sobol's first dimension (van der Corput in base 2) and second (direction numbers v_k = v_{k-1}
// ^ (v_{k-1} >> 1)), as 32-bit fractions.
inline uint32_t sobol_dimension0(uint32_t index) { return reverse_bits(index); }
inline uint32_t sobol_dimension1(uint32_t index) {
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

// Laine-Karras style permutation: bit k of the result depends on bits 0..k of x only.
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Nested uniform (Owen) scramble of a 32-bit fraction: each digit is flipped by a hash of the
// digits above it.
inline uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

inline uint32_t hash_u32(uint64_t a, uint64_t b) {
  uint64_t z = a * 0x9E3779B97F4A7C15ULL + b + 0x632BE59BD9B4E019ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return static_cast<uint32_t>(z ^ (z >> 31));
}

inline float fraction_to_float(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

// Point `index` of pair `pair` of the sequence scrambled by `seed`, as 32-bit fractions of 2^32.
inline std::array<uint32_t, 2> owen_sobol_bits(uint32_t index, uint32_t pair, uint64_t seed) {
  const uint32_t shuffle = hash_u32(seed, 4 * pair + 0);
  const uint32_t i = nested_uniform_scramble(index, shuffle);
  return {nested_uniform_scramble(sobol_dimension0(i), hash_u32(seed, 4 * pair + 1)),
          nested_uniform_scramble(sobol_dimension1(i), hash_u32(seed, 4 * pair + 2))};
}

// The same point in [0, 1)^2.
inline Vec2 owen_sobol_2d(uint32_t index, uint32_t pair, uint64_t seed) {
  const std::array<uint32_t, 2> bits = owen_sobol_bits(index, pair, seed);
  return Vec2(fraction_to_float(bits[0]), fraction_to_float(bits[1]));
}

}  // namespace fenestra
