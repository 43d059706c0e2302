#pragma once
// A vertex position as a hash key: coordinates rounded to 10 micrometers, so that faces sharing a
// corner match even where the model repeats the vertex.
#include <cmath>
#include <cstdint>

#include "math/vec.h"

namespace fenestra {

inline uint64_t position_key(const Vec3& p) {
  auto q = [](float x) { return static_cast<uint64_t>(static_cast<int64_t>(std::llround(x * 1e5)) & 0x1FFFFF); };
  return q(p.x()) | (q(p.y()) << 21) | (q(p.z()) << 42);
}

}  // namespace fenestra
