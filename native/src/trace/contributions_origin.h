#pragma once
// What a contribution matrix was computed for, so that it is never used with another scene:
// sensor and element counts, a fingerprint of the sensors and the element grid, and one of the sky.
#include <cstdint>
#include <string>

namespace fenestra {

struct Scene;
struct Contributions;

struct ContributionsOrigin {
  std::string source;       // the scene's file name, for messages
  uint64_t sensors = 0, elements = 0;
  uint64_t layout = 0;      // sensor points and normals, element grid and corners
  uint64_t sky = 0;         // the sky and the sun list
  bool known() const { return layout != 0; }
};

ContributionsOrigin contributions_origin(const Scene& scene);

// Throws std::invalid_argument ("<use>: the contributions were computed for ...") when `c` does
// not belong to `scene`: different sensor or element counts always; a different layout or sky
// when `c` knows its origin.
void check_contributions_match(const Scene& scene, const Contributions& c, const std::string& use);

}  // namespace fenestra
