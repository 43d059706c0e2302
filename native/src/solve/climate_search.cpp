#include "solve/climate_search.h"

#include "solve/genetic_search.h"

namespace fenestra {
namespace {

// The error model of the genetic engine (solve/genetic_search.h) for climate goals: batched, each
// individual's year kept in a slot of the model's shards.
class ClimateError {
 public:
  struct Response {
    int slot = 0;
    int base = ClimateRecipe::kModelState;
    double error = 0.0;
  };
  static constexpr bool kBatched = true;
  // A trial flip costs a year of every goal sensor: pairs would cost elements^2 of them.
  static constexpr bool kPairPolish = false;

  ClimateError(ClimateModel& model, const ClimateObjective& objective) : model_(&model), objective_(objective) {}

  Response response(const std::vector<uint8_t>&) const { return {}; }
  void flip(Response*, const std::vector<uint8_t>&, int) const {}  // the state itself says what to settle
  double operator()(const Response& r) const { return r.error; }
  double scale() const { return 1.0; }  // errors are fractions of the goals

  void settle(const std::vector<Response*>& responses, const std::vector<const std::vector<uint8_t>*>& states) const {
    std::vector<ClimateRecipe> batch(responses.size());
    for (size_t i = 0; i < batch.size(); ++i) batch[i] = {responses[i]->slot, responses[i]->base, *states[i]};
    const std::vector<ClimateTally> tallies = model_->settle(batch);
    for (size_t i = 0; i < batch.size(); ++i) responses[i]->error = objective_.error(tallies[i], open_area(*states[i]));
  }

  std::vector<double> flip_errors(const Response& r, const std::vector<uint8_t>& open,
                                  const std::vector<int>& elements) const {
    const std::vector<ClimateTally> tallies = model_->flip_tallies(r.slot, elements);
    const double area = open_area(open);
    std::vector<double> out(elements.size());
    for (size_t i = 0; i < elements.size(); ++i) {
      const int k = elements[i];
      out[i] = objective_.error(tallies[i], area + (open[k] ? -1.0 : 1.0) * objective_.element_area(k));
    }
    return out;
  }

 private:
  double open_area(const std::vector<uint8_t>& open) const {
    double area = 0.0;
    for (size_t k = 0; k < open.size(); ++k)
      if (open[k]) area += objective_.element_area(static_cast<int>(k));
    return area;
  }

  ClimateModel* model_;
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
  add_flip(model.flip_total[j], sign, &r->total);
  if (r->direct.size())
    for (const DirectChange& d : model.flip_direct[j]) r->direct(d.row, d.column) += sign * d.lux;
}

GeneticResult run_climate_genetic(ClimateModel& model, const ClimateObjective& objective, const ElementGrid& grid,
                                  const std::vector<std::vector<uint8_t>>& seeds, const GeneticSettings& settings,
                                  Progress* progress) {
  return genetic_search::run_search(ClimateError(model, objective), grid, seeds, settings, progress);
}

}  // namespace fenestra
