#pragma once
// Open elements merged into rectangles: within each panel, greedy maximal rectangles (widest run
// along a row first, then as many rows as keep it whole), in world coordinates.
#include <cstdint>
#include <vector>

#include "scene/opening_domain.h"

namespace fenestra {

struct OpeningRectangle {
  std::array<Vec3, 4> corners;  // counter-clockwise about the panel normal, meters
  int panel = 0;
  int row0 = 0, row1 = 0, col0 = 0, col1 = 0;  // inclusive element ranges
  std::vector<int> elements;
};

std::vector<OpeningRectangle> merge_into_rectangles(const OpeningDomain& domain, const std::vector<uint8_t>& open);

}  // namespace fenestra
