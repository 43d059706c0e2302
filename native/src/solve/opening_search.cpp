#include "solve/opening_search.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "util/progress.h"

namespace fenestra {
namespace {

using Openings = std::vector<GridRectangle>;

// A move smaller than this share of the score is no gain (rounding, not light).
constexpr double kRelativeGain = 1e-9;
// Restarts per round that descend: the kicks that score best once kicked (and fitted).
constexpr size_t kRestartDescents = 4;
// Pair moves per round scored: those the screen ranks best.
constexpr size_t kPairScores = 8;

GridRectangle holding_both(const GridRectangle& a, const GridRectangle& b) {
  return {a.panel, std::min(a.row0, b.row0), std::max(a.row1, b.row1), std::min(a.col0, b.col0),
          std::max(a.col1, b.col1)};
}

bool all_well_formed(const Openings& set) {
  return std::all_of(set.begin(), set.end(), [](const GridRectangle& r) { return r.well_formed(); });
}

Openings replaced(const Openings& set, size_t i, const GridRectangle& r) {
  Openings out = set;
  out[i] = r;
  return out;
}

Openings without(const Openings& set, size_t i) {
  Openings out = set;
  out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
  return out;
}

// Opening i changed alone: moved, a side or both sides of an axis out or in, width traded for
// height (its place in the set kept).
void moves_of_one_opening(const Openings& set, size_t i, std::vector<Openings>* out) {
  const GridRectangle& r = set[i];
  for (auto [dr, dc] : {std::pair{0, -1}, {0, 1}, {-1, 0}, {1, 0}}) out->push_back(replaced(set, i, r.moved(dr, dc)));
  for (int side = 0; side < 4; ++side)
    for (int step : {1, -1}) out->push_back(replaced(set, i, r.side_moved(side, step)));
  for (int first_side : {0, 2})  // both sides of an axis out or in: wider or narrower about its centre
    for (int step : {1, -1}) out->push_back(replaced(set, i, r.side_moved(first_side, step).side_moved(first_side + 1, step)));
  for (int grow = 0; grow < 4; ++grow)
    for (int shrink = grow < 2 ? 2 : 0; shrink < (grow < 2 ? 4 : 2); ++shrink)
      out->push_back(replaced(set, i, r.side_moved(grow, 1).side_moved(shrink, -1)));
}

// Opening i with each of its sides moved by at most one element, all at once (81 rectangles).
void box_moves_of_one_opening(const Openings& set, size_t i, std::vector<Openings>* out) {
  const GridRectangle& r = set[i];
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c)
        for (int d = -1; d <= 1; ++d)
          if (a || b || c || d) out->push_back(replaced(set, i, {r.panel, r.row0 + a, r.row1 + b, r.col0 + c, r.col1 + d}));
}

// Each opening removed, or changed alone.
void single_opening_moves(const Openings& set, std::vector<Openings>* out) {
  for (size_t i = 0; i < set.size(); ++i) {
    moves_of_one_opening(set, i, out);
    out->push_back(without(set, i));
  }
}

// Two openings of a panel merged.
void merges(const Openings& set, std::vector<Openings>* out) {
  for (size_t i = 0; i < set.size(); ++i)
    for (size_t j = i + 1; j < set.size(); ++j)
      if (set[i].panel == set[j].panel) {
        Openings merged = without(set, j);
        merged[i] = holding_both(set[i], set[j]);
        out->push_back(std::move(merged));
      }
}

class Search {
 public:
  Search(const OpeningDomain& domain, const OpeningConstraints& constraints, const OpeningScore& score,
         const OpeningBound& bound, int max_evaluations, Progress* progress)
      : domain_(domain), constraints_(constraints), score_(score), bound_(bound), max_evaluations_(max_evaluations),
        progress_(progress) {}

  // The score of an admissible set (sorted), once per set; nullopt when it breaks the constraints,
  // the evaluations ran out, or (with a bound) it cannot be below `beat`.
  std::optional<double> scored(Openings set, double beat = std::numeric_limits<double>::infinity()) {
    std::sort(set.begin(), set.end());
    auto known = known_.find(set);
    if (known == known_.end()) {
      if (!all_well_formed(set) || !satisfies_all(domain_, set, constraints_))
        return known_.emplace(std::move(set), Judged{}).first->second.score;
      if (max_evaluations_ > 0 && result.evaluations >= max_evaluations_) {
        result.out_of_evaluations = true;
        return std::nullopt;
      }
      if (progress_) progress_->throw_if_cancelled();
      Judged judged;
      judged.admissible = true;
      if (bound_ && beat < std::numeric_limits<double>::infinity()) judged.bound = bound_(set);
      ++result.evaluations;
      if (progress_) progress_->advance();
      known = known_.emplace(std::move(set), judged).first;
    }
    Judged& j = known->second;
    if (!j.admissible || j.score) return j.score;
    if (j.bound >= beat) return std::nullopt;  // it cannot win here
    if (progress_) progress_->throw_if_cancelled();
    j.score = score_(known->first);
    ++result.scored;
    return j.score;
  }

  // Descent from `set` (admissible, scored `s`): the first neighbour that gains is taken and the
  // scan goes on from the next one (round the openings, so that no one opening takes every move),
  // until a whole scan gains nothing; a move costs a few scores rather than all its neighbours'.
  // With `only` >= 0, over the moves of that opening alone, never removing it (an opening just
  // added finds its place and size before the others may move or take it away).
  std::pair<Openings, double> descend(Openings set, double s, int only = -1) {
    size_t next = 0;
    while (!result.out_of_evaluations) {
      std::vector<Openings> candidates;
      if (only >= 0) {
        moves_of_one_opening(set, static_cast<size_t>(only), &candidates);
      } else {
        single_opening_moves(set, &candidates);
        merges(set, &candidates);
      }
      bool gained = false;
      for (size_t t = 0; t < candidates.size() && !gained; ++t) {
        const size_t k = (next + t) % candidates.size();
        const double beat = s - kRelativeGain * std::abs(s);
        const std::optional<double> cs = scored(candidates[k], beat);
        if (!cs || !(*cs < beat)) continue;
        set = std::move(candidates[k]), s = *cs, next = k + 1, gained = true;
        if (only < 0) std::sort(set.begin(), set.end());
        ++result.moves;
      }
      if (!gained) break;
    }
    return {std::move(set), s};
  }

  void take(const Openings& set, double s, int start) {
    ends.emplace(s, set);
    if (s < result.score) {
      result.rects = set, result.score = s, result.best_found_after = result.evaluations;
      if (start >= 0) result.best_start = start;
    }
  }

  // The best, each opening in turn refitted with every side moved by at most one element at once
  // (what single moves cannot reach through worse sets), then descent. Whether it gained.
  bool refit_round() {
    const double before = result.score;
    for (size_t i = 0; i < result.rects.size() && !result.out_of_evaluations; ++i) {
      std::vector<Openings> candidates;
      box_moves_of_one_opening(result.rects, i, &candidates);
      std::optional<Openings> best;
      double best_score = result.score;
      for (Openings& c : candidates) {
        const std::optional<double> cs = scored(c, best_score);
        if (cs && *cs < best_score) best_score = *cs, best = std::move(c);
      }
      if (!best || !(best_score < result.score - kRelativeGain * std::abs(result.score))) continue;
      std::sort(best->begin(), best->end());
      auto [set, score] = descend(std::move(*best), best_score);
      take(set, score, -1);
      i = static_cast<size_t>(-1);  // the openings changed: from the first again
    }
    return result.score < before - kRelativeGain * std::abs(before);
  }

  // Pair moves of the best, ranked by the screen; the best few scored, descent from the first
  // that gains. Whether it gained.
  bool pair_round(const OpeningScreen& screen) {
    const Openings best = result.rects;
    const double before = result.score;
    std::vector<Openings> fresh;  // both moves at once: admissible, not scored yet, once each
    std::vector<std::array<Openings, 2>> singles;  // each move alone
    std::set<Openings> seen;
    for (size_t i = 0; i < best.size(); ++i)
      for (size_t j = i + 1; j < best.size(); ++j) {
        std::vector<Openings> moves_i, moves_j;
        moves_of_one_opening(best, i, &moves_i);
        moves_of_one_opening(best, j, &moves_j);
        for (const Openings& a : moves_i)
          for (const Openings& b : moves_j) {
            Openings both = a;
            both[j] = b[j];
            std::sort(both.begin(), both.end());
            if (known_.count(both) || !seen.insert(both).second || !all_well_formed(both) ||
                !satisfies_all(domain_, both, constraints_))
              continue;
            fresh.push_back(std::move(both));
            singles.push_back({a, b});
          }
      }
    if (fresh.empty()) return false;
    const std::vector<double> predicted = screen(best, singles);
    std::vector<size_t> order(fresh.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return predicted[a] < predicted[b]; });
    for (size_t n = 0; n < order.size() && n < kPairScores && !result.out_of_evaluations; ++n) {
      Openings& c = fresh[order[n]];
      const double beat = before - kRelativeGain * std::abs(before);
      const std::optional<double> s = scored(c, beat);
      if (!s || !(*s < beat)) continue;
      ++result.pair_moves;
      auto [set, score] = descend(std::move(c), *s);
      take(set, score, -1);
      break;
    }
    return result.score < before - kRelativeGain * std::abs(before);
  }

  // Restarts from the best: each opening removed, or moved by two elements; each opening of the
  // pool added (fitted alone first), or put in place of one on its panel. Then descent.
  bool restart_round() {
    const Openings best = result.rects;
    const double before = result.score;
    std::vector<std::pair<Openings, int>> kicks;  // and the opening to fit first (-1: none)
    for (size_t i = 0; i < best.size(); ++i) {
      kicks.push_back({without(best, i), -1});
      for (auto [dr, dc] : {std::pair{0, -2}, {0, 2}, {-2, 0}, {2, 0}})
        kicks.push_back({replaced(best, i, best[i].moved(dr, dc)), -1});
    }
    for (const GridRectangle& p : pool) {
      if (std::find(best.begin(), best.end(), p) != best.end()) continue;
      Openings added = best;
      added.push_back(p);
      kicks.push_back({std::move(added), static_cast<int>(best.size())});
      for (size_t i = 0; i < best.size(); ++i)
        if (best[i].panel == p.panel) kicks.push_back({replaced(best, i, p), static_cast<int>(i)});
    }
    // Each kick scored (an added opening fitted first); descent from the most promising only.
    std::vector<std::pair<double, Openings>> kicked;
    for (auto& [k, fit_first] : kicks) {
      if (result.out_of_evaluations) break;
      std::optional<double> s = scored(k);
      if (!s) continue;
      if (fit_first >= 0) std::tie(k, *s) = descend(std::move(k), *s, fit_first);
      std::sort(k.begin(), k.end());
      kicked.push_back({*s, std::move(k)});
    }
    std::stable_sort(kicked.begin(), kicked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    if (kicked.size() > kRestartDescents) kicked.resize(kRestartDescents);
    for (auto& [s, k] : kicked) {
      if (result.out_of_evaluations) break;
      ++result.restarts;
      auto [set, score] = descend(std::move(k), s);
      take(set, score, -1);
    }
    return result.score < before - kRelativeGain * std::abs(before);
  }

  Openings pool;
  OpeningSearchResult result;
  std::multimap<double, Openings> ends;  // where each descent ended, by score

 private:
  const OpeningDomain& domain_;
  const OpeningConstraints& constraints_;
  // What is known of a set considered: whether it is admissible, its bound, its score once scored.
  struct Judged {
    bool admissible = false;
    double bound = -std::numeric_limits<double>::infinity();
    std::optional<double> score;
  };

  const OpeningScore& score_;
  const OpeningBound& bound_;
  const int max_evaluations_;
  Progress* progress_;
  std::map<Openings, Judged> known_;
};

}  // namespace

OpeningSearchResult search_whole_openings(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                          const std::vector<std::vector<GridRectangle>>& starts,
                                          const OpeningScore& score, int max_evaluations, Progress* progress,
                                          const OpeningScreen& screen, const OpeningBound& bound) {
  Search search(domain, constraints, score, bound, max_evaluations, progress);
  for (const Openings& start : starts)
    for (const GridRectangle& r : start)
      if (std::find(search.pool.begin(), search.pool.end(), r) == search.pool.end()) search.pool.push_back(r);
  std::sort(search.pool.begin(), search.pool.end());
  // Descent from the best start first (the evaluations may run out).
  std::vector<std::pair<double, size_t>> order;
  for (size_t k = 0; k < starts.size(); ++k)
    if (const std::optional<double> s = search.scored(starts[k])) order.push_back({*s, k});
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [start_score, k] : order) {
    const std::optional<double> s = start_score;
    if (*s < search.result.start_score) search.result.start_score = *s;
    Openings sorted = starts[k];
    std::sort(sorted.begin(), sorted.end());
    auto [set, descended] = search.descend(std::move(sorted), *s);
    search.take(set, descended, static_cast<int>(k));
  }
  // Restarts, refits and pair moves, while any gains.
  while (search.result.best_start >= 0 && !search.result.out_of_evaluations) {
    const bool restarts_gained = search.restart_round();
    const bool refits_gained = search.refit_round();
    const bool pairs_gained = screen && !search.result.out_of_evaluations && search.pair_round(screen);
    if (!restarts_gained && !refits_gained && !pairs_gained) break;
  }
  for (const auto& [s, set] : search.ends) {
    if (search.result.alternatives.size() >= kSearchAlternatives) break;
    const auto& alt = search.result.alternatives;
    if (set != search.result.rects && std::find(alt.begin(), alt.end(), set) == alt.end())
      search.result.alternatives.push_back(set);
  }
  return std::move(search.result);
}

}  // namespace fenestra
