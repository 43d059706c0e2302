#include "solve/climate_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "annual/annual_study.h"
#include "solve/record_queries.h"

namespace fenestra {
namespace {

// Each goal the final openings miss, with what they reach and, when even every element open
// falls short, what the domain can give at most: the best compromise, said as such.
std::vector<std::string> unmet_climate_goals(const ClimateGoals& goals, const std::vector<ClimateFigure>& achieved,
                                             const std::vector<ClimateFigure>& elements,
                                             const std::vector<ClimateFigure>& all_open) {
  std::vector<std::string> out;
  for (size_t g = 0; g < goals.goals.size() && g < achieved.size(); ++g) {
    const ClimateGoal& goal = goals.goals[g];
    if (figure_meets(goal, achieved[g].achieved)) continue;
    std::string line = goal.describe() + " is not met: the openings reach " + figure_text(goal, achieved[g].achieved);
    if (g < all_open.size() && goal.sense() == GoalSense::AtLeast && !figure_meets(goal, all_open[g].achieved))
      line += "; even every element of the opening domain open reaches only " + figure_text(goal, all_open[g].achieved) +
              ": the goal cannot be met here";
    else if (g < elements.size() && figure_meets(goal, elements[g].achieved))
      line += "; the open elements before the constraints reached " + figure_text(goal, elements[g].achieved) +
              ": the opening constraints cost it";
    else
      line += " (the best compromise found with the other goals)";
    out.push_back(line);
  }
  return out;
}

// Whether a goal's figure from the path records and with real cutters differ beyond the noise: sDA
// by more than its noise (sda_noise) and kHeadlineFractionGap, another fraction by more than
// kHeadlineFractionGap, an annual mean (lux) by more than 3 combined standard errors of the goal's
// sensors' mean.
// An sDA goal's noise: the share of its sensors whose DA, in either year, lies within its noise of
// the time fraction (either side may be right for them). A sensor's DA is uncertain by the share of
// occupied hours whose value lies within 3 combined relative standard errors r of the threshold
// (the coefficients' errors move every hour by about r).
double sda_noise(const ClimateGoal& goal, const AnnualStudy& a, const AnnualStudy& b) {
  int uncertain = 0;
  for (int i : goal.sensors) {
    const double mean = std::max(1e-9, a.occupied_mean.value[i]);
    const double r = std::hypot(a.occupied_mean.standard_error[i], b.occupied_mean.standard_error[i]) / mean;
    int occupied = 0, near = 0, over_a = 0, over_b = 0;
    for (size_t h = 0; h < a.occupied.size(); ++h) {
      if (!a.occupied[h]) continue;
      const double e = a.illuminance.total(i, static_cast<Eigen::Index>(h));
      ++occupied;
      near += std::abs(e - goal.illuminance_lux) <= 3.0 * r * e;
      over_a += e >= goal.illuminance_lux;
      over_b += b.illuminance.total(i, static_cast<Eigen::Index>(h)) >= goal.illuminance_lux;
    }
    if (occupied == 0) continue;
    const double band = (near + 1.0) / occupied;
    uncertain += std::abs(static_cast<double>(over_a) / occupied - goal.time_fraction) <= band ||
                 std::abs(static_cast<double>(over_b) / occupied - goal.time_fraction) <= band;
  }
  return static_cast<double>(uncertain) / static_cast<double>(std::max<size_t>(1, goal.sensors.size()));
}

bool beyond_noise(const ClimateGoal& goal, double records, double cut, const AnnualStudy& records_year,
                  const AnnualStudy& cut_year) {
  if (goal.metric == ClimateMetric::SpatialDaylightAutonomy)
    return std::abs(records - cut) > std::max(kHeadlineFractionGap, sda_noise(goal, records_year, cut_year)) + 1e-9;
  if (goal.unit() != "lux") return std::abs(records - cut) > kHeadlineFractionGap;
  double variance = 0.0;
  for (int i : goal.sensors)
    variance += std::pow(records_year.occupied_mean.standard_error[i], 2) + std::pow(cut_year.occupied_mean.standard_error[i], 2);
  const double n = static_cast<double>(std::max<size_t>(1, goal.sensors.size()));
  return std::abs(records - cut) > 3.0 * std::sqrt(variance) / n;
}

}  // namespace

std::string figure_text(const ClimateGoal& goal, double x) {
  char text[48];
  if (goal.unit() == "lux") std::snprintf(text, sizeof text, "%.0f lx", x);
  else std::snprintf(text, sizeof text, "%.1f %%", 100.0 * x);
  return text;
}

void report_climate(const Scene& scene, RecordQueries& records, const ClimateProblem& problem,
                    const std::vector<PanelRectangle>& openings, bool verify, int verify_paths, SolveResult* out) {
  ClimateOutcome& climate = out->climate;
  for (const PanelRectangle& r : openings) climate.glazing_area_m2 += (r.u1 - r.u0) * (r.v1 - r.v0);
  for (const Element& e : scene.domain.elements()) climate.domain_area_m2 += static_cast<double>(e.width()) * e.height();
  try {
    auto study = std::make_shared<AnnualStudy>(records.annual_study(openings));
    climate.achieved = climate_figures(problem, study->illuminance.total, study->illuminance.direct);
    climate.study = std::move(study);
  } catch (const std::invalid_argument& e) {
    out->warnings.push_back(std::string("climate goals: the path records cannot give the final openings' year (") +
                            e.what() + ")");
  }
  if (verify) {
    const std::vector<OpeningInput> cutters(openings.begin(), openings.end());
    auto cut = std::make_shared<AnnualStudy>(records.annual_cut(cutters, verify_paths));
    climate.verified = climate_figures(problem, cut->illuminance.total, cut->illuminance.direct);
    climate.verified_study = std::move(cut);
  }
  std::string apart;  // the goals whose two figures disagree beyond the noise
  for (size_t g = 0; g < climate.verified.size() && g < climate.achieved.size(); ++g) {
    const ClimateGoal& goal = scene.sensors.climate_goals.goals[g];
    const double records = climate.achieved[g].achieved, cut = climate.verified[g].achieved;
    climate.apart.push_back(beyond_noise(goal, records, cut, *climate.study, *climate.verified_study) ? 1 : 0);
    if (climate.apart.back())
      apart += std::string(apart.empty() ? "" : ", ") + goal.describe() + ": " + figure_text(goal, records) +
               " from the path records, " + figure_text(goal, cut) + " with real cutters";
    else if (figure_meets(goal, records) && !figure_meets(goal, cut))
      out->warnings.push_back("climate goals: " + goal.describe() + " is met from the path records (" +
                              figure_text(goal, records) + ") but not with real cutters (" + figure_text(goal, cut) +
                              "): a result at the edge of the goal; more paths per sensor tell which is right");
  }
  if (!apart.empty()) {
    climate.headline_cutters = true;
    out->warnings.push_back("climate goals: the year from the path records and the year with real cutters disagree "
                            "beyond the noise (" + apart + "): the figures shown are the real cutters'");
  }
  const std::vector<ClimateFigure>& judged = climate.headline();
  climate.unmet =
      unmet_climate_goals(scene.sensors.climate_goals, judged, climate.element_figures, climate.all_open_figures);
  for (const std::string& u : climate.unmet) out->warnings.push_back("climate goals: " + u);
}

std::vector<ClimateFigure> tradeoff_climate(RecordQueries& records, const ClimateProblem& problem,
                                            const TradeoffResult& entry, const SolveResult& out) {
  if (entry.answer) return out.climate.headline();
  std::vector<PanelRectangle> rects;
  for (const OpeningRectangle& o : entry.openings) rects.push_back(o.parameter);
  try {
    const AnnualStudy year = records.annual_study(rects);
    return climate_figures(problem, year.illuminance.total, year.illuminance.direct);
  } catch (const std::invalid_argument&) {
    return {};  // edges off the grid lines of a thick wall: the records cannot tell
  }
}

}  // namespace fenestra
