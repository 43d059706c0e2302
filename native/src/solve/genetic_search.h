#pragma once
// The genetic algorithm's engine, for any error model: the population, breeding, survivors and
// the final polish (solve/genetic.h tells what it does). An error model `Error` gives:
//   using Response = ...;                        what the error is computed from
//   static constexpr bool kPairPolish;           whether the polish also tries pairs of flips
//   Response response(const State& open) const;  computed in full
//   void flip(Response*, const State& open, int j) const;   element j flips (open: before it)
//   double operator()(const Response&) const;    the error
//   double flip_change(const Response&, const State&, int j) const;
//   double pair_change(const Response&, const State&, int j, int k) const;
//   double scale() const;                        the size of errors (rounding tolerance)
//   static constexpr bool kBatched;              whether responses are scored in batches:
// A batched model (climate goals held in shards, where each question is a round trip) scores no
// response when it is made or flipped. Its Response carries `slot` (where its state's year is
// kept), `base` (the slot it was derived from) and `error`; the engine gives every individual a
// slot of its own and asks:
//   void settle(const std::vector<Response*>&, const std::vector<const State*>&) const;
//       scores a batch of responses (each derived from its base, which is settled) in one go
//   std::vector<double> flip_errors(const Response&, const State&, const std::vector<int>& js) const;
//       the error after each of js flips alone
// Internal to the solver: included by genetic.cpp and climate_search.cpp only.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "solve/genetic.h"
#include "util/progress.h"
#include "util/rng.h"

// A child: tournament selection (3 entrants) of two parents, a random rectangular block of one
// panel taken from the second (openings are 2D shapes, so whole blocks carry meaning), then one
// or two mutations (a random flip; an element added to or removed from a region's side; a whole
// side moved by one). The survivors are the best distinct states of parents and children. The
// best is finally polished by greedy one- and two-element flips, which finish what random
// mutations reach only slowly on large grids.

namespace fenestra {
namespace genetic_search {

using State = std::vector<uint8_t>;

constexpr int kNone = ElementGrid::kNone;
// Slots of ElementGrid::neighbours(): 0 left, 1 right, 2 down, 3 up, then the corners.
constexpr int kEdgeSlots = 4;
// The slots perpendicular to each edge slot (the direction along a region's side).
constexpr int kAlongSide[4][2] = {{2, 3}, {2, 3}, {0, 1}, {0, 1}};
// The N-8 ring in cyclic order, as neighbour slots: corner, edge, corner, edge...
constexpr int kRing[8] = {4, 2, 5, 1, 7, 3, 6, 0};

constexpr int kTournamentSize = 3;
constexpr double kCrossoverRate = 0.9;
// Per child, 1 or 2: most children that survive differ from a parent in one move, and more
// moves per child rarely pay.
constexpr int kMaxMutations = 2;
constexpr int kMaxSeedMutations = 8;     // per mutated copy of a seed in the first population
constexpr int kMaxPolishSweeps = 100;
constexpr int kPolishChunk = 64;  // single flips a batched model scores in one batch while polishing
constexpr int kPollElements = 256;  // elements of a polishing sweep between two polls of cancellation
constexpr uint64_t kFirstPopulation = ~uint64_t{0};  // generation index of the seeds' copies

inline double squared_excess(double x) { return x > 0.0 ? x * x : 0.0; }

// Each child draws from its own stream, so results do not depend on which thread bred it.
inline Rng child_rng(uint64_t seed, uint64_t generation, uint64_t child) {
  const uint64_t key = mix_seed(mix_seed(seed, generation), child);
  return Rng(key, mix_seed(key, 0x6E4E));
}

// ---------------------------------------------------------------------------------------------
// Validation (the only place that checks; the search trusts its input).

inline void check_state(const State& open, int elements, const char* what) {
  if (static_cast<int>(open.size()) != elements)
    throw std::invalid_argument(std::string("genetic: ") + what + " has " + std::to_string(open.size()) +
                                " values for " + std::to_string(elements) + " elements");
}

inline void check_settings(const GeneticSettings& s) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("genetic settings: " + what); };
  if (s.population < 2) fail("population must be at least 2, got " + std::to_string(s.population));
  if (s.generations < 0) fail("generations must be >= 0, got " + std::to_string(s.generations));
  if (s.elite < 1) fail("elite must be at least 1, got " + std::to_string(s.elite));
  if (!(s.time_budget_s >= 0.0)) fail("time_budget_s must be >= 0");
  for (double w : {s.shape.isolated, s.shape.boundary, s.shape.regions})
    if (!std::isfinite(w) || w < 0.0) fail("shape weights must be finite and >= 0");
}

// ---------------------------------------------------------------------------------------------
// Shape counts.

inline bool isolated(const ElementGrid& grid, const State& open, int k) {
  if (!open[k]) return false;
  for (int n : grid.neighbours(k))
    if (n != kNone && open[n]) return false;
  return true;
}

// Isolated elements among k and its N-8 neighbours: the only ones a flip of k can change.
inline int isolated_around(const ElementGrid& grid, const State& open, int k) {
  int count = isolated(grid, open, k);
  for (int n : grid.neighbours(k))
    if (n != kNone) count += isolated(grid, open, n);
  return count;
}

inline int open_edge_neighbours(const ElementGrid& grid, const State& open, int k) {
  int count = 0;
  for (int s = 0; s < kEdgeSlots; ++s) {
    const int n = grid.neighbours(k)[s];
    count += n != kNone && open[n];
  }
  return count;
}

// Change of the perimeter when k flips: its 4 edges turn between "open beside closed/missing"
// and "closed beside open".
inline int boundary_change(const ElementGrid& grid, const State& open, int k) {
  const int open_edges = open_edge_neighbours(grid, open, k);
  return open[k] ? 2 * open_edges - kEdgeSlots : kEdgeSlots - 2 * open_edges;
}

// Labels of the connected open regions (-1 on closed elements); returns their number.
inline int label_regions(const ElementGrid& grid, const State& open, std::vector<int>* labels) {
  labels->assign(open.size(), -1);
  std::vector<int> stack;
  int regions = 0;
  for (int k = 0; k < grid.size(); ++k) {
    if (!open[k] || (*labels)[k] >= 0) continue;
    (*labels)[k] = regions;
    stack.push_back(k);
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      for (int n : grid.neighbours(c))
        if (n != kNone && open[n] && (*labels)[n] < 0) {
          (*labels)[n] = regions;
          stack.push_back(n);
        }
    }
    ++regions;
  }
  return regions;
}

// Change of the region count when k flips, from the labels of the current state when the
// N-8 ring decides it. Closing k can split its region only if its open neighbours are not
// connected around k: then `exact` is false and the returned 0 is a lower bound.
inline int regions_change(const ElementGrid& grid, const State& open, const std::vector<int>& labels, int k, bool* exact) {
  const auto& nb = grid.neighbours(k);
  *exact = true;
  if (!open[k]) {
    int distinct[8], count = 0;
    for (int n : nb)
      if (n != kNone && open[n] && std::find(distinct, distinct + count, labels[n]) == distinct + count)
        distinct[count++] = labels[n];
    return 1 - count;
  }
  bool ring_open[8];
  int open_count = 0;
  for (int i = 0; i < 8; ++i) {
    const int n = nb[kRing[i]];
    ring_open[i] = n != kNone && open[n];
    open_count += ring_open[i];
  }
  if (open_count == 0) return -1;
  // Components of the open ring cells: neighbours in the ring touch, and so do two edge cells
  // either side of a corner (diagonally).
  int component[8];
  for (int i = 0; i < 8; ++i) component[i] = i;
  auto root = [&](int i) {
    while (component[i] != i) i = component[i];
    return i;
  };
  for (int i = 0; i < 8; ++i) {
    const int next = (i + 1) % 8, across = (i + 2) % 8;
    if (ring_open[i] && ring_open[next]) component[root(i)] = root(next);
    if (i % 2 == 1 && ring_open[i] && ring_open[across]) component[root(i)] = root(across);
  }
  int components = 0;
  for (int i = 0; i < 8; ++i) components += ring_open[i] && root(i) == i;
  *exact = components == 1;
  return 0;
}

// ---------------------------------------------------------------------------------------------

template <typename Response>
struct Scored {
  State open;
  Response response;  // what the error is computed from (Error::Response)
  ShapeCounts counts;
  double error = 0.0, fitness = 0.0;
  uint64_t key = 0;   // Zobrist hash of `open`, kept up to date by every flip
};

// A panel as a dense grid of element indices, for rectangular crossover.
struct PanelBlock {
  int min_row = 0, min_col = 0, rows = 0, cols = 0;
  std::vector<int> elements;  // rows x cols, row-major, kNone where the panel has no element
};

// Everything that scores and changes individuals; shared read-only by the breeding threads.
template <typename Error>
class Search {
 public:
  using Individual = Scored<typename Error::Response>;

  Search(const Error& error, const ElementGrid& grid, const ShapeWeights& shape)
      : error_(error), grid_(grid), shape_(shape) {
    closed_error_ = error.scale();
    keys_.resize(grid.size());
    for (int k = 0; k < grid.size(); ++k) keys_[k] = mix_seed(0x5A0B15F, static_cast<uint64_t>(k));
    build_panels();
  }

  Individual from_state(const State& state) const {
    Individual x;
    x.open.resize(state.size());
    for (size_t k = 0; k < state.size(); ++k) x.open[k] = state[k] != 0;
    for (size_t k = 0; k < x.open.size(); ++k)
      if (x.open[k]) x.key ^= keys_[k];
    x.response = error_.response(x.open);
    x.counts = shape_counts(grid_, x.open);
    if constexpr (!Error::kBatched) rescore(&x);  // else once settled
    return x;
  }

  // Scores a batched model's individuals in one batch (each derived from a settled base).
  template <typename Individuals>
  void settle(Individuals& xs) const {
    std::vector<typename Error::Response*> responses;
    std::vector<const State*> states;
    for (Individual* x : xs) responses.push_back(&x->response), states.push_back(&x->open);
    error_.settle(responses, states);
    tbb::parallel_for(size_t(0), xs.size(), [&](size_t i) { rescore(xs[i]); });
  }

  // Flips element j: residual, key, isolated and boundary counts follow; regions and the
  // fitness wait for rescore().
  void flip(Individual* x, int j) const {
    const int isolated_before = isolated_around(grid_, x->open, j);
    x->counts.boundary += boundary_change(grid_, x->open, j);
    error_.flip(&x->response, x->open, j);
    x->open[j] ^= 1;
    x->counts.isolated += isolated_around(grid_, x->open, j) - isolated_before;
    x->key ^= keys_[j];
  }

  void rescore(Individual* x, std::vector<int>* labels = nullptr) const {
    x->error = error_(x->response);
    if (shape_.regions > 0.0 || labels) {
      std::vector<int> scratch;
      x->counts.regions = label_regions(grid_, x->open, labels ? labels : &scratch);
    }
    x->fitness = x->error + shape_penalty(shape_, x->counts);
  }

  // Into `child`, whose storage is reused (a climate individual holds megabytes of hours).
  void breed(const Individual& a, const Individual& b, Rng& rng, Individual* child) const {
    if (rng.uniform() < kCrossoverRate) {
      take_block(a, b, rng, child);
    } else {
      *child = a;
    }
    const int mutations = 1 + uniform_int(rng, kMaxMutations);
    for (int m = 0; m < mutations; ++m) mutate(child, rng);
    if constexpr (!Error::kBatched) rescore(child);  // else once settled
  }

  Individual mutated_copy(const Individual& seed, Rng& rng) const {
    Individual x = seed;
    const int mutations = 1 + uniform_int(rng, kMaxSeedMutations);
    for (int m = 0; m < mutations; ++m) mutate(&x, rng);
    if constexpr (!Error::kBatched) rescore(&x);  // else once settled
    return x;
  }

  // Greedy local search: sweeps of single-element flips, then of flips of two N-8 neighbours
  // (an element moved to the next cell, a pair added or removed), each taken as soon as it
  // lowers the fitness, until a sweep finds none.
  void polish(Individual* x, const Progress* progress) const {
    if constexpr (Error::kBatched) polish_in_chunks(x, progress);
    else polish_one_at_a_time(x, progress);
  }

 private:
  void polish_one_at_a_time(Individual* x, const Progress* progress) const {
    std::vector<int> labels;
    rescore(x, &labels);
    for (int sweep = 0; sweep < kMaxPolishSweeps; ++sweep) {
      bool improved = false;
      for (int j = 0; j < grid_.size(); ++j) {
        if (progress && j % kPollElements == 0) progress->throw_if_cancelled();  // a sweep is O(elements^2) at worst
        if (flip_change(*x, labels, j) < -tolerance(*x)) {
          flip(x, j);
          rescore(x, &labels);
          improved = true;
        }
      }
      std::vector<int> window;
      for (int j = 0; j < grid_.size() && Error::kPairPolish; ++j) {
        if (progress && j % kPollElements == 0) progress->throw_if_cancelled();
        if (!on_edge(x->open, j)) continue;
        nearby(j, &window);
        for (int k : window)
          if (!(k < j && on_edge(x->open, k)) && try_pair(x, j, k, &labels)) improved = true;
      }
      if (!improved) break;
    }
  }

  // The single-flip sweeps of polish() for a batched model: the flips of a chunk of elements are
  // scored in one batch against the current state and walked in order; the first that lowers the
  // fitness is taken and the walk starts again after it. The same flips as one at a time.
  void polish_in_chunks(Individual* x, const Progress* progress) const {
    std::vector<int> labels, chunk;
    rescore(x, &labels);
    for (int sweep = 0; sweep < kMaxPolishSweeps; ++sweep) {
      bool improved = false;
      for (int j = 0; j < grid_.size();) {
        if (progress) progress->throw_if_cancelled();
        chunk.clear();
        for (int k = j; k < std::min(grid_.size(), j + kPolishChunk); ++k) chunk.push_back(k);
        const std::vector<double> after = error_.flip_errors(x->response, x->open, chunk);
        j = chunk.back() + 1;
        for (size_t i = 0; i < chunk.size(); ++i) {
          if (!(shape_change(*x, labels, chunk[i], after[i] - x->error) < -tolerance(*x))) continue;
          flip(x, chunk[i]);
          x->response.base = x->response.slot;  // changed in place
          std::vector<Individual*> one = {x};
          settle(one);
          rescore(x, &labels);
          improved = true;
          j = chunk[i] + 1;
          break;
        }
      }
      if (!improved) break;
    }
  }

  // An element whose state differs from one of its N-8 neighbours'.
  bool on_edge(const State& open, int j) const {
    for (int n : grid_.neighbours(j))
      if (n != kNone && open[n] != open[j]) return true;
    return false;
  }

  // The elements within two rows and columns of j (same panel), j excluded.
  void nearby(int j, std::vector<int>* cells) const {
    cells->clear();
    for (int n : grid_.neighbours(j)) {
      if (n == kNone) continue;
      for (int m : grid_.neighbours(n))
        if (m != kNone && m != j && std::find(cells->begin(), cells->end(), m) == cells->end()) cells->push_back(m);
    }
  }

  // Changes below this are rounding, not improvements (relative to the fitness and to the
  // error of the closed wall, so that an exact fit does not chase rounding noise).
  double tolerance(const Individual& x) const { return 1e-12 * (std::abs(x.fitness) + closed_error_); }

  // Flips j and k if that lowers the fitness. Their error and perimeter changes are exact and
  // cheap; only a promising pair is applied and fully rescored (regions), and undone if worse.
  bool try_pair(Individual* x, int j, int k, std::vector<int>* labels) const {
    State& open = x->open;
    double change = error_.pair_change(x->response, open, j, k);
    int around[18], count = 0;
    for (int c : {j, k}) {
      around[count++] = c;
      for (int n : grid_.neighbours(c))
        if (n != kNone && std::find(around, around + count, n) == around + count) around[count++] = n;
    }
    auto isolated_count = [&] {
      int isolated_now = 0;
      for (int i = 0; i < count; ++i) isolated_now += isolated(grid_, open, around[i]);
      return isolated_now;
    };
    const int isolated_before = isolated_count();
    int boundary = boundary_change(grid_, open, j);
    open[j] ^= 1;
    boundary += boundary_change(grid_, open, k);
    open[k] ^= 1;
    const int isolated_after = isolated_count();
    open[j] ^= 1;
    open[k] ^= 1;
    change += shape_.boundary * boundary + shape_.isolated * (isolated_after - isolated_before);
    if (change >= -tolerance(*x)) return false;
    const Individual before = *x;
    flip(x, j);
    flip(x, k);
    rescore(x, labels);
    if (x->fitness < before.fitness - tolerance(before)) return true;
    *x = before;
    rescore(x, labels);
    return false;
  }

  // Change of the fitness if j flipped, without flipping it (except to count regions when
  // the ring around j cannot tell and the rest of the change is promising).
  double flip_change(Individual& x, const std::vector<int>& labels, int j) const {
    return shape_change(x, labels, j, error_.flip_change(x.response, x.open, j));
  }

  // The fitness change of flipping j, given the error's change.
  double shape_change(Individual& x, const std::vector<int>& labels, int j, double change) const {
    change += shape_.boundary * boundary_change(grid_, x.open, j);
    const int isolated_before = isolated_around(grid_, x.open, j);
    x.open[j] ^= 1;
    change += shape_.isolated * (isolated_around(grid_, x.open, j) - isolated_before);
    x.open[j] ^= 1;
    if (shape_.regions == 0.0) return change;
    bool exact = true;
    const int regions = regions_change(grid_, x.open, labels, j, &exact);
    if (exact || change >= 0.0) return change + shape_.regions * regions;
    std::vector<int> scratch;
    x.open[j] ^= 1;
    const int regions_after = label_regions(grid_, x.open, &scratch);
    x.open[j] ^= 1;
    return change + shape_.regions * (regions_after - x.counts.regions);
  }

  // Rectangular crossover: a random block of one panel comes from `b`.
  // The child starts from whichever parent it differs from in fewer elements, so that it takes
  // the fewest flips (each costs a year of hours with climate goals).
  void take_block(const Individual& a, const Individual& b, Rng& rng, Individual* child) const {
    const PanelBlock& panel = panels_[panel_of_[uniform_int(rng, grid_.size())]];
    const int rows = 1 + uniform_int(rng, panel.rows), cols = 1 + uniform_int(rng, panel.cols);
    const int row0 = uniform_int(rng, panel.rows - rows + 1), col0 = uniform_int(rng, panel.cols - cols + 1);
    std::vector<uint8_t> in_block(a.open.size(), 0);
    int inside = 0, total = 0;
    for (int r = row0; r < row0 + rows; ++r)
      for (int c = col0; c < col0 + cols; ++c) {
        const int k = panel.elements[static_cast<size_t>(r) * panel.cols + c];
        if (k == kNone) continue;
        in_block[k] = 1;
        inside += a.open[k] != b.open[k];
      }
    for (size_t k = 0; k < a.open.size(); ++k) total += a.open[k] != b.open[k];
    const bool from_b = inside > total - inside;
    *child = from_b ? b : a;
    for (size_t k = 0; k < a.open.size(); ++k) {
      const uint8_t want = in_block[k] ? b.open[k] : a.open[k];
      if (child->open[k] != want) flip(child, static_cast<int>(k));
    }
  }

  // One of: a random flip; one element added to or removed from a region's side; a whole side
  // of a region moved out or in by one element (what turns a rectangle into a larger one).
  void mutate(Individual* x, Rng& rng) const {
    const int kind = uniform_int(rng, 3);
    if (kind > 0) {
      for (int attempt = 0; attempt < 4; ++attempt) {
        const int k = random_open(*x, rng);
        if (k == kNone) break;
        const int side = uniform_int(rng, kEdgeSlots);
        const bool grow = rng.next_u32() & 1u;
        if (move_side(x, k, side, grow, /*whole_side=*/kind == 2)) return;
      }
    }
    flip(x, uniform_int(rng, grid_.size()));
  }

  // A uniformly chosen open element, or kNone when none (after a few draws, the first open one
  // from a random start).
  int random_open(const Individual& x, Rng& rng) const {
    const int n = grid_.size();
    for (int attempt = 0; attempt < 32; ++attempt) {
      const int k = uniform_int(rng, n);
      if (x.open[k]) return k;
    }
    const int start = uniform_int(rng, n);
    for (int i = 0; i < n; ++i)
      if (x.open[(start + i) % n]) return (start + i) % n;
    return kNone;
  }

  // Moves the `side` (edge slot) of the region at open element k out (grow) or in by one: k's
  // cell alone, or the whole straight run of cells on that side through k. False when k is not
  // on that side (or, growing, the side is at the panel's edge).
  bool move_side(Individual* x, int k, int side, bool grow, bool whole_side) const {
    auto on_side = [&](int c) {
      if (c == kNone || !x->open[c]) return false;
      const int beyond = grid_.neighbours(c)[side];
      return grow ? beyond != kNone && !x->open[beyond] : beyond == kNone || !x->open[beyond];
    };
    if (!on_side(k)) return false;
    std::vector<int> run{k};
    if (whole_side)
      for (int along : kAlongSide[side])
        for (int c = grid_.neighbours(k)[along]; on_side(c); c = grid_.neighbours(c)[along]) run.push_back(c);
    for (int c : run) flip(x, grow ? grid_.neighbours(c)[side] : c);
    return true;
  }

  void build_panels() {
    panel_of_.resize(grid_.size());
    std::vector<int> ids;
    for (int k = 0; k < grid_.size(); ++k) {
      const auto& cell = grid_.cell(k);
      const auto it = std::find(ids.begin(), ids.end(), cell.panel);
      panel_of_[k] = static_cast<int>(it - ids.begin());
      if (it == ids.end()) {
        ids.push_back(cell.panel);
        panels_.push_back({cell.row, cell.col, 0, 0, {}});
      }
      PanelBlock& p = panels_[panel_of_[k]];
      p.min_row = std::min(p.min_row, cell.row);
      p.min_col = std::min(p.min_col, cell.col);
    }
    for (int k = 0; k < grid_.size(); ++k) {
      PanelBlock& p = panels_[panel_of_[k]];
      p.rows = std::max(p.rows, grid_.cell(k).row - p.min_row + 1);
      p.cols = std::max(p.cols, grid_.cell(k).col - p.min_col + 1);
    }
    for (PanelBlock& p : panels_) p.elements.assign(static_cast<size_t>(p.rows) * p.cols, kNone);
    for (int k = 0; k < grid_.size(); ++k) {
      PanelBlock& p = panels_[panel_of_[k]];
      const auto& cell = grid_.cell(k);
      p.elements[static_cast<size_t>(cell.row - p.min_row) * p.cols + (cell.col - p.min_col)] = k;
    }
  }

  const Error& error_;
  const ElementGrid& grid_;
  ShapeWeights shape_;
  double closed_error_ = 0.0;  // the error with every element closed
  std::vector<uint64_t> keys_;
  std::vector<PanelBlock> panels_;
  std::vector<int> panel_of_;
};

// The best distinct states seen so far, best first.
class DistinctBest {
 public:
  explicit DistinctBest(int capacity) : capacity_(static_cast<size_t>(capacity)) {}

  template <typename Individual>
  void offer(const Individual& x) {
    if (entries_.size() == capacity_ && !(x.fitness < entries_.back().fitness)) return;
    // The same state reached along another lineage may score a rounding error lower: keep that.
    for (auto e = entries_.begin(); e != entries_.end(); ++e)
      if (e->key == x.key && e->open == x.open) {
        if (!(x.fitness < e->fitness)) return;
        entries_.erase(e);
        break;
      }
    const auto at = std::upper_bound(entries_.begin(), entries_.end(), x.fitness,
                                     [](double f, const Entry& e) { return f < e.fitness; });
    entries_.insert(at, Entry{x.fitness, x.key, x.open});
    if (entries_.size() > capacity_) entries_.pop_back();
  }

  void fill(GeneticResult* result) const {
    result->best = entries_.front().open;
    result->best_fitness = entries_.front().fitness;
    result->elite.clear();
    for (const Entry& e : entries_) result->elite.push_back(e.open);
  }

 private:
  struct Entry {
    double fitness;
    uint64_t key;
    State open;
  };
  size_t capacity_;
  std::vector<Entry> entries_;
};

template <typename Individual>
void sort_by_fitness(std::vector<Individual>* population) {
  std::stable_sort(population->begin(), population->end(),
                   [](const Individual& a, const Individual& b) { return a.fitness < b.fitness; });
}

template <typename Individual>
bool same_state(const Individual& a, const Individual& b) { return a.key == b.key && a.open == b.open; }

// (mu + lambda) selection: the best distinct states among parents and children, sorted. Elitism
// in full, so the best fitness never rises, while copies of one state cannot crowd out the rest.
template <typename Individual>
// The others go back to `children`, to be bred into again.
std::vector<Individual> survivors(std::vector<Individual> parents, std::vector<Individual>* children, int size) {
  for (Individual& x : *children) parents.push_back(std::move(x));
  children->clear();
  sort_by_fitness(&parents);
  std::vector<Individual> kept, copies;
  kept.reserve(size);
  for (Individual& x : parents) {
    if (static_cast<int>(kept.size()) == size) {
      children->push_back(std::move(x));
      continue;
    }
    const bool copy = std::any_of(kept.begin(), kept.end(), [&](const Individual& y) { return same_state(x, y); });
    (copy ? copies : kept).push_back(std::move(x));
  }
  // Fewer distinct states than places (a tiny grid): fill up with copies, still in order.
  size_t i = 0;
  for (; static_cast<int>(kept.size()) < size; ++i) kept.push_back(std::move(copies[i]));
  for (; i < copies.size(); ++i) children->push_back(std::move(copies[i]));
  return kept;
}

// The population is sorted, so the best of a few random picks is the smallest index.
inline int tournament(int population, Rng& rng) {
  int best = uniform_int(rng, population);
  for (int i = 1; i < kTournamentSize; ++i) best = std::min(best, uniform_int(rng, population));
  return best;
}

template <typename Individual>
GenerationRecord record(int generation, const std::vector<Individual>& population, double seconds) {
  double sum = 0.0;
  for (const Individual& x : population) sum += x.fitness;
  return {generation, population.front().fitness, sum / static_cast<double>(population.size()), seconds};
}


// A long run keeps at most kMaxHistory records, evenly spread: when full, every other record goes
// and the stride between recorded generations doubles (a 10^7-generation run would otherwise
// write gigabytes of history).
inline void thin_history(std::vector<GenerationRecord>* history, int* stride) {
  if (history->size() < kMaxHistory) return;
  size_t kept = 0;
  for (size_t i = 0; i < history->size(); i += 2) (*history)[kept++] = (*history)[i];
  history->resize(kept);
  *stride *= 2;
}

// The genetic algorithm with any error model (see ResidualError in genetic.cpp for the interface).
template <typename Error>
GeneticResult run_search(const Error& error, const ElementGrid& grid, const std::vector<std::vector<uint8_t>>& seeds,
                         const GeneticSettings& settings, Progress* progress) {
  if (grid.size() == 0) throw std::invalid_argument("genetic: the element grid is empty");
  check_settings(settings);
  if (seeds.empty()) throw std::invalid_argument("genetic: at least one seed state is needed");
  for (const State& s : seeds) check_state(s, grid.size(), "a seed");

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  using Individual = typename Search<Error>::Individual;
  const Search<Error> search(error, grid, settings.shape);
  const int size = settings.population;
  const int seeded = std::min<int>(size, static_cast<int>(seeds.size()));
  std::vector<Individual> population(size);
  for (int i = 0; i < seeded; ++i) population[i] = search.from_state(seeds[i]);
  if constexpr (Error::kBatched)
    for (int i = 0; i < seeded; ++i) population[i].response.slot = i;  // from the model's state
  tbb::parallel_for(seeded, size, [&](int i) {
    Rng rng = child_rng(settings.seed, kFirstPopulation, static_cast<uint64_t>(i));
    population[i] = search.mutated_copy(population[i % seeded], rng);
  });
  // A batched model's slots: the population's, then the children's (each keeps its own as the
  // survivors move between the two), and the polished individual's.
  [[maybe_unused]] auto derive = [](Individual* x, [[maybe_unused]] int slot) {
    if constexpr (Error::kBatched) x->response.base = x->response.slot, x->response.slot = slot;
  };
  if constexpr (Error::kBatched) {
    std::vector<Individual*> all;
    for (int i = 0; i < size; ++i) {
      if (i >= seeded) derive(&population[i], i);  // from its seed's slot, settled before it
      all.push_back(&population[i]);
    }
    search.settle(all);
  }
  sort_by_fitness(&population);
  DistinctBest best(settings.elite);
  for (const Individual& x : population) best.offer(x);

  GeneticResult result;
  int history_stride = 1;
  if (progress) progress->start("genetic algorithm", static_cast<uint64_t>(settings.generations));
  std::vector<Individual> children(size);
  if constexpr (Error::kBatched)
    for (int i = 0; i < size; ++i) children[i].response.slot = size + i;
  for (int g = 0; g < settings.generations; ++g) {
    if (progress) progress->throw_if_cancelled();
    if (settings.time_budget_s > 0.0 && seconds() >= settings.time_budget_s) {
      result.out_of_time = true;
      break;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, size), [&](const tbb::blocked_range<int>& range) {
      for (int i = range.begin(); i < range.end(); ++i) {
        Rng rng = child_rng(settings.seed, static_cast<uint64_t>(g), static_cast<uint64_t>(i));
        const Individual& a = population[tournament(size, rng)];
        const Individual& b = population[tournament(size, rng)];
        int slot = 0;
        if constexpr (Error::kBatched) slot = children[i].response.slot;
        search.breed(a, b, rng, &children[i]);
        derive(&children[i], slot);  // from the parent it copied
      }
    });
    if constexpr (Error::kBatched) {
      std::vector<Individual*> bred;
      for (Individual& x : children) bred.push_back(&x);
      search.settle(bred);
    }
    population = survivors(std::move(population), &children, size);
    for (const Individual& x : population) best.offer(x);
    if (g % history_stride == 0 || g + 1 == settings.generations) {
      result.history.push_back(record(g, population, seconds()));
      thin_history(&result.history, &history_stride);
    }
    result.generations = g + 1;
    if (progress) progress->advance();
  }

  if (settings.polish) {
    Individual polished = population.front();
    derive(&polished, 2 * size);  // its own slot: the population's best stays as it is
    if constexpr (Error::kBatched) {
      std::vector<Individual*> one = {&polished};
      search.settle(one);
    }
    search.polish(&polished, progress);
    best.offer(polished);
  }
  best.fill(&result);
  return result;
}

}  // namespace genetic_search
}  // namespace fenestra
