#include "solve/climate_search.h"

#include "solve/genetic_search.h"

namespace fenestra {
namespace {

// The error model of the genetic engine (solve/genetic_search.h) for climate goals.
class ClimateError {
 public:
  using Response = ClimateResponse;
  // A trial flip copies the year of every goal sensor: pairs would cost elements^2 copies.
  static constexpr bool kPairPolish = false;

  ClimateError(const HourlyFlipModel& model, const ClimateObjective& objective) : model_(model), objective_(objective) {}

  Response response(const std::vector<uint8_t>& open) const { return climate_response(model_, objective_, open); }
  void flip(Response* r, const std::vector<uint8_t>& open, int j) const {
    flip_climate_response(model_, objective_, open, j, r);
  }
  double operator()(const Response& r) const { return objective_.error(r.total, r.direct, r.open_area); }
  double flip_change(const Response& r, const std::vector<uint8_t>& open, int j) const {
    Response after = r;
    flip(&after, open, j);
    return (*this)(after) - (*this)(r);
  }
  double pair_change(const Response& r, const std::vector<uint8_t>& open, int j, int k) const {
    Response after = r;
    flip(&after, open, j);
    std::vector<uint8_t> between = open;
    between[j] ^= 1;
    flip(&after, between, k);
    return (*this)(after) - (*this)(r);
  }
  double scale() const { return 1.0; }  // errors are fractions of the goals

 private:
  const HourlyFlipModel& model_;
  const ClimateObjective& objective_;
};

}  // namespace

ClimateResponse climate_response(const HourlyFlipModel& model, const ClimateObjective& objective,
                                 const std::vector<uint8_t>& open) {
  ClimateResponse r;
  r.total = model.total;
  if (objective.needs_direct()) r.direct = model.direct;
  std::vector<uint8_t> state = model.about;
  for (size_t k = 0; k < open.size(); ++k) {
    if (open[k]) r.open_area += objective.element_area(static_cast<int>(k));
    if ((open[k] != 0) != (model.about[k] != 0)) {
      // Apply as flips from the model's state (the area is counted above).
      const double area = r.open_area;
      flip_climate_response(model, objective, state, static_cast<int>(k), &r);
      r.open_area = area;
      state[k] ^= 1;
    }
  }
  return r;
}

void flip_climate_response(const HourlyFlipModel& model, const ClimateObjective& objective,
                           const std::vector<uint8_t>& open, int j, ClimateResponse* r) {
  // Away from the model's state the change adds; back toward it, it comes off again.
  const float sign = (open[j] != 0) == (model.about[j] != 0) ? 1.0f : -1.0f;
  r->open_area += (open[j] ? -1.0 : 1.0) * objective.element_area(j);
  const HourlyMatrix& change = model.flip_total[j];
  if (change.size() == 0) return;
  if (sign > 0.0f) r->total += change;
  else r->total -= change;
  if (r->direct.size())
    for (const DirectChange& d : model.flip_direct[j]) r->direct(d.row, d.column) += sign * d.lux;
}

GeneticResult run_climate_genetic(const HourlyFlipModel& model, const ClimateObjective& objective,
                                  const ElementGrid& grid, const std::vector<std::vector<uint8_t>>& seeds,
                                  const GeneticSettings& settings, Progress* progress) {
  if (static_cast<size_t>(grid.size()) != model.about.size())
    throw std::invalid_argument("climate genetic: the model has " + std::to_string(model.about.size()) +
                                " elements, the grid " + std::to_string(grid.size()));
  return genetic_search::run_search(ClimateError(model, objective), grid, seeds, settings, progress);
}

}  // namespace fenestra
