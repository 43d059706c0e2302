#include "solve/constraint_costs.h"

#include <algorithm>
#include <cstdio>

#include "util/number_text.h"

namespace fenestra {
namespace {

constexpr double kUnlimited = OpeningConstraints::kUnlimited;



struct Family {
  std::vector<std::string> keys;
  void (*lift)(OpeningConstraints*);
};

const std::vector<Family>& families() {
  static const std::vector<Family> all = {
      {{"min_width", "min_height", "min_area"},
       [](OpeningConstraints* c) { c->min_width = c->min_height = c->min_area = 0.0; }},
      {{"max_width", "max_height", "max_area"},
       [](OpeningConstraints* c) { c->max_width = c->max_height = c->max_area = kUnlimited; }},
      {{"min_aspect", "max_aspect"},
       [](OpeningConstraints* c) { c->min_aspect = 0.0, c->max_aspect = kUnlimited; }},
      {{"margin"}, [](OpeningConstraints* c) { c->margin = 0.0; }},
      {{"sill_min", "sill_max", "head_min", "head_max", "head_clearance"},
       [](OpeningConstraints* c) {
         c->sill_min = c->head_min = c->head_clearance = 0.0;
         c->sill_max = c->head_max = kUnlimited;
       }},
      {{"min_gap"}, [](OpeningConstraints* c) { c->min_gap = 0.0; }},
      {{"max_openings"}, [](OpeningConstraints* c) { c->max_openings = 0; }},
      {{"max_openings_per_panel", "panel_width_per_opening"},
       [](OpeningConstraints* c) {
         c->max_openings_per_panel = 0;
         c->panel_width_per_opening = 0.0;
       }},
      {{"catalogue"}, [](OpeningConstraints* c) { c->catalogue = WindowCatalogue(); }},
  };
  return all;
}

OpeningConstraints lifted(const OpeningConstraints& c, const Family& family) {
  OpeningConstraints out = c;
  family.lift(&out);
  for (OpeningConstraints& p : out.per_panel) family.lift(&p);
  return out;
}

// The constraints with every family but `kept` lifted.
OpeningConstraints only(const OpeningConstraints& c, const Family& kept) {
  OpeningConstraints out = c;
  for (const Family& other : families())
    if (&other != &kept) out = lifted(out, other);
  return out;
}

// Whether lifting the family changes any limit (the text form names every limit that is set).
bool present(const OpeningConstraints& c, const Family& family) {
  const OpeningConstraints without = lifted(c, family);
  if (without.to_string() != c.to_string() || without.catalogue.empty() != c.catalogue.empty()) return true;
  for (size_t p = 0; p < c.per_panel.size(); ++p)
    if (without.per_panel[p].to_string() != c.per_panel[p].to_string() ||
        without.per_panel[p].catalogue.empty() != c.per_panel[p].catalogue.empty())
      return true;
  return false;
}

// The family's keys that are set (on some panel), as the text form names them ("catalogue" by
// itself).
std::vector<std::string> set_keys(const OpeningConstraints& c, const Family& family) {
  std::vector<std::string> out;
  auto named = [](const OpeningConstraints& x, const std::string& key) {
    return key == "catalogue" ? !x.catalogue.empty() : x.to_string().find(key + "=") != std::string::npos;
  };
  for (const std::string& key : family.keys) {
    bool set = named(c, key);
    for (const OpeningConstraints& p : c.per_panel) set = set || named(p, key);
    if (set) out.push_back(key);
  }
  return out;
}

std::string joined(const std::vector<std::string>& keys) {
  std::string s;
  for (const std::string& k : keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

}  // namespace

std::vector<ConstraintCost> constraint_costs(
    const OpeningConstraints& constraints, const std::function<double(const OpeningConstraints&)>& error_with,
    double free_error, double constrained_error) {
  std::vector<const Family*> set;
  for (const Family& family : families())
    if (present(constraints, family)) set.push_back(&family);
  std::vector<ConstraintCost> out;
  for (const Family* family : set) out.push_back({set_keys(constraints, *family), error_with(lifted(constraints, *family))});
  auto by_error = [](const ConstraintCost& a, const ConstraintCost& b) { return a.error_without < b.error_without; };
  std::stable_sort(out.begin(), out.end(), by_error);
  const double halfway = 0.5 * (free_error + constrained_error);
  if (set.size() < 2 || out.front().error_without <= halfway) return out;
  // No family alone explains the cost: limits that bind together (a margin and a sill both keep an
  // opening off the floor). Each family alone, the others lifted: those that cost more than half
  // the way on their own are lifted together; and every family at once, which tells whether the
  // limits cost the light at all.
  OpeningConstraints without_binding = constraints;
  ConstraintCost binding;
  size_t binding_families = 0;
  for (const Family* family : set) {
    if (error_with(only(constraints, *family)) <= halfway) continue;
    without_binding = lifted(without_binding, *family);
    const std::vector<std::string> keys = set_keys(constraints, *family);
    binding.keys.insert(binding.keys.end(), keys.begin(), keys.end());
    ++binding_families;
  }
  if (binding_families >= 2 && binding_families < set.size()) {
    binding.error_without = error_with(without_binding);
    out.push_back(binding);
  }
  OpeningConstraints without_all = constraints;
  ConstraintCost all;
  for (const Family* family : set) {
    without_all = lifted(without_all, *family);
    const std::vector<std::string> keys = set_keys(constraints, *family);
    all.keys.insert(all.keys.end(), keys.begin(), keys.end());
  }
  all.error_without = error_with(without_all);
  out.push_back(all);
  std::stable_sort(out.begin(), out.end(), by_error);
  return out;
}

bool constraints_cost_much(double free_error, double constrained_error) {
  return constrained_error > 1.25 * free_error && constrained_error > free_error + 0.02;
}

std::string constraint_cost_warning(double free_error, double constrained_error,
                                    const std::vector<ConstraintCost>& costs) {
  std::string s = "the openings within the constraints meet the goals at " + percent_text(constrained_error) +
                  " on the element grid, the free answer at " + percent_text(free_error);
  if (costs.empty()) return s;
  // Lifting the limits, alone or together, gives back under a tenth of the difference: the
  // constraints are not what keeps the answer from the goals (the search within them is).
  if (costs[0].error_without > constrained_error - 0.1 * (constrained_error - free_error))
    return s + "; lifting the constraints, alone or together, does not bring it lower (constraint_costs in the result)";
  s += "; without " + joined(costs[0].keys) + " it would be " + percent_text(costs[0].error_without);
  return s + " (constraint_costs in the result)";
}

}  // namespace fenestra
