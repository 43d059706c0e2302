#include "solve/composition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "solve/edge_refinement.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr double kSame = 1e-3;         // meters: two sills, heads, widths or piers are equal
constexpr double kRowTolerance = 0.01;  // meters: openings whose sills are this close form a row
constexpr double kTuneStep = 0.02;      // meters: the finest step of the search after the rules

using Openings = std::vector<PanelRectangle>;

std::string meters(double x) {
  std::ostringstream s;
  s << std::round(x * 1000.0) / 1000.0 << " m";
  return s.str();
}

// Heights of a wall opening's edges: world z of panel coordinate v, and back.
class WallHeights {
 public:
  WallHeights(const OpeningDomain& domain, const OpeningConstraints& c) : domain_(domain), c_(c) {}

  double base(int panel) const {
    return wall_heights(domain_.panels()[static_cast<size_t>(panel)], panel, c_, domain_.element_size()).base;
  }
  double z(int panel, double v) const {
    const Panel& p = domain_.panels()[static_cast<size_t>(panel)];
    return p.origin.z() + v * p.v_axis.z();
  }
  // Sill and head above the wall's base.
  double sill(const PanelRectangle& r) const { return std::min(z(r.panel, r.v0), z(r.panel, r.v1)) - base(r.panel); }
  double head(const PanelRectangle& r) const { return std::max(z(r.panel, r.v0), z(r.panel, r.v1)) - base(r.panel); }
  // r moved up or down so that its sill is at `sill`, or with its head at `head` (`keep_sill`:
  // resized, else moved).
  PanelRectangle with_sill(PanelRectangle r, double sill) const { return shifted(r, sill - this->sill(r)); }
  PanelRectangle with_head(PanelRectangle r, double head, bool keep_sill) const {
    const double dz = head - this->head(r);
    if (!keep_sill) return shifted(r, dz);
    const double vz = domain_.panels()[static_cast<size_t>(r.panel)].v_axis.z();
    (vz > 0.0 ? r.v1 : r.v0) += dz / vz;  // the edge that is the head
    return r;
  }

 private:
  PanelRectangle shifted(PanelRectangle r, double dz) const {
    const double dv = dz / domain_.panels()[static_cast<size_t>(r.panel)].v_axis.z();
    r.v0 += dv, r.v1 += dv;
    return r;
  }
  const OpeningDomain& domain_;
  const OpeningConstraints& c_;
};

bool near(double a, double b) { return std::abs(a - b) <= kSame; }

// Distinct values, in order of first appearance.
std::vector<double> distinct(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values)
    if (std::none_of(out.begin(), out.end(), [&](double o) { return near(o, v); })) out.push_back(v);
  return out;
}

class Composer {
 public:
  Composer(const OpeningDomain& domain, const OpeningConstraints& c, Openings openings,
           const std::function<double(const Openings&)>& error_of, Progress* progress)
      : domain_(domain), c_(c), heights_(domain, c), facade_(facades_of(domain)), openings_(std::move(openings)),
        error_of_(error_of), progress_(progress) {
    error_ = error_of_(openings_);
  }

  Composition run() {
    const OpeningConstraints& rules = rules_of_first();
    if (!rules.sill_heights.empty() || rules.align_sills)
      step(rules.align_sills ? "align_sills" : "sill_heights", [&] { sill_candidates(); });
    if (rules.align_heads) step("align_heads", [&] { head_candidates(); });
    if (rules.equal_widths) step("equal_widths", [&] { width_candidates(); });
    if (rules.same_type_in_row) step("same_type_in_row", [&] { type_candidates(); });
    if (rules.symmetric) step("symmetric", [&] { symmetric_candidates(); });
    if (rules.equal_spacing) step("equal_spacing", [&] { spacing_candidates(); });
    return {openings_, steps_};
  }

 private:
  // The rules of the facades: those of the first panel that is part of one.
  const OpeningConstraints& rules_of_first() const {
    for (size_t p = 0; p < facade_.size(); ++p)
      if (facade_[p] >= 0 && c_.for_panel(static_cast<int>(p)).composes()) return c_.for_panel(static_cast<int>(p));
    return c_;
  }
  int facade(const PanelRectangle& r) const { return facade_[static_cast<size_t>(r.panel)]; }
  std::vector<int> facades_with_openings() const {
    std::vector<int> out;
    for (const PanelRectangle& r : openings_)
      if (facade(r) >= 0 && std::count(out.begin(), out.end(), facade(r)) == 0) out.push_back(facade(r));
    return out;
  }

  // Applies one rule (facade by facade, keep_best), lets the openings recover what they can under
  // the rules so far (tune), and records what the rule cost.
  template <typename Apply>
  void step(const std::string& rule, Apply apply) {
    const bool automatic = c_.automatic_alignment && (rule == "align_sills" || rule == "align_heads");
    if (automatic && !a_facade_has_two_openings()) return;  // nothing to line up
    const Openings before = openings_;
    CompositionStep s;
    s.rule = rule;
    s.automatic = automatic;
    s.error_before = error_;
    met_all_ = true;
    apply();
    applied_.push_back(rule);
    if (met_all_) tune();
    s.met = met_all_;
    s.error_after = error_;
    if (automatic && (!s.met || s.error_after > s.error_before + kAutomaticAlignmentCost)) {
      s.kept = false;  // too dear: the openings as they were
      openings_ = before;
      error_ = s.error_before;
      applied_.pop_back();
    }
    steps_.push_back(s);
  }

  bool a_facade_has_two_openings() const {
    std::map<int, int> count;
    for (const PanelRectangle& r : openings_)
      if (facade(r) >= 0 && ++count[facade(r)] >= 2) return true;
    return false;
  }

  // The constraints with only the rules applied so far (what tune must keep).
  OpeningConstraints rules_so_far() const {
    auto only = [&](OpeningConstraints set) {
      auto on = [&](const char* rule) { return std::count(applied_.begin(), applied_.end(), rule) > 0; };
      set.align_sills = set.align_sills && on("align_sills");
      if (!on("align_sills") && !on("sill_heights")) set.sill_heights.clear();
      set.align_heads = set.align_heads && on("align_heads");
      set.equal_widths = set.equal_widths && on("equal_widths");
      set.same_type_in_row = set.same_type_in_row && on("same_type_in_row");
      set.symmetric = set.symmetric && on("symmetric");
      set.equal_spacing = set.equal_spacing && on("equal_spacing");
      return set;
    };
    OpeningConstraints out = only(c_);
    for (OpeningConstraints& set : out.per_panel) set = only(set);
    return out;
  }

  // Keeps the best valid candidate of one facade's (or opening's) alternatives; returns whether one was.
  bool keep_best(const std::vector<Openings>& alternatives) {
    double best = std::numeric_limits<double>::infinity();
    const Openings* chosen = nullptr;
    for (const Openings& a : alternatives) {
      if (progress_) progress_->throw_if_cancelled();
      if (!constraint_violations(domain_, a, c_).empty()) continue;
      const double e = error_of_(a);
      if (e < best) best = e, chosen = &a;
    }
    if (!chosen) {
      met_all_ = false;
      return false;
    }
    openings_ = *chosen;
    error_ = best;
    return true;
  }

  // The rules: each offers its alternatives to keep_best, facade by facade (or row, or panel).
  void sill_candidates() {
    const OpeningConstraints& rules = rules_of_first();
    if (!rules.align_sills) {  // each opening on one of the heights
      for (size_t i = 0; i < openings_.size();) {
        if (facade(openings_[i]) < 0) {
          ++i;
          continue;
        }
        std::vector<Openings> alternatives;
        for (double h : rules.sill_heights) {
          Openings a = openings_;
          a[i] = heights_.with_sill(a[i], h);
          alternatives.push_back(a);
        }
        const bool met_before = met_all_;
        if (keep_best(alternatives)) {
          ++i;
          continue;
        }
        // On none of the heights without meeting another opening (one stacked above another): the
        // rule is kept by giving that opening up, when the rest still hold.
        Openings without = openings_;
        without.erase(without.begin() + static_cast<std::ptrdiff_t>(i));
        if (!without.empty() && keep_best({without})) {
          met_all_ = met_before;
          continue;
        }
        ++i;
      }
      return;
    }
    common_per_facade([this](const PanelRectangle& r) { return heights_.sill(r); },
                      [this](const PanelRectangle& r, double h) { return heights_.with_sill(r, h); },
                      rules.sill_heights, false);
  }

  void head_candidates() {
    const OpeningConstraints& rules = rules_of_first();
    const bool keep_sill = rules.align_sills || !rules.sill_heights.empty();
    common_per_facade([this](const PanelRectangle& r) { return heights_.head(r); },
                      [this, keep_sill](const PanelRectangle& r, double h) { return heights_.with_head(r, h, keep_sill); },
                      {}, false);
  }

  // One value per facade: each distinct `value` of its openings (or each of `given`, when there
  // are any; and their mean, with `and_mean`) made the common one by `with`; the best kept.
  using Value = std::function<double(const PanelRectangle&)>;
  using WithValue = std::function<PanelRectangle(const PanelRectangle&, double)>;
  void common_per_facade(const Value& value, const WithValue& with, const std::vector<double>& given, bool and_mean) {
    for (int f : facades_with_openings()) {
      std::vector<double> values = given;
      if (values.empty())
        for (const PanelRectangle& r : openings_)
          if (facade(r) == f) values.push_back(value(r));
      if (and_mean) {
        double mean = 0.0;
        for (double v : values) mean += v / static_cast<double>(values.size());
        values.push_back(mean);
      }
      const bool met_before = met_all_;
      if (!keep_best(aligned(openings_, f, values, with))) fewer_aligned(f, value, with, given, and_mean, met_before);
    }
  }

  // `from` with facade f's openings given each of `values` in turn (distinct ones).
  std::vector<Openings> aligned(const Openings& from, int f, const std::vector<double>& values,
                                const WithValue& with) const {
    std::vector<Openings> out;
    for (double v : distinct(values)) {
      Openings a = from;
      for (PanelRectangle& r : a)
        if (facade(r) == f) r = with(r, v);
      out.push_back(a);
    }
    return out;
  }

  // No common value suits all of facade f's openings (one stacked above another cannot share its
  // sill): the rule is kept by giving up openings, one at a time, the one whose loss lets the rest
  // align best, until the rest align (the rule's cost is reported as every rule's is).
  void fewer_aligned(int f, const Value& value, const WithValue& with, const std::vector<double>& given,
                     bool and_mean, bool met_before) {
    Openings kept = openings_;
    while (std::count_if(kept.begin(), kept.end(), [&](const PanelRectangle& r) { return facade(r) == f; }) > 1) {
      std::vector<Openings> alternatives;
      for (size_t i = 0; i < kept.size(); ++i) {
        if (facade(kept[i]) != f) continue;
        Openings without = kept;
        without.erase(without.begin() + static_cast<std::ptrdiff_t>(i));
        std::vector<double> values = given;
        if (values.empty())
          for (const PanelRectangle& r : without)
            if (facade(r) == f) values.push_back(value(r));
        if (and_mean && !values.empty()) {
          double mean = 0.0;
          for (double v : values) mean += v / static_cast<double>(values.size());
          values.push_back(mean);
        }
        for (Openings& a : aligned(without, f, values, with)) alternatives.push_back(std::move(a));
      }
      if (keep_best(alternatives)) {
        met_all_ = met_before;
        return;
      }
      // None aligns yet: drop the opening whose loss costs least, and try again.
      double best = std::numeric_limits<double>::infinity();
      Openings next;
      for (size_t i = 0; i < kept.size(); ++i) {
        if (facade(kept[i]) != f) continue;
        Openings without = kept;
        without.erase(without.begin() + static_cast<std::ptrdiff_t>(i));
        const double e = error_of_(without);
        if (e < best) best = e, next = std::move(without);
      }
      kept = std::move(next);
    }
  }

  // r with width w about its centre, slid back inside its panel's grid (less the margin) when that
  // pushes it out.
  PanelRectangle with_width(PanelRectangle r, double w) const {
    const double centre = 0.5 * (r.u0 + r.u1);
    r.u0 = centre - 0.5 * w, r.u1 = centre + 0.5 * w;
    const Panel& panel = domain_.panels()[static_cast<size_t>(r.panel)];
    const double margin = c_.for_panel(r.panel).margin;
    const double lo = panel.u_lines.front() + margin, hi = panel.u_lines.back() - margin;
    if (r.u0 < lo) r.u1 += lo - r.u0, r.u0 = lo;
    if (r.u1 > hi) r.u0 -= r.u1 - hi, r.u1 = hi;
    return r;
  }

  void width_candidates() {
    common_per_facade([](const PanelRectangle& r) { return r.width(); },
                      [this](const PanelRectangle& r, double w) { return with_width(r, w); }, {}, true);
  }

  // The rules fix relations, not positions: a local search over moves that keep them (a facade's
  // sills, heads or widths all together, an opening sliding along its wall where neither symmetry
  // nor spacing holds it, a mirrored pair sliding apart), in halving steps from half an element to
  // kTuneStep, lets the openings recover the light the rules cost.
  void tune() {
    const OpeningConstraints kept = rules_so_far();
    const OpeningConstraints& rules = kept.for_panel(openings_.front().panel);
    const bool keep_sill = rules.align_sills || !rules.sill_heights.empty();
    const bool slide = !rules.symmetric && !rules.equal_spacing;
    std::vector<std::function<Openings(double)>> moves;
    for (int f : facades_with_openings()) {
      auto each = [this, f](std::function<PanelRectangle(const PanelRectangle&, double)> change) {
        return [this, f, change](double d) {
          Openings a = openings_;
          for (PanelRectangle& r : a)
            if (facade(r) == f) r = change(r, d);
          return a;
        };
      };
      if (!keep_sill) moves.push_back(each([this](const PanelRectangle& r, double d) { return heights_.with_sill(r, heights_.sill(r) + d); }));
      moves.push_back(each([this, keep_sill](const PanelRectangle& r, double d) {
        return heights_.with_head(r, heights_.head(r) + d, keep_sill);
      }));
      moves.push_back(each([this](const PanelRectangle& r, double d) { return with_width(r, r.width() + d); }));
    }
    for (size_t i = 0; i < openings_.size() && slide; ++i)
      moves.push_back([this, i](double d) {
        Openings a = openings_;
        a[i].u0 += d, a[i].u1 += d;
        return a;
      });
    const double s = domain_.element_size();
    for (double step = 0.5 * s; step >= kTuneStep * (1.0 - 1e-9); step *= 0.5) {
      for (bool improved = true; improved;) {
        improved = false;
        for (const auto& move : moves)
          for (double d : {step, -step}) {
            if (progress_) progress_->throw_if_cancelled();
            const Openings a = move(d);
            if (!constraint_violations(domain_, a, c_).empty() || !composition_violations(domain_, kept, a).empty()) continue;
            const double e = error_of_(a);
            if (e < error_ * (1.0 - 1e-6)) openings_ = a, error_ = e, improved = true;
          }
      }
    }
  }

  // Rows: the openings of a facade with one sill (kRowTolerance), as indices.
  std::vector<std::vector<size_t>> rows() const {
    std::vector<std::vector<size_t>> out;
    std::vector<std::pair<int, double>> keys;
    for (size_t i = 0; i < openings_.size(); ++i) {
      const int f = facade(openings_[i]);
      if (f < 0) continue;
      const double sill = heights_.sill(openings_[i]);
      size_t k = 0;
      while (k < keys.size() && !(keys[k].first == f && std::abs(keys[k].second - sill) <= kRowTolerance)) ++k;
      if (k == keys.size()) keys.push_back({f, sill}), out.emplace_back();
      out[k].push_back(i);
    }
    return out;
  }

  void type_candidates() {
    for (const std::vector<size_t>& row : rows()) {
      std::vector<Openings> alternatives;
      for (size_t j : row) {
        const double w = openings_[j].width();
        Openings a = openings_;
        for (size_t i : row) {
          const double sill = heights_.sill(a[i]);
          PanelRectangle r = with_width(a[i], w);
          r.v1 = r.v0 + openings_[j].height();
          a[i] = heights_.with_sill(r, sill);
        }
        alternatives.push_back(a);
      }
      keep_best(alternatives);
    }
  }

  void symmetric_candidates() {
    std::vector<int> panels;
    for (const PanelRectangle& r : openings_)
      if (facade(r) >= 0 && std::count(panels.begin(), panels.end(), r.panel) == 0) panels.push_back(r.panel);
    for (int p : panels) {
      const Panel& panel = domain_.panels()[static_cast<size_t>(p)];
      const double axis = 0.5 * (panel.parameter_lower.x() + panel.parameter_upper.x());
      std::vector<Openings> alternatives;
      for (int side : {-1, 1}) {  // keep the left (right) half, mirrored onto the other
        Openings a;
        for (const PanelRectangle& r : openings_) {
          if (r.panel != p) {
            a.push_back(r);
            continue;
          }
          const double centre = 0.5 * (r.u0 + r.u1);
          if (r.u0 < axis && r.u1 > axis) {  // across the axis: centred on it
            PanelRectangle c = r;
            c.u0 = axis - 0.5 * r.width(), c.u1 = axis + 0.5 * r.width();
            a.push_back(c);
          } else if ((centre - axis) * side > 0) {
            a.push_back(r);
            PanelRectangle m = r;
            m.u0 = 2.0 * axis - r.u1, m.u1 = 2.0 * axis - r.u0;
            a.push_back(m);
          }
        }
        std::sort(a.begin(), a.end(), [](const PanelRectangle& x, const PanelRectangle& y) {
          return std::tie(x.panel, x.u0, x.v0) < std::tie(y.panel, y.u0, y.v0);
        });
        // A half without openings would leave the wall blank: not a way to meet the rule.
        if (std::any_of(a.begin(), a.end(), [&](const PanelRectangle& r) { return r.panel == p; }))
          alternatives.push_back(a);
      }
      keep_best(alternatives);
    }
  }

  void spacing_candidates() {
    for (std::vector<size_t> row : rows()) {
      if (row.size() < 3) continue;  // two openings have one pier
      // Along the facade: the first panel's u axis.
      const Panel& first = domain_.panels()[static_cast<size_t>(openings_[row[0]].panel)];
      const Vec3 along = first.u_axis;
      auto x_of = [&](int panel, double u) {
        const Panel& p = domain_.panels()[static_cast<size_t>(panel)];
        return static_cast<double>((p.origin + static_cast<float>(u) * p.u_axis).dot(along));
      };
      auto u_of = [&](int panel, double x) {
        const Panel& p = domain_.panels()[static_cast<size_t>(panel)];
        return (x - static_cast<double>(p.origin.dot(along))) / static_cast<double>(p.u_axis.dot(along));
      };
      auto left = [&](size_t i) { return std::min(x_of(openings_[i].panel, openings_[i].u0), x_of(openings_[i].panel, openings_[i].u1)); };
      std::sort(row.begin(), row.end(), [&](size_t a, size_t b) { return left(a) < left(b); });
      const double start = left(row.front());
      const double end = left(row.back()) + openings_[row.back()].width();
      double widths = 0.0;
      for (size_t i : row) widths += openings_[i].width();
      const double pier = (end - start - widths) / static_cast<double>(row.size() - 1);
      Openings a = openings_;
      double x = start;
      for (size_t i : row) {
        PanelRectangle& r = a[i];
        const double u = u_of(r.panel, x), u_end = u_of(r.panel, x + r.width());
        r.u0 = std::min(u, u_end), r.u1 = std::max(u, u_end);
        x += r.width() + pier;
      }
      keep_best({a});
    }
  }

  const OpeningDomain& domain_;
  const OpeningConstraints& c_;
  const WallHeights heights_;
  const std::vector<int> facade_;
  Openings openings_;
  const std::function<double(const Openings&)>& error_of_;
  Progress* progress_;
  double error_ = 0.0;
  bool met_all_ = true;
  std::vector<CompositionStep> steps_;
  std::vector<std::string> applied_;  // the rules applied so far
};

}  // namespace

Composition compose_facades(const OpeningDomain& domain, const OpeningConstraints& constraints,
                            const std::vector<PanelRectangle>& openings,
                            const std::function<double(const std::vector<PanelRectangle>&)>& error_of,
                            Progress* progress) {
  return Composer(domain, constraints, openings, error_of, progress).run();
}

std::vector<std::string> composition_violations(const OpeningDomain& domain, const OpeningConstraints& c,
                                                const std::vector<PanelRectangle>& openings) {
  std::vector<std::string> out;
  const std::vector<int> facade = facades_of(domain);
  const WallHeights heights(domain, c);
  std::map<int, std::vector<PanelRectangle>> by_facade;
  for (const PanelRectangle& r : openings)
    if (r.panel >= 0 && static_cast<size_t>(r.panel) < facade.size() && facade[static_cast<size_t>(r.panel)] >= 0)
      by_facade[facade[static_cast<size_t>(r.panel)]].push_back(r);
  for (const auto& [f, list] : by_facade) {
    const OpeningConstraints& rules = c.for_panel(list.front().panel);
    const std::string name = "facade " + std::to_string(f) + " (panel " + std::to_string(list.front().panel) + ")";
    auto all_same = [&](auto value) {
      return std::all_of(list.begin(), list.end(), [&](const PanelRectangle& r) { return near(value(r), value(list.front())); });
    };
    const bool required = !rules.automatic_alignment;  // automatic: kept only where cheap (composition.h)
    if (required && rules.align_sills && !all_same([&](const PanelRectangle& r) { return heights.sill(r); }))
      out.push_back(name + ": sills not aligned (align_sills)");
    if (required && rules.align_heads && !all_same([&](const PanelRectangle& r) { return heights.head(r); }))
      out.push_back(name + ": heads not aligned (align_heads)");
    if (rules.equal_widths && !all_same([](const PanelRectangle& r) { return r.width(); }))
      out.push_back(name + ": widths differ (equal_widths)");
    for (const PanelRectangle& r : list)
      if (!rules.sill_heights.empty() &&
          std::none_of(rules.sill_heights.begin(), rules.sill_heights.end(), [&](double h) { return near(h, heights.sill(r)); }))
        out.push_back(name + ": a sill at " + meters(heights.sill(r)) + " is none of sill_heights");
    if (rules.symmetric)
      for (const PanelRectangle& r : list) {
        const Panel& panel = domain.panels()[static_cast<size_t>(r.panel)];
        const double axis = 0.5 * (panel.parameter_lower.x() + panel.parameter_upper.x());
        const bool mirrored = std::any_of(list.begin(), list.end(), [&](const PanelRectangle& m) {
          return m.panel == r.panel && near(m.u0, 2 * axis - r.u1) && near(m.u1, 2 * axis - r.u0) && near(m.v0, r.v0) &&
                 near(m.v1, r.v1);
        });
        if (!mirrored) {
          out.push_back(name + ": an opening has no mirror image about panel " + std::to_string(r.panel) +
                        "'s axis (symmetric)");
          break;
        }
      }
  }
  // Rows (same_type_in_row, equal_spacing): openings of a facade with one sill.
  for (const auto& [f, list] : by_facade) {
    const OpeningConstraints& rules = c.for_panel(list.front().panel);
    if (!rules.same_type_in_row && !rules.equal_spacing) continue;
    std::vector<std::vector<PanelRectangle>> rows;
    for (const PanelRectangle& r : list) {
      auto row = std::find_if(rows.begin(), rows.end(), [&](const std::vector<PanelRectangle>& w) {
        return std::abs(heights.sill(w.front()) - heights.sill(r)) <= kRowTolerance;
      });
      if (row == rows.end()) rows.push_back({r});
      else row->push_back(r);
    }
    const std::string name = "facade " + std::to_string(f);
    for (std::vector<PanelRectangle>& row : rows) {
      if (rules.same_type_in_row)
        for (const PanelRectangle& r : row)
          if (!near(r.width(), row.front().width()) || !near(r.height(), row.front().height())) {
            out.push_back(name + ": a row has openings of different sizes (same_type_in_row)");
            break;
          }
      if (rules.equal_spacing && row.size() >= 3) {
        const Panel& first = domain.panels()[static_cast<size_t>(row.front().panel)];
        auto left = [&](const PanelRectangle& r) {
          const Panel& p = domain.panels()[static_cast<size_t>(r.panel)];
          const double a = (p.origin + static_cast<float>(r.u0) * p.u_axis).dot(first.u_axis);
          const double b = (p.origin + static_cast<float>(r.u1) * p.u_axis).dot(first.u_axis);
          return std::min(a, b);
        };
        std::sort(row.begin(), row.end(), [&](const PanelRectangle& a, const PanelRectangle& b) { return left(a) < left(b); });
        const double pier = left(row[1]) - left(row[0]) - row[0].width();
        for (size_t i = 1; i + 1 < row.size(); ++i)
          if (std::abs(left(row[i + 1]) - left(row[i]) - row[i].width() - pier) > 2 * kSame) {
            out.push_back(name + ": piers between the openings of a row differ (equal_spacing)");
            break;
          }
      }
    }
  }
  return out;
}

}  // namespace fenestra
