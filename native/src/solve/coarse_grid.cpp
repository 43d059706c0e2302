#include "solve/coarse_grid.h"

#include <map>
#include <tuple>

namespace fenestra {

namespace {
int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace

CoarseGrid coarsen(const ElementGrid& fine, int factor) {
  CoarseGrid out;
  std::map<std::tuple<int, int, int>, int> index;
  std::vector<ElementGrid::Cell> cells;
  out.coarse_of.resize(fine.size());
  for (int k = 0; k < fine.size(); ++k) {
    const ElementGrid::Cell& c = fine.cell(k);
    const std::tuple<int, int, int> key{c.panel, floor_div(c.row, factor), floor_div(c.col, factor)};
    const auto [it, inserted] = index.emplace(key, static_cast<int>(cells.size()));
    if (inserted) cells.push_back({c.panel, std::get<1>(key), std::get<2>(key)});
    out.coarse_of[k] = it->second;
  }
  out.grid = ElementGrid(std::move(cells));
  return out;
}

Eigen::MatrixXd CoarseGrid::columns(const Eigen::MatrixXd& fine) const {
  Eigen::MatrixXd coarse = Eigen::MatrixXd::Zero(fine.rows(), grid.size());
  for (size_t k = 0; k < coarse_of.size(); ++k) coarse.col(coarse_of[k]) += fine.col(static_cast<Eigen::Index>(k));
  return coarse;
}

std::vector<uint8_t> CoarseGrid::expand(const std::vector<uint8_t>& coarse_open) const {
  std::vector<uint8_t> fine(coarse_of.size());
  for (size_t k = 0; k < coarse_of.size(); ++k) fine[k] = coarse_open[coarse_of[k]];
  return fine;
}

}  // namespace fenestra
