#include "solve/refine_openings.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "util/rng.h"

namespace fenestra {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kRelative = 1e-6;  // as in constraints.cpp: limits are met up to float rounding
// Re-clustering rounds (step 5). Each one that does not end the loop changes the number of
// openings; the bound only guards against a cycle.
constexpr int kMaxRounds = 32;
// One improvement proposal in this many adds an opening (while max_openings allows).
constexpr int kAddOneIn = 10;
// Proposals on an existing opening: 4 moves, 4 sides out, 4 sides in, removal.
constexpr int kChanges = 13;
// Local-search proposals between two polls of cancellation (a proposal takes about a microsecond).
constexpr int kPollProposals = 256;

struct Cell {
  int row = 0, col = 0;
};

// A connected set of open elements of one panel and its bounding box.
struct Region {
  std::vector<Cell> cells;
  GridRectangle box;
};

struct Size {
  int rows = 0, cols = 0;  // 0: no admissible opening fits the panel
};

// Counts of marked cells over rectangles in O(1), from a rows x cols grid of 0/1.
class CellCounts {
 public:
  CellCounts() = default;
  CellCounts(int rows, int cols, const std::vector<uint8_t>& marked)
      : cols_(cols), prefix_(static_cast<size_t>(rows + 1) * (cols + 1), 0) {
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        at(r + 1, c + 1) = at(r, c + 1) + at(r + 1, c) - at(r, c) + marked[static_cast<size_t>(r) * cols + c];
  }
  // Marked cells in rows [row0, row1] and columns [col0, col1].
  int in(int row0, int row1, int col0, int col1) const {
    return at(row1 + 1, col1 + 1) - at(row0, col1 + 1) - at(row1 + 1, col0) + at(row0, col0);
  }

 private:
  int& at(int r, int c) { return prefix_[static_cast<size_t>(r) * (cols_ + 1) + c]; }
  int at(int r, int c) const { return prefix_[static_cast<size_t>(r) * (cols_ + 1) + c]; }
  int cols_ = 0;
  std::vector<int> prefix_;
};

// Squares of a panel that an opening must not cover: missing elements, and elements with a
// missing one (or the grid's border) within the margin.
CellCounts blocked_squares(const Panel& panel, int margin) {
  const int rows = panel.rows, cols = panel.cols;
  std::vector<uint8_t> missing(static_cast<size_t>(rows) * cols);
  for (size_t k = 0; k < missing.size(); ++k) missing[k] = panel.grid[k] < 0;
  const CellCounts gaps(rows, cols, missing);
  std::vector<uint8_t> blocked(missing.size());
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const bool near_border = r - margin < 0 || c - margin < 0 || r + margin >= rows || c + margin >= cols;
      blocked[static_cast<size_t>(r) * cols + c] =
          near_border || gaps.in(r - margin, r + margin, c - margin, c + margin) > 0;
    }
  return CellCounts(rows, cols, blocked);
}

// The N-8 connected parts of a set of cells of one panel, in the order of their first cell
// (row by row), each with its bounding box.
std::vector<Region> connected_parts(int panel, const std::vector<Cell>& cells) {
  if (cells.empty()) return {};
  int row0 = cells[0].row, row1 = row0, col0 = cells[0].col, col1 = col0;
  for (const Cell& c : cells) {
    row0 = std::min(row0, c.row), row1 = std::max(row1, c.row);
    col0 = std::min(col0, c.col), col1 = std::max(col1, c.col);
  }
  const int rows = row1 - row0 + 1, cols = col1 - col0 + 1;
  constexpr int kOutside = -2, kUnvisited = -1;
  std::vector<int> label(static_cast<size_t>(rows) * cols, kOutside);
  auto index = [&](int r, int c) { return static_cast<size_t>(r - row0) * cols + (c - col0); };
  for (const Cell& c : cells) label[index(c.row, c.col)] = kUnvisited;
  std::vector<Region> parts;
  std::vector<Cell> stack;
  for (int r = row0; r <= row1; ++r)
    for (int c = col0; c <= col1; ++c) {
      if (label[index(r, c)] != kUnvisited) continue;
      Region part;
      part.box = {panel, r, r, c, c};
      label[index(r, c)] = static_cast<int>(parts.size());
      stack.push_back({r, c});
      while (!stack.empty()) {
        const Cell x = stack.back();
        stack.pop_back();
        part.cells.push_back(x);
        GridRectangle& b = part.box;
        b.row0 = std::min(b.row0, x.row), b.row1 = std::max(b.row1, x.row);
        b.col0 = std::min(b.col0, x.col), b.col1 = std::max(b.col1, x.col);
        for (int dr = -1; dr <= 1; ++dr)
          for (int dc = -1; dc <= 1; ++dc) {
            const int nr = x.row + dr, nc = x.col + dc;
            if (nr < row0 || nr > row1 || nc < col0 || nc > col1 || label[index(nr, nc)] != kUnvisited) continue;
            label[index(nr, nc)] = static_cast<int>(parts.size());
            stack.push_back({nr, nc});
          }
      }
      parts.push_back(std::move(part));
    }
  return parts;
}

// Whether the marked cells of a window that lie in rectangle [i0, i1] x [j0, j1] (window
// coordinates) form one N-8 connected piece of `inside` cells.
bool in_one_piece(const std::vector<uint8_t>& marked, int window_cols, int i0, int i1, int j0, int j1, int inside) {
  const int rows = i1 - i0 + 1, cols = j1 - j0 + 1;
  std::vector<uint8_t> seen(static_cast<size_t>(rows) * cols, 0);
  auto is_marked = [&](int i, int j) { return marked[static_cast<size_t>(i) * window_cols + j] != 0; };
  std::vector<Cell> stack;
  for (int i = i0; i <= i1 && stack.empty(); ++i)
    for (int j = j0; j <= j1 && stack.empty(); ++j)
      if (is_marked(i, j)) {
        stack.push_back({i, j});
        seen[static_cast<size_t>(i - i0) * cols + (j - j0)] = 1;
      }
  int reached = 0;
  while (!stack.empty()) {
    const Cell x = stack.back();
    stack.pop_back();
    ++reached;
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj) {
        const int i = x.row + di, j = x.col + dj;
        if (i < i0 || i > i1 || j < j0 || j > j1 || !is_marked(i, j)) continue;
        uint8_t& s = seen[static_cast<size_t>(i - i0) * cols + (j - j0)];
        if (s) continue;
        s = 1;
        stack.push_back({i, j});
      }
  }
  return reached == inside;
}

void lower_to(std::atomic<double>& bound, double value) {
  double current = bound.load(std::memory_order_relaxed);
  while (value < current && !bound.compare_exchange_weak(current, value, std::memory_order_relaxed)) {
  }
}

// ---------------------------------------------------------------------------------------------

// Light of grid rectangles at the sensors (sums of E's columns) in O(sensors) each, from 2D
// prefix sums per panel, over the sensors that carry weight (the others add to no error).
class RectangleLight {
 public:
  RectangleLight(const OpeningDomain& domain, const LinearObjective& o) : bound_weight_(o.bound_weight) {
    for (Index i = 0; i < o.E.rows(); ++i)
      if (o.weight[i] > 0.0) kept_.push_back(i);
    const Index n = static_cast<Index>(kept_.size());
    weight_.resize(n), sqrt_weight_.resize(n), target_.resize(n), lower_.resize(n), upper_.resize(n);
    for (Index s = 0; s < n; ++s) {
      const Index i = kept_[s];
      weight_[s] = o.weight[i];
      sqrt_weight_[s] = std::sqrt(o.weight[i]);
      target_[s] = o.target[i];
      lower_[s] = o.lower.size() ? o.lower[i] : -kInfinity;
      upper_[s] = o.upper.size() ? o.upper[i] : kInfinity;
    }
    for (const Panel& panel : domain.panels()) {
      const int stride = panel.cols + 1;
      MatrixXd prefix = MatrixXd::Zero(n, static_cast<Index>(panel.rows + 1) * stride);
      for (int r = 0; r < panel.rows; ++r)
        for (int c = 0; c < panel.cols; ++c) {
          auto out = prefix.col((r + 1) * stride + c + 1);
          out = prefix.col(r * stride + c + 1) + prefix.col((r + 1) * stride + c) - prefix.col(r * stride + c);
          const int k = panel.grid[static_cast<size_t>(r) * panel.cols + c];
          if (k >= 0)
            for (Index s = 0; s < n; ++s) out[s] += o.E(kept_[s], k);
        }
      prefix_.push_back(std::move(prefix));
      stride_.push_back(stride);
    }
  }

  Index sensors() const { return static_cast<Index>(kept_.size()); }
  const VectorXd& sqrt_weight() const { return sqrt_weight_; }
  // Light of the panel's elements in rows [0, row) and columns [0, col).
  auto corner(int panel, int row, int col) const { return prefix_[panel].col(row * stride_[panel] + col); }
  VectorXd of(const GridRectangle& r) const {
    return corner(r.panel, r.row1 + 1, r.col1 + 1) - corner(r.panel, r.row0, r.col1 + 1) -
           corner(r.panel, r.row1 + 1, r.col0) + corner(r.panel, r.row0, r.col0);
  }
  VectorXd of(const std::vector<GridRectangle>& rects) const {
    VectorXd sum = VectorXd::Zero(sensors());
    for (const GridRectangle& r : rects) sum += of(r);
    return sum;
  }
  // objective_error() of a prediction given on the weighted sensors.
  double error(const VectorXd& p) const {
    auto excess = [](double x) { return x > 0.0 ? x * x : 0.0; };
    double e = 0.0;
    for (Index s = 0; s < p.size(); ++s) {
      const double r = p[s] - target_[s];
      e += weight_[s] * (r * r + bound_weight_ * (excess(lower_[s] - p[s]) + excess(p[s] - upper_[s])));
    }
    return e;
  }

 private:
  std::vector<Index> kept_;
  VectorXd weight_, sqrt_weight_, target_, lower_, upper_;
  double bound_weight_;
  std::vector<MatrixXd> prefix_;
  std::vector<int> stride_;
};

// A rectangle and how far its light is from what it should match.
struct Candidate {
  GridRectangle rect;
  double error = kInfinity;
};

class Refiner {
 public:
  Refiner(const OpeningDomain& domain, const LinearObjective& objective, const OpeningConstraints& constraints,
          const Progress* progress = nullptr)
      : domain_(domain),
        constraints_(constraints),
        progress_(progress),
        a_(domain.element_size()),
        light_(domain, objective) {
    for (int p = 0; p < static_cast<int>(domain.panels().size()); ++p) {
      limits_.push_back(grid_limits(constraints.for_panel(p), a_));
      blocked_.push_back(blocked_squares(domain.panels()[p], limits_[p].margin_elements));
      smallest_.push_back(smallest_size(domain.panels()[p], limits_[p]));
    }
  }

  // Steps 1-4 once: the refined rectangles of each region of `open`.
  std::vector<GridRectangle> rectangles_of(const std::vector<uint8_t>& open) const {
    std::vector<GridRectangle> out;
    for (int p = 0; p < static_cast<int>(domain_.panels().size()); ++p) {
      const Panel& panel = domain_.panels()[p];
      std::vector<Cell> cells;
      for (int r = 0; r < panel.rows; ++r)
        for (int c = 0; c < panel.cols; ++c) {
          const int k = panel.grid[static_cast<size_t>(r) * panel.cols + c];
          if (k >= 0 && open[k]) cells.push_back({r, c});
        }
      for (const Region& region : connected_parts(p, cells)) {
        poll();
        for (const GridRectangle& r : refine_region(region)) out.push_back(r);
      }
    }
    return out;
  }

  // Throws Cancelled once the caller asked to stop.
  void poll() const {
    if (progress_) progress_->throw_if_cancelled();
  }

  // Step 6: the least change (fewest elements lost, then the lowest error) that parts each pair.
  void separate(std::vector<GridRectangle>* rects) const {
    VectorXd light = light_.of(*rects);
    for (;;) {
      poll();
      size_t i = 0, j = 0;
      if (!find_conflict(*rects, &i, &j)) return;
      const size_t smaller = (*rects)[j].element_count() <= (*rects)[i].element_count() ? j : i;
      struct Change {
        size_t which = 0;
        bool drop = false;
        GridRectangle rect;
        int lost = std::numeric_limits<int>::max();
        double error = kInfinity;
      } best;
      auto consider = [&](const Change& c) {
        if (c.lost < best.lost || (c.lost == best.lost && c.error < best.error)) best = c;
      };
      for (const auto& [x, y] : {std::pair{i, j}, std::pair{j, i}}) {
        const GridRectangle& rx = (*rects)[x];
        for (const GridRectangle& t : trims(rx, (*rects)[y]))
          if (admissible(t) && apart(t, (*rects)[y], constraints_, a_))
            consider({x, false, t, rx.element_count() - t.element_count(),
                      light_.error(light - light_.of(rx) + light_.of(t))});
      }
      const GridRectangle& rs = (*rects)[smaller];
      consider({smaller, true, rs, rs.element_count(), light_.error(light - light_.of(rs))});
      light -= light_.of((*rects)[best.which]);
      if (best.drop) {
        rects->erase(rects->begin() + static_cast<std::ptrdiff_t>(best.which));
      } else {
        light += light_.of(best.rect);
        (*rects)[best.which] = best.rect;
      }
    }
  }

  // Step 7.
  // Beyond a panel's limit (panel_opening_limit), then beyond max_openings, the opening whose
  // removal raises the error least is dropped, one at a time.
  void limit_count(std::vector<GridRectangle>* rects) const {
    VectorXd light = light_.of(*rects);
    auto drop_one = [&](int panel) {  // panel < 0: any
      size_t dropped = rects->size();
      double best = kInfinity;
      for (size_t i = 0; i < rects->size(); ++i) {
        if (panel >= 0 && (*rects)[i].panel != panel) continue;
        const double e = light_.error(light - light_.of((*rects)[i]));
        if (e < best || dropped == rects->size()) best = e, dropped = i;
      }
      light -= light_.of((*rects)[dropped]);
      rects->erase(rects->begin() + static_cast<std::ptrdiff_t>(dropped));
    };
    for (int p = 0; p < static_cast<int>(domain_.panels().size()); ++p) {
      const int limit = panel_limit(p);
      while (limit > 0 && openings_on(p, *rects) > limit) {
        poll();
        drop_one(p);
      }
    }
    while (constraints_.max_openings > 0 && static_cast<int>(rects->size()) > constraints_.max_openings) {
      poll();
      drop_one(-1);
    }
  }

  int panel_limit(int panel) const {
    return panel_opening_limit(domain_.panels()[panel], panel, constraints_, a_);
  }
  static int openings_on(int panel, const std::vector<GridRectangle>& rects) {
    return static_cast<int>(std::count_if(rects.begin(), rects.end(), [&](const GridRectangle& r) { return r.panel == panel; }));
  }

  std::vector<GridRectangle> improve(std::vector<GridRectangle> rects, uint64_t seed, int iterations) const {
    Rng rng(mix_seed(seed, 0x0BE4), mix_seed(seed, 0x1A7E));
    std::vector<int> hosts;  // panels that can hold an opening
    for (int p = 0; p < static_cast<int>(smallest_.size()); ++p)
      if (smallest_[p].rows > 0) hosts.push_back(p);
    VectorXd light = light_.of(rects);
    double error = light_.error(light);
    for (int it = 0; it < iterations; ++it) {
      if (it % kPollProposals == 0) poll();
      const int count = static_cast<int>(rects.size());
      const bool room_for_more = constraints_.max_openings <= 0 || count < constraints_.max_openings;
      if (count == 0 || (room_for_more && uniform_int(rng, kAddOneIn) == 0)) {
        if (!room_for_more || hosts.empty()) continue;
        const int p = hosts[uniform_int(rng, static_cast<int>(hosts.size()))];
        if (panel_limit(p) > 0 && openings_on(p, rects) >= panel_limit(p)) continue;
        const Panel& panel = domain_.panels()[p];
        const Size s = smallest_[p];
        GridRectangle added;
        added.panel = p;
        added.row0 = uniform_int(rng, panel.rows - s.rows + 1), added.row1 = added.row0 + s.rows - 1;
        added.col0 = uniform_int(rng, panel.cols - s.cols + 1), added.col1 = added.col0 + s.cols - 1;
        if (!admissible(added) || !apart_from_all(added, rects, -1)) continue;
        const VectorXd trial = light + light_.of(added);
        const double e = light_.error(trial);
        if (e < error) light = trial, error = e, rects.push_back(added);
        continue;
      }
      const int i = uniform_int(rng, count);
      const int change = uniform_int(rng, kChanges);
      if (change == kChanges - 1) {  // removal
        const VectorXd trial = light - light_.of(rects[i]);
        const double e = light_.error(trial);
        if (e < error) light = trial, error = e, rects.erase(rects.begin() + i);
        continue;
      }
      const GridRectangle t = changed(rects[i], change);
      if (t.row0 > t.row1 || t.col0 > t.col1 || !admissible(t) || !apart_from_all(t, rects, i)) continue;
      const VectorXd trial = light - light_.of(rects[i]) + light_.of(t);
      const double e = light_.error(trial);
      if (e < error) light = trial, error = e, rects[i] = t;
    }
    return rects;
  }

 private:
  enum class Split { kNone, kWidth, kHeight };

  // Steps 2-4 for one region: the region itself when it is admissible, else whichever of the
  // best single rectangle, the refined halves (when it needs splitting) and no opening at all
  // matches its light best.
  std::vector<GridRectangle> refine_region(const Region& region) const {
    poll();
    const GridRectangle& box = region.box;
    if (static_cast<int>(region.cells.size()) == box.element_count() && admissible(box)) return {box};
    const VectorXd y = weighted_light(region.cells, box.panel);
    double best_error = y.squaredNorm();  // of no opening
    std::vector<GridRectangle> best;
    const Candidate single = best_rectangle(region, y);
    if (single.error <= best_error) best = {single.rect}, best_error = single.error;
    auto consider = [&](std::vector<GridRectangle> rects) {
      if (rects.empty()) return;
      VectorXd light = VectorXd::Zero(y.size());
      for (const GridRectangle& r : rects) light += light_.of(r);
      const double error = (light_.sqrt_weight().cwiseProduct(light) - y).squaredNorm();
      if (error < best_error) best = std::move(rects), best_error = error;
    };
    consider(split(region));
    // Openings joined by a thin bridge of elements (the genetic algorithm's answers often have
    // them) match better as separate openings: try parting the region at its thinnest line.
    consider(part_at_waist(region, true));
    consider(part_at_waist(region, false));
    return best;
  }

  // The refined parts of a region cut across its thinnest run of `gap` columns (across_width) or
  // rows, when that run holds at most half as many elements as the region's lines do on average.
  std::vector<GridRectangle> part_at_waist(const Region& region, bool across_width) const {
    const GridRectangle& box = region.box;
    const int length = across_width ? box.cols() : box.rows();
    const int gap = limits_[box.panel].gap_elements;
    if (length < gap + 2) return {};
    std::vector<int> line(length, 0);
    for (const Cell& c : region.cells) ++line[across_width ? c.col - box.col0 : c.row - box.row0];
    int best_start = -1, best_count = std::numeric_limits<int>::max();
    for (int start = 1; start + gap < length; ++start) {
      int count = 0;
      for (int k = start; k < start + gap; ++k) count += line[k];
      if (count < best_count) best_count = count, best_start = start;
    }
    const double mean_per_line = static_cast<double>(region.cells.size()) / length;
    if (best_start < 0 || best_count > 0.5 * mean_per_line * gap) return {};
    return refine_either_side(region, across_width, best_start, gap);
  }

  // The refined parts of the region on either side of the `gap` lines (columns when
  // across_width, else rows) starting `start` lines into its bounding box, which are dropped.
  std::vector<GridRectangle> refine_either_side(const Region& region, bool across_width, int start, int gap) const {
    std::vector<Cell> sides[2];
    for (const Cell& c : region.cells) {
      const int offset = across_width ? c.col - region.box.col0 : c.row - region.box.row0;
      if (offset < start)
        sides[0].push_back(c);
      else if (offset >= start + gap)
        sides[1].push_back(c);
    }
    std::vector<GridRectangle> out;
    for (const auto& side : sides)
      for (const Region& part : connected_parts(region.box.panel, side))
        for (const GridRectangle& r : refine_region(part)) out.push_back(r);
    return out;
  }

  // Light of a set of cells, times the square root of the sensor weights.
  VectorXd weighted_light(const std::vector<Cell>& cells, int panel) const {
    VectorXd light = VectorXd::Zero(light_.sensors());
    for (const Cell& c : cells) light += light_.of(GridRectangle{panel, c.row, c.row, c.col, c.col});
    return light_.sqrt_weight().cwiseProduct(light);
  }

  // Step 4: the side of a region's bounding box to halve, when no one admissible opening could
  // cover the region.
  Split split_of(const GridRectangle& box, size_t elements) const {
    const GridLimits& limits = limits_[box.panel];
    const double aspect = static_cast<double>(box.cols()) / box.rows();
    if (box.cols() > limits.max_cols || aspect > limits.max_aspect * (1.0 + kRelative)) return Split::kWidth;
    if (box.rows() > limits.max_rows || aspect < limits.min_aspect * (1.0 - kRelative)) return Split::kHeight;
    if (static_cast<int64_t>(elements) > limits.max_elements)
      return box.cols() >= box.rows() ? Split::kWidth : Split::kHeight;
    return Split::kNone;
  }

  // The refined halves of a region that needs splitting (none when it does not, or is too short
  // to leave the gap and two halves).
  std::vector<GridRectangle> split(const Region& region) const {
    const Split how = split_of(region.box, region.cells.size());
    if (how == Split::kNone) return {};
    const bool across_width = how == Split::kWidth;
    const int length = across_width ? region.box.cols() : region.box.rows();
    const int gap = limits_[region.box.panel].gap_elements;
    if (length < gap + 2) return {};
    return refine_either_side(region, across_width, (length - gap) / 2, gap);
  }

  // Step 3: the admissible rectangle whose light best matches the region's, searched over the
  // region's bounding box (grown to hold the smallest admissible opening). For each band of rows
  // the light of column ranges [j0, j1) is F_j1 - F_j0 with F_j the band's light left of column
  // j, so all the band's errors come from one Gram matrix F^T F.
  // `y`: the region's weighted_light().
  Candidate best_rectangle(const Region& region, const VectorXd& y) const {
    const int p = region.box.panel;
    if (smallest_[p].rows == 0) return {};
    const Panel& panel = domain_.panels()[p];
    const GridRectangle w = window(region.box, smallest_[p], panel);
    const int rows = w.rows(), cols = w.cols();
    std::vector<uint8_t> member(static_cast<size_t>(rows) * cols, 0);
    for (const Cell& c : region.cells) member[static_cast<size_t>(c.row - w.row0) * cols + (c.col - w.col0)] = 1;
    const CellCounts in_region(rows, cols, member);
    const double yy = y.squaredNorm();
    const int total = static_cast<int>(region.cells.size());
    const CellCounts& blocked = blocked_[p];
    const VectorXd& sqrt_w = light_.sqrt_weight();
    const GridLimits& limits = limits_[p];

    std::atomic<double> bound{kInfinity};  // best error found so far by any band
    std::vector<Candidate> by_first_row(rows);
    tbb::parallel_for(0, rows, [&](int i0) {
      MatrixXd F(light_.sensors(), cols + 1), G(cols + 1, cols + 1);
      VectorXd g(cols + 1);
      Candidate& best = by_first_row[i0];
      const int row0 = w.row0 + i0;
      for (int i1 = i0; i1 < rows; ++i1) {
        if (progress_ && progress_->cancelled()) return;  // best_rectangle's caller polls
        const int band = i1 - i0 + 1, row1 = w.row0 + i1;
        if (band > limits.max_rows) break;
        if (band < limits.min_rows || in_region.in(i0, i1, 0, cols - 1) == 0) continue;
        if (!heights_ok(panel, p, row0, row1, constraints_, a_) || !wide_enough(blocked, row0, row1, w))
          continue;
        const VectorXd left = light_.corner(p, row1 + 1, w.col0) - light_.corner(p, row0, w.col0);
        F.col(0).setZero();
        for (int j = 1; j <= cols; ++j)
          F.col(j) = sqrt_w.cwiseProduct(light_.corner(p, row1 + 1, w.col0 + j) - light_.corner(p, row0, w.col0 + j) -
                                         left);
        G.setZero();
        G.selfadjointView<Eigen::Lower>().rankUpdate(F.transpose());
        g.noalias() = F.transpose() * y;
        for (int j0 = 0; j0 < cols; ++j0)
          for (int j1 = j0 + 1; j1 <= cols; ++j1) {  // columns [j0, j1) of the window
            const int width = j1 - j0;
            if (width > limits.max_cols || blocked.in(row0, row1, w.col0 + j0, w.col0 + j1 - 1) > 0) break;
            if (!limits.fits(band, width)) continue;
            const int inside = in_region.in(i0, i1, j0, j1 - 1);
            if (inside == 0) continue;
            const double e = G(j1, j1) + G(j0, j0) - 2.0 * G(j1, j0) - 2.0 * (g[j1] - g[j0]) + yy;
            if (!(e < best.error) || e > bound.load(std::memory_order_relaxed)) continue;
            if (inside < total && !in_one_piece(member, cols, i0, i1, j0, j1 - 1, inside)) continue;
            best = {GridRectangle{p, row0, row1, w.col0 + j0, w.col0 + j1 - 1}, e};
            lower_to(bound, e);
          }
      }
    });
    poll();
    Candidate best;
    for (const Candidate& c : by_first_row)
      if (c.error < best.error) best = c;  // ties: the lowest row first, as each band scans
    return best;
  }

  // Whether rows [row0, row1] of window `w` have min_cols adjacent unblocked columns.
  bool wide_enough(const CellCounts& blocked, int row0, int row1, const GridRectangle& w) const {
    const GridLimits& limits = limits_[w.panel];
    int run = 0;
    for (int col = w.col0; col <= w.col1; ++col) {
      run = blocked.in(row0, row1, col, col) == 0 ? run + 1 : 0;
      if (run >= limits.min_cols) return true;
    }
    return false;
  }

  // The region's bounding box grown about its centre (within the panel) to hold `smallest`.
  static GridRectangle window(const GridRectangle& box, Size smallest, const Panel& panel) {
    auto grow = [](int* lo, int* hi, int need, int limit) {
      const int extra = need - (*hi - *lo + 1);
      if (extra <= 0) return;
      *lo -= extra / 2;
      *hi += extra - extra / 2;
      if (*lo < 0) *hi -= *lo, *lo = 0;
      if (*hi >= limit) *lo -= *hi - limit + 1, *hi = limit - 1;
      *lo = std::max(*lo, 0);
    };
    GridRectangle w = box;
    grow(&w.row0, &w.row1, smallest.rows, panel.rows);
    grow(&w.col0, &w.col1, smallest.cols, panel.cols);
    return w;
  }

  // The admissible size of fewest elements (the squarest among equals) that the panel's grid
  // could hold, ignoring holes and heights.
  static Size smallest_size(const Panel& panel, const GridLimits& limits) {
    Size best;
    int64_t best_area = 0;
    for (int rows = limits.min_rows; rows <= std::min(limits.max_rows, panel.rows); ++rows)
      for (int cols = limits.min_cols; cols <= std::min(limits.max_cols, panel.cols); ++cols) {
        if (!limits.fits(rows, cols)) continue;
        const int64_t area = int64_t{rows} * cols;
        if (best.rows == 0 || area < best_area ||
            (area == best_area && std::abs(rows - cols) < std::abs(best.rows - best.cols)))
          best = {rows, cols}, best_area = area;
        break;  // wider ones at this height are larger
      }
    return best;
  }

  // The fast form of satisfies(): the same rules, with the squares checked by prefix sums.
  bool admissible(const GridRectangle& r) const {
    const Panel& panel = domain_.panels()[r.panel];
    if (r.row0 < 0 || r.col0 < 0 || r.row1 >= panel.rows || r.col1 >= panel.cols) return false;
    return limits_[r.panel].fits(r.rows(), r.cols()) && blocked_[r.panel].in(r.row0, r.row1, r.col0, r.col1) == 0 &&
           heights_ok(panel, r.panel, r.row0, r.row1, constraints_, a_);
  }

  bool apart_from_all(const GridRectangle& r, const std::vector<GridRectangle>& rects, int except) const {
    for (int k = 0; k < static_cast<int>(rects.size()); ++k)
      if (k != except && !apart(r, rects[k], constraints_, a_)) return false;
    return true;
  }

  // The first pair of openings that are not apart().
  bool find_conflict(const std::vector<GridRectangle>& rects, size_t* i, size_t* j) const {
    for (size_t x = 0; x < rects.size(); ++x, poll())
      for (size_t y = x + 1; y < rects.size(); ++y)
        if (!apart(rects[x], rects[y], constraints_, a_)) {
          *i = x, *j = y;
          return true;
        }
    return false;
  }

  // Whole elements needed between two openings along one axis when `across` elements separate
  // them along the other.
  int gap_needed(int panel, int across) const {
    for (int n = 0;; ++n)
      if (apart(GridRectangle{panel, 0, 0, 0, 0}, GridRectangle{panel, across + 1, across + 1, n + 1, n + 1},
                constraints_, a_))
        return n;
  }

  // `x` with the side facing `y` pulled back just far enough to be apart from it (each axis,
  // each direction where that leaves something).
  std::vector<GridRectangle> trims(const GridRectangle& x, const GridRectangle& y) const {
    const int gap_rows = std::max({0, y.row0 - x.row1 - 1, x.row0 - y.row1 - 1});
    const int gap_cols = std::max({0, y.col0 - x.col1 - 1, x.col0 - y.col1 - 1});
    const int need_cols = gap_needed(x.panel, gap_rows), need_rows = gap_needed(x.panel, gap_cols);
    std::vector<GridRectangle> out;
    auto keep = [&](const GridRectangle& t) {
      if (t.row0 <= t.row1 && t.col0 <= t.col1 && t != x) out.push_back(t);
    };
    GridRectangle t = x;
    t.col1 = std::min(x.col1, y.col0 - 1 - need_cols);
    keep(t);
    t = x;
    t.col0 = std::max(x.col0, y.col1 + 1 + need_cols);
    keep(t);
    t = x;
    t.row1 = std::min(x.row1, y.row0 - 1 - need_rows);
    keep(t);
    t = x;
    t.row0 = std::max(x.row0, y.row1 + 1 + need_rows);
    keep(t);
    return out;
  }

  // Improvement proposal `change` (< kChanges - 1) on one opening.
  static GridRectangle changed(GridRectangle r, int change) {
    if (change < 4) {  // moves: left, right, down, up
      const int dc = change == 0 ? -1 : change == 1 ? 1 : 0, dr = change == 2 ? -1 : change == 3 ? 1 : 0;
      return r.moved(dr, dc);
    }
    const int side = (change - 4) / 2, step = (change - 4) % 2 == 0 ? 1 : -1;  // out, then in
    return r.side_moved(side, step);
  }

  const OpeningDomain& domain_;
  const OpeningConstraints& constraints_;
  const Progress* progress_;
  double a_;
  std::vector<GridLimits> limits_;  // per panel
  RectangleLight light_;
  std::vector<CellCounts> blocked_;  // per panel
  std::vector<Size> smallest_;       // per panel
};

void check_inputs(const OpeningDomain& domain, const LinearObjective& o, const OpeningConstraints& c) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("opening refinement: " + what); };
  const Index elements = static_cast<Index>(domain.element_count()), sensors = o.E.rows();
  if (elements == 0) fail("the opening domain has no elements");
  if (o.E.cols() != elements)
    fail("E has " + std::to_string(o.E.cols()) + " columns for " + std::to_string(elements) + " elements");
  if (o.target.size() != sensors || o.weight.size() != sensors)
    fail("target and weight need one value per sensor (" + std::to_string(sensors) + ")");
  if ((o.lower.size() != 0 && o.lower.size() != sensors) || (o.upper.size() != 0 && o.upper.size() != sensors))
    fail("lower and upper need one value per sensor (" + std::to_string(sensors) + ") or none");
  if (!o.E.allFinite() || !o.target.allFinite()) fail("E and target must be finite");
  if (!o.weight.allFinite() || (o.weight.array() < 0.0).any()) fail("weights must be finite and >= 0");
  if (o.lower.hasNaN() || o.upper.hasNaN()) fail("bounds must not be NaN");
  if (!(o.bound_weight >= 0.0) || !std::isfinite(o.bound_weight)) fail("bound_weight must be >= 0");
  const size_t panels = domain.panels().size();
  if (!c.panel_base_z.empty() && c.panel_base_z.size() != panels)
    fail("panel_base_z has " + std::to_string(c.panel_base_z.size()) + " values for " + std::to_string(panels) +
         " panels");
  if (!c.per_panel.empty() && c.per_panel.size() != panels)
    fail("per_panel has " + std::to_string(c.per_panel.size()) + " sets for " + std::to_string(panels) + " panels");
  check_feasible(c, domain.element_size());
  for (const OpeningConstraints& set : c.per_panel) check_feasible(set, domain.element_size());
}

}  // namespace

std::vector<GridRectangle> refine_openings(const OpeningDomain& domain, const std::vector<uint8_t>& open,
                                           const LinearObjective& objective, const OpeningConstraints& constraints,
                                           const Progress* progress) {
  check_inputs(domain, objective, constraints);
  if (open.size() != domain.element_count())
    throw std::invalid_argument("opening refinement: the open mask has " + std::to_string(open.size()) +
                                " values for " + std::to_string(domain.element_count()) + " elements");
  const Refiner refiner(domain, objective, constraints, progress);
  std::vector<GridRectangle> rects = refiner.rectangles_of(open);
  for (int round = 1; round < kMaxRounds; ++round) {
    std::vector<GridRectangle> next = refiner.rectangles_of(rectangles_mask(domain, rects));
    const bool stable = next.size() == rects.size();
    rects = std::move(next);
    if (stable) break;
  }
  refiner.separate(&rects);
  refiner.limit_count(&rects);
  std::sort(rects.begin(), rects.end());
  std::string why;
  if (!satisfies_all(domain, rects, constraints, &why))
    throw std::logic_error("opening refinement left an inadmissible opening: " + why);
  return rects;
}

std::vector<GridRectangle> improve_rectangles(const OpeningDomain& domain, std::vector<GridRectangle> rectangles,
                                              const LinearObjective& objective, const OpeningConstraints& constraints,
                                              uint64_t seed, int iterations, const Progress* progress) {
  check_inputs(domain, objective, constraints);
  if (iterations < 0) throw std::invalid_argument("opening improvement: iterations must be >= 0");
  std::string why;
  if (!satisfies_all(domain, rectangles, constraints, &why))
    throw std::invalid_argument("opening improvement: the openings given break the constraints: " + why);
  const Refiner refiner(domain, objective, constraints, progress);
  std::vector<GridRectangle> out = refiner.improve(std::move(rectangles), seed, iterations);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace fenestra
