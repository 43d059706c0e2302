#pragma once
// The opening elements as grid cells: panel, row, column and the N-8 neighbourhood within the
// panel, which the solver's redistribution and shape terms need.
#include <array>
#include <cstdint>
#include <vector>

namespace fenestra {

class OpeningDomain;

class ElementGrid {
 public:
  static constexpr int kNone = -1;
  struct Cell {
    int panel = 0, row = 0, col = 0;
  };

  ElementGrid() = default;
  explicit ElementGrid(std::vector<Cell> cells);      // neighbours found from (panel, row, col)
  static ElementGrid from_domain(const OpeningDomain& domain);
  static ElementGrid rectangle(int rows, int cols);   // one panel, row-major cells (tests, benchmarks)

  int size() const { return static_cast<int>(cells_.size()); }
  const Cell& cell(int k) const { return cells_[k]; }
  // N-8 neighbours of element k in its panel, kNone where the grid has no element. Order:
  // the 4 edge neighbours first (left, right, down, up), then the 4 corner ones.
  const std::array<int32_t, 8>& neighbours(int k) const { return neighbours_[k]; }
  // Element at (panel, row, col) or kNone.
  int at(int panel, int row, int col) const;

 private:
  std::vector<Cell> cells_;
  std::vector<std::array<int32_t, 8>> neighbours_;
};

}  // namespace fenestra
