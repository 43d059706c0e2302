#include "solve/element_grid.h"

#include <map>
#include <stdexcept>
#include <tuple>

#include "scene/opening_domain.h"

namespace fenestra {

namespace {
using Key = std::tuple<int, int, int>;
constexpr int kOffsets[8][2] = {{0, -1}, {0, 1}, {-1, 0}, {1, 0}, {-1, -1}, {-1, 1}, {1, -1}, {1, 1}};  // (row, col)
}  // namespace

ElementGrid::ElementGrid(std::vector<Cell> cells) : cells_(std::move(cells)) {
  std::map<Key, int> index;
  for (int k = 0; k < size(); ++k) {
    const Cell& c = cells_[k];
    if (!index.emplace(Key{c.panel, c.row, c.col}, k).second)
      throw std::invalid_argument("element grid: two elements share panel " + std::to_string(c.panel) + ", row " +
                                  std::to_string(c.row) + ", column " + std::to_string(c.col));
  }
  neighbours_.resize(cells_.size());
  for (int k = 0; k < size(); ++k) {
    const Cell& c = cells_[k];
    for (int n = 0; n < 8; ++n) {
      const auto it = index.find(Key{c.panel, c.row + kOffsets[n][0], c.col + kOffsets[n][1]});
      neighbours_[k][n] = it == index.end() ? kNone : it->second;
    }
  }
}

ElementGrid ElementGrid::from_domain(const OpeningDomain& domain) {
  std::vector<Cell> cells;
  for (const Element& e : domain.elements()) cells.push_back({e.panel, e.row, e.col});
  return ElementGrid(std::move(cells));
}

ElementGrid ElementGrid::rectangle(int rows, int cols) {
  std::vector<Cell> cells;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) cells.push_back({0, r, c});
  return ElementGrid(std::move(cells));
}

int ElementGrid::at(int panel, int row, int col) const {
  // Cells are few per lookup site (tests, coarsening): a linear search keeps the class small.
  for (int k = 0; k < size(); ++k)
    if (cells_[k].panel == panel && cells_[k].row == row && cells_[k].col == col) return k;
  return kNone;
}

}  // namespace fenestra
