#include "solve/catalogue_snap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <optional>

#include "solve/edge_refinement.h"
#include "solve/thick_wall_edges.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr int kPasses = 2;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr size_t kExactTries = 4;  // best-ranked sizes evaluated exactly per opening and pass
// A size is moved by up to this many elements (in quarter-element steps) to become admissible.
constexpr int kMaxShiftElements = 3;

using Slot = std::optional<PanelRectangle>;  // an opening of the start, or none (dropped)

double snap(double x, double module) { return module > 0.0 ? module * std::round(x / module) : x; }

// Offsets (du, dv) in quarter elements, nearest first.
std::vector<std::pair<double, double>> shifts(double a) {
  std::vector<std::pair<double, double>> out;
  const int n = 4 * kMaxShiftElements;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) out.push_back({0.25 * a * i, 0.25 * a * j});
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) {
    return std::hypot(x.first, x.second) < std::hypot(y.first, y.second);
  });
  return out;
}

class Snapper {
 public:
  Snapper(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
          const OpeningConstraints& constraints, const Eigen::MatrixXd& opening_light,
          const std::vector<PanelRectangle>& start, Progress* progress, int cut_paths)
      : domain_(domain),
        records_(records),
        cut_paths_(cut_paths),
        objective_(objective),
        constraints_(constraints),
        light_(opening_light),
        start_(start),
        closed_(records.contributions().closed.value),
        progress_(progress),
        shifts_(shifts(domain.element_size())),
        search_(cut_paths > 0 ? nullptr : records.region_search(start)) {  // cuts need no records' index
    slots_.assign(start.begin(), start.end());
    if (cut_paths_ > 0) {
      const SensorValues start_cut = cut(slots_);
      values_ = start_cut.value, errors_ = start_cut.standard_error;
    } else {
      values_ = search_->values();
    }
  }

  CatalogueSnap run() {
    for (int pass = 0; pass < kPasses; ++pass)
      for (size_t i = 0; i < slots_.size(); ++i)
        if (slots_[i]) snap_one(i, pass == 0);
    CatalogueSnap out;
    for (const Slot& s : slots_)
      if (s) out.openings.push_back(*s);
    out.values = values_;
    out.exact = true;
    out.standard_error = errors_;
    for (size_t i = 0; i < slots_.size() && cut_paths_ == 0; ++i)
      if (slots_[i] && thick(i) && !same(*slots_[i], start_[i])) out.exact = false;
    out.notes = notes_;
    return out;
  }

 private:
  bool thick(size_t i) const { return domain_.panels()[start_[i].panel].thickness > 0.0f; }
  static bool same(const PanelRectangle& a, const PanelRectangle& b) {
    return a.panel == b.panel && a.u0 == b.u0 && a.u1 == b.u1 && a.v0 == b.v0 && a.v1 == b.v1;
  }

  // The slots with slot i replaced: what the records evaluate (resized openings in thick walls
  // stay on the grid there) and the linear change those leave out.
  std::vector<PanelRectangle> evaluated(const std::vector<Slot>& slots) const {
    std::vector<PanelRectangle> out;
    for (size_t j = 0; j < slots.size(); ++j)
      if (slots[j]) out.push_back(thick(j) ? start_[j] : *slots[j]);
    return out;
  }
  Eigen::VectorXd thick_change(const std::vector<Slot>& slots) const {
    Eigen::VectorXd change = Eigen::VectorXd::Zero(closed_.size());
    for (size_t j = 0; j < slots.size(); ++j)
      if (slots[j] && thick(j) && !same(*slots[j], start_[j]))
        change = screened_values(domain_, light_, change, start_[j], *slots[j]);
    return change;
  }
  double error_of(const Eigen::VectorXd& values) const { return prediction_error(objective_, values - closed_); }

  SensorValues cut(const std::vector<Slot>& slots) {
    std::vector<OpeningInput> openings;
    for (const Slot& s : slots)
      if (s) openings.emplace_back(*s);
    return records_.cut(openings, cut_paths_, kThickWallEdgeCutStream);
  }
  // The trial's values: cut, or from the records (and the linear change of resized openings in
  // thick walls), as the search's last try.
  SensorValues values_of(const std::vector<Slot>& trial) {
    if (cut_paths_ > 0) return cut(trial);
    SensorValues v;
    v.value = search_->try_region(evaluated(trial)) + thick_change(trial);
    return v;
  }

  // Catalogue sizes for opening i, each at its first admissible place near the anchors.
  std::vector<PanelRectangle> candidates(size_t i) const {
    const PanelRectangle& at = *slots_[i];
    const Panel& panel = domain_.panels()[at.panel];
    const OpeningConstraints& set = constraints_.for_panel(at.panel);
    const double cu = 0.5 * (at.u0 + at.u1), cv = 0.5 * (at.v0 + at.v1);
    std::vector<PanelRectangle> out;
    for (const CatalogueSize& size : set.catalogue.sizes_for(panel)) {
      const double anchors_v0[] = {cv - 0.5 * size.height, at.v0, at.v1 - size.height};
      for (double v0 : anchors_v0) {
        const std::optional<PanelRectangle> r = placed(i, at.panel, cu - 0.5 * size.width, v0, size);
        if (r && std::none_of(out.begin(), out.end(), [&](const PanelRectangle& o) { return same(o, *r); }))
          out.push_back(*r);
      }
    }
    return out;
  }

  // A width x height opening with its corner near (u0, v0), admissible and apart from the others.
  std::optional<PanelRectangle> placed(size_t i, int panel, double u0, double v0, const CatalogueSize& size) const {
    const double module = constraints_.for_panel(panel).module;
    for (const auto& [du, dv] : shifts_) {
      PanelRectangle r{panel, snap(u0 + du, module), 0.0, snap(v0 + dv, module), 0.0};
      r.u1 = r.u0 + size.width;
      r.v1 = r.v0 + size.height;
      if (!admissible(r, domain_, constraints_)) continue;
      bool apart_from_others = true;
      for (size_t j = 0; j < slots_.size() && apart_from_others; ++j)
        if (j != i && slots_[j]) apart_from_others = apart(r, *slots_[j], constraints_);
      if (apart_from_others) return r;
    }
    return std::nullopt;
  }

  void snap_one(size_t i, bool must_change) {
    if (progress_) progress_->throw_if_cancelled();
    const PanelRectangle at = *slots_[i];
    const Panel& panel = domain_.panels()[at.panel];
    const WindowCatalogue& catalogue = constraints_.for_panel(at.panel).catalogue;
    if (catalogue.sizes_for(panel).empty()) return;  // sizes free on this kind of panel
    must_change = must_change && !catalogue.allows(panel, at.width(), at.height());
    // Rank by the linear model, from the current values (with cuts, every size is cut).
    std::vector<std::pair<double, Slot>> ranked;
    for (const PanelRectangle& r : candidates(i)) {
      const Eigen::VectorXd v = screened_values(domain_, light_, values_, at, r);
      ranked.push_back({error_of(v), r});
    }
    std::sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    if (cut_paths_ == 0 && ranked.size() > kExactTries) ranked.resize(kExactTries);
    ranked.push_back({0.0, std::nullopt});  // no opening
    double best = must_change ? std::numeric_limits<double>::infinity() : error_of(values_);
    std::optional<std::vector<Slot>> kept;
    SensorValues kept_values;
    for (const auto& [screened, choice] : ranked) {
      std::vector<Slot> trial = slots_;
      trial[i] = choice;
      const SensorValues v = values_of(trial);
      const double e = error_of(v.value);
      if (e < best * (1.0 - 1e-9) || (must_change && !kept && std::isinf(best))) {
        best = e;
        kept = trial;
        kept_values = v;
        if (cut_paths_ == 0) search_->accept();
      }
    }
    if (!kept) return;
    // try_region / accept leave the search at the last accepted try, which is the kept one.
    slots_ = *kept;
    values_ = kept_values.value;
    errors_ = kept_values.standard_error;
    if (must_change && !slots_[i])
      notes_.push_back("catalogue: an opening of " + fmt(at.width()) + " x " + fmt(at.height()) + " m on panel " +
                       std::to_string(at.panel) + " was dropped: no catalogue size fits there, or none helps");
  }

  static std::string fmt(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", x);
    return buf;
  }

  const OpeningDomain& domain_;
  RecordQueries& records_;
  const int cut_paths_;
  const LinearObjective& objective_;
  const OpeningConstraints& constraints_;
  const Eigen::MatrixXd& light_;
  const std::vector<PanelRectangle> start_;
  const Eigen::VectorXd closed_;
  Progress* progress_;
  const std::vector<std::pair<double, double>> shifts_;
  std::unique_ptr<RegionQueries> search_;
  std::vector<Slot> slots_;
  Eigen::VectorXd values_;
  Eigen::VectorXd errors_;  // with cuts: values_'s standard errors
  std::vector<std::string> notes_;
};

}  // namespace

OpeningConstraints grid_search_constraints(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  if (!uses_catalogue(domain, constraints)) return constraints;
  const double a = domain.element_size();
  OpeningConstraints out = constraints;
  out.per_panel.clear();
  for (size_t p = 0; p < domain.panels().size(); ++p) {
    OpeningConstraints set = constraints.for_panel(static_cast<int>(p));
    set.per_panel.clear();
    const std::vector<CatalogueSize> sizes = set.catalogue.sizes_for(domain.panels()[p]);
    if (!sizes.empty()) {
      OpeningConstraints near = set;
      double w0 = kInfinity, w1 = 0.0, h0 = kInfinity, h1 = 0.0;
      for (const CatalogueSize& s : sizes)
        w0 = std::min(w0, s.width), w1 = std::max(w1, s.width), h0 = std::min(h0, s.height), h1 = std::max(h1, s.height);
      near.min_width = std::max(set.min_width, w0 - a);
      near.max_width = std::min(set.max_width, w1 + a);
      near.min_height = std::max(set.min_height, h0 - a);
      near.max_height = std::min(set.max_height, h1 + a);
      try {
        check_feasible(near, a);
        set = near;
      } catch (const std::invalid_argument&) {
        // the set as given: the snap still finds catalogue sizes near its openings
      }
    }
    out.per_panel.push_back(set);
  }
  return out;
}

bool uses_catalogue(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  for (size_t p = 0; p < domain.panels().size(); ++p)
    if (!constraints.for_panel(static_cast<int>(p)).catalogue.sizes_for(domain.panels()[p]).empty()) return true;
  return false;
}

CatalogueSnap snap_to_catalogue(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                                const OpeningConstraints& constraints, const Eigen::MatrixXd& opening_light,
                                const std::vector<PanelRectangle>& start, Progress* progress, int cut_paths) {
  return Snapper(domain, records, objective, constraints, opening_light, start, progress, cut_paths).run();
}

}  // namespace fenestra
