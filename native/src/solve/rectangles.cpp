#include "solve/rectangles.h"

#include <map>
#include <tuple>

namespace fenestra {

std::vector<OpeningRectangle> merge_into_rectangles(const OpeningDomain& domain, const std::vector<uint8_t>& open) {
  const auto& elements = domain.elements();
  std::map<std::tuple<int, int, int>, int> index;  // (panel, row, col) -> element
  for (size_t k = 0; k < elements.size(); ++k)
    if (open[k]) index[{elements[k].panel, elements[k].row, elements[k].col}] = static_cast<int>(k);
  auto free_at = [&](int panel, int row, int col) {
    const auto it = index.find({panel, row, col});
    return it == index.end() ? -1 : it->second;
  };
  std::vector<OpeningRectangle> out;
  while (!index.empty()) {
    // The first free element in (panel, row, col) order starts a rectangle.
    const auto [panel, row0, col0] = index.begin()->first;
    int col1 = col0;
    while (free_at(panel, row0, col1 + 1) >= 0) ++col1;
    int row1 = row0;
    for (;;) {
      bool whole = true;
      for (int c = col0; c <= col1 && whole; ++c) whole = free_at(panel, row1 + 1, c) >= 0;
      if (!whole) break;
      ++row1;
    }
    OpeningRectangle r;
    r.panel = panel;
    r.row0 = row0;
    r.row1 = row1;
    r.col0 = col0;
    r.col1 = col1;
    for (int rr = row0; rr <= row1; ++rr)
      for (int c = col0; c <= col1; ++c) {
        r.elements.push_back(free_at(panel, rr, c));
        index.erase({panel, rr, c});
      }
    const auto corner = [&](int rr, int c, int which) { return elements[r.elements[(rr - row0) * (col1 - col0 + 1) + (c - col0)]].corners[which]; };
    r.corners = {corner(row0, col0, 0), corner(row0, col1, 1), corner(row1, col1, 2), corner(row1, col0, 3)};
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace fenestra
