#pragma once
// Fenestra's mathematical constants, in one home (as pbrt-v4's util/math.h).

namespace fenestra {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
constexpr double kPiD = 3.14159265358979323846;  // the daylight models compute in double

}  // namespace fenestra
