#include "daylight/annual_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "util/number_text.h"

namespace fenestra {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// EN 17037 Table A.1: E_TM over 95 % of the reference plane; E_T over 50 % (vertical or inclined
// openings) or 95 % (horizontal openings).
constexpr double kEnMinimumAreaFraction = 0.95;
constexpr double kEnTargetAreaFractionVertical = 0.50;
constexpr double kEnTargetAreaFractionHorizontal = 0.95;

[[noreturn]] void refuse(const std::string& message) {
  throw std::invalid_argument("annual metrics: " + message);
}

std::string clock(double hours) {
  const int minutes = static_cast<int>(std::floor(hours * 60.0 + 0.5));
  char text[16];
  std::snprintf(text, sizeof text, "%02d:%02d", minutes / 60, minutes % 60);
  return text;
}

// "hour 17 (01-01 17:30)": the column index and its stamp, for messages.
std::string hour_name(const std::vector<HourStamp>& hours, Eigen::Index column) {
  const HourStamp& h = hours[static_cast<size_t>(column)];
  char text[48];
  std::snprintf(text, sizeof text, " (%02d-%02d %s)", h.month, h.day, clock(h.clock_hour).c_str());
  return "hour " + std::to_string(column) + text;
}

bool valid_day(int month, int day) {
  static const int kDays[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month >= 1 && month <= 12 && day >= 1 && day <= kDays[month - 1];
}

void check_stamps(const std::vector<HourStamp>& hours) {
  for (size_t j = 0; j < hours.size(); ++j) {
    const HourStamp& h = hours[j];
    const std::string where = "hours[" + std::to_string(j) + "]";
    if (!valid_day(h.month, h.day))
      refuse(where + ": month " + std::to_string(h.month) + ", day " + std::to_string(h.day) + " is not a date");
    if (!(h.clock_hour >= 0.0 && h.clock_hour < 24.0))
      refuse(where + ".clock_hour = " + decimal_text(h.clock_hour, 10) + " is outside [0, 24)");
  }
}

void check_positive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) refuse(std::string(field) + " = " + decimal_text(value, 10) + " must be > 0");
}

void check_fraction(const std::string& field, double value) {
  if (!(value > 0.0 && value <= 1.0)) refuse(field + " = " + decimal_text(value, 10) + " must lie in (0, 1]");
}

void check_settings(const AnnualMetricSettings& s) {
  if (!(s.occupied_start_hour >= 0.0 && s.occupied_start_hour < s.occupied_end_hour && s.occupied_end_hour <= 24.0))
    refuse("occupied hours [" + decimal_text(s.occupied_start_hour, 10) + ", " + decimal_text(s.occupied_end_hour, 10) +
           ") must satisfy 0 <= start < end <= 24");
  check_positive("da_threshold_lux", s.da_threshold_lux);
  check_fraction("sda_time_fraction", s.sda_time_fraction);
  for (size_t i = 0; i < s.sda_pass_levels.size(); ++i)
    check_fraction("sda_pass_levels[" + std::to_string(i) + "]", s.sda_pass_levels[i]);
  if (s.udi_edges_lux.size() < 2)
    refuse("udi_edges_lux needs at least 2 edges, has " + std::to_string(s.udi_edges_lux.size()));
  for (size_t i = 0; i < s.udi_edges_lux.size(); ++i) {
    const std::string field = "udi_edges_lux[" + std::to_string(i) + "]";
    check_positive(field.c_str(), s.udi_edges_lux[i]);
    if (i > 0 && !(s.udi_edges_lux[i] > s.udi_edges_lux[i - 1]))
      refuse(field + " = " + decimal_text(s.udi_edges_lux[i], 10) + " must exceed the edge before it, " +
             decimal_text(s.udi_edges_lux[i - 1], 10));
  }
  check_positive("ase_threshold_lux", s.ase_threshold_lux);
  if (!(std::isfinite(s.ase_hours) && s.ase_hours >= 0.0))
    refuse("ase_hours = " + decimal_text(s.ase_hours, 10) + " must be >= 0");
  if (!(s.ase_pass_limit >= 0.0 && s.ase_pass_limit <= 1.0))
    refuse("ase_pass_limit = " + decimal_text(s.ase_pass_limit, 10) + " must lie in [0, 1]");
  if (s.en17037_levels.empty()) refuse("en17037_levels is empty");
  for (size_t i = 0; i < s.en17037_levels.size(); ++i) {
    const En17037Level& level = s.en17037_levels[i];
    const std::string field = "en17037_levels[" + std::to_string(i) + "] (" + level.name + ")";
    check_positive((field + ".target_lux").c_str(), level.target_lux);
    check_positive((field + ".minimum_target_lux").c_str(), level.minimum_target_lux);
    if (i > 0 && !(level.target_lux > s.en17037_levels[i - 1].target_lux))
      refuse(field + ".target_lux = " + decimal_text(level.target_lux, 10) + " must exceed the level before it, " +
             decimal_text(s.en17037_levels[i - 1].target_lux, 10));
  }
  check_fraction("en17037_time_fraction", s.en17037_time_fraction);
}

// Illuminance must be finite and >= 0; the first offender is named by sensor and hour.
template <class Matrix>
void check_illuminance(const Matrix& m, const char* field, const std::vector<HourStamp>& hours) {
  using Scalar = typename Matrix::Scalar;
  // One vectorised pass to see whether anything is wrong (NaN fails both comparisons).
  const Scalar* v = m.data();
  const Scalar largest = std::numeric_limits<Scalar>::max();
  unsigned bad = 0;
  for (Eigen::Index k = 0, size = m.size(); k < size; ++k)
    bad |= static_cast<unsigned>(!(v[k] >= Scalar(0))) | static_cast<unsigned>(!(v[k] <= largest));
  if (!bad) return;
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      const double value = m(i, j);
      if (!(std::isfinite(value) && value >= 0.0))
        refuse(std::string(field) + " at sensor " + std::to_string(i) + ", " + hour_name(hours, j) + " is " +
               decimal_text(value, 10) + " lux: it must be finite and >= 0");
    }
}

Eigen::VectorXd sensor_weights(const std::vector<double>& areas, Eigen::Index sensors) {
  if (areas.empty()) return Eigen::VectorXd::Ones(sensors);
  if (static_cast<Eigen::Index>(areas.size()) != sensors)
    refuse("sensor_areas_m2 has " + std::to_string(areas.size()) + " values for " + std::to_string(sensors) +
           " sensors");
  Eigen::VectorXd w(sensors);
  for (Eigen::Index i = 0; i < sensors; ++i) {
    const double a = areas[static_cast<size_t>(i)];
    if (!(std::isfinite(a) && a >= 0.0))
      refuse("sensor_areas_m2[" + std::to_string(i) + "] = " + decimal_text(a, 10) + " m^2 must be finite and >= 0");
    w[i] = a;
  }
  if (!(w.sum() > 0.0)) refuse("sensor_areas_m2 are all 0: no area to take fractions of");
  return w;
}

std::vector<Eigen::Index> occupied_columns(const std::vector<HourStamp>& hours, const AnnualMetricSettings& s) {
  std::vector<Eigen::Index> columns;
  for (size_t j = 0; j < hours.size(); ++j)
    if (hours[j].clock_hour >= s.occupied_start_hour && hours[j].clock_hour < s.occupied_end_hour)
      columns.push_back(static_cast<Eigen::Index>(j));
  if (columns.empty())
    refuse("none of the " + std::to_string(hours.size()) + " hours lies in the occupied period [" +
           clock(s.occupied_start_hour) + ", " + clock(s.occupied_end_hour) + ") local standard time");
  return columns;
}

std::vector<UdiBand> udi_bands(const std::vector<double>& edges) {
  const size_t k = edges.size();
  std::vector<UdiBand> bands(k + 1);
  for (size_t b = 0; b <= k; ++b) {
    UdiBand& band = bands[b];
    band.lower_lux = b == 0 ? 0.0 : edges[b - 1];
    band.upper_lux = b == k ? kInfinity : edges[b];
    band.lower_inclusive = b != k;             // the top band is E > last edge
    band.upper_inclusive = b == k - 1;         // the highest inner band closes at the last edge
    std::ostringstream name;
    if (b == 0)
      name << "E < " << band.upper_lux << " lx";
    else if (b == k)
      name << "E > " << band.lower_lux << " lx";
    else
      name << band.lower_lux << " <= E " << (band.upper_inclusive ? "<=" : "<") << " " << band.upper_lux << " lx";
    band.name = name.str();
  }
  if (k == 3) {  // Mardaljevic's names for the four bands
    const char* names[4] = {"fell-short", "supplementary", "autonomous", "exceeded"};
    for (size_t b = 0; b < 4; ++b) bands[b].name = std::string(names[b]) + " (" + bands[b].name + ")";
  }
  return bands;
}

// The hot loops: plain loops over one contiguous column that the compiler vectorises (Eigen's
// comparisons yield bool arrays whose casts it does not). Values are widened to double, exactly.
template <class Scalar>
void widen(const Scalar* column, Eigen::Index n, double* e) {
  for (Eigen::Index i = 0; i < n; ++i) e[i] = static_cast<double>(column[i]);
}
void count_at_or_above(const double* e, Eigen::Index n, double threshold, double* count) {
  for (Eigen::Index i = 0; i < n; ++i) count[i] += e[i] >= threshold ? 1.0 : 0.0;
}
void count_above(const double* e, Eigen::Index n, double threshold, double* count) {
  for (Eigen::Index i = 0; i < n; ++i) count[i] += e[i] > threshold ? 1.0 : 0.0;
}
// Four partial sums, so that the sum vectorises without reordering licence from the compiler.
double area_at_or_above(const double* e, const double* w, Eigen::Index n, double threshold) {
  double a[4] = {0.0, 0.0, 0.0, 0.0};
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4)
    for (int k = 0; k < 4; ++k) a[k] += e[i + k] >= threshold ? w[i + k] : 0.0;
  for (; i < n; ++i) a[0] += e[i] >= threshold ? w[i] : 0.0;
  return (a[0] + a[1]) + (a[2] + a[3]);
}

// Sums over occupied hours, per sensor, in one pass over the matrix's columns.
struct OccupiedSums {
  Eigen::ArrayXd illuminance, at_threshold, continuous;
  std::vector<Eigen::ArrayXd> at_or_above_edge;  // E >= edge, per UDI edge
  Eigen::ArrayXd above_last_edge;                // E > last edge
};

template <class Matrix>
OccupiedSums occupied_sums(const Matrix& m, const std::vector<Eigen::Index>& columns, const AnnualMetricSettings& s) {
  const Eigen::Index n = m.rows();
  OccupiedSums sums;
  sums.illuminance = sums.at_threshold = sums.continuous = sums.above_last_edge = Eigen::ArrayXd::Zero(n);
  sums.at_or_above_edge.assign(s.udi_edges_lux.size(), Eigen::ArrayXd::Zero(n));
  const double inverse_threshold = 1.0 / s.da_threshold_lux;
  Eigen::ArrayXd column(n);
  double* e = column.data();
  for (Eigen::Index j : columns) {
    widen(m.col(j).data(), n, e);
    double* sum = sums.illuminance.data();
    double* continuous = sums.continuous.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      sum[i] += e[i];
      continuous[i] += std::min(e[i] * inverse_threshold, 1.0);
    }
    count_at_or_above(e, n, s.da_threshold_lux, sums.at_threshold.data());
    for (size_t k = 0; k < s.udi_edges_lux.size(); ++k)
      count_at_or_above(e, n, s.udi_edges_lux[k], sums.at_or_above_edge[k].data());
    count_above(e, n, s.udi_edges_lux.back(), sums.above_last_edge.data());
  }
  return sums;
}

template <class Matrix>
Eigen::VectorXi hours_above(const Matrix& m, const std::vector<Eigen::Index>& columns, double threshold) {
  const Eigen::Index n = m.rows();
  Eigen::ArrayXd column(n), count = Eigen::ArrayXd::Zero(n);
  for (Eigen::Index j : columns) {
    widen(m.col(j).data(), n, column.data());
    count_above(column.data(), n, threshold, count.data());
  }
  return count.matrix().cast<int>();
}

double weighted_mean(const Eigen::VectorXd& w, const Eigen::VectorXd& v) { return w.dot(v) / w.sum(); }

// The EN 17037 daylight hours and where they came from.
template <class Matrix>
std::vector<char> daylight_hour_flags(const Matrix& m, const AnnualMetricInputs& in, const Eigen::VectorXd& w,
                                      std::string& basis) {
  const size_t hours = static_cast<size_t>(m.cols());
  if (!in.daylight_hours.empty()) {
    if (in.daylight_hours.size() != hours)
      refuse("daylight_hours has " + std::to_string(in.daylight_hours.size()) + " flags for " +
             std::to_string(hours) + " hours");
    for (size_t j = 0; j < hours; ++j)
      if (in.daylight_hours[j] != 0 && in.daylight_hours[j] != 1)
        refuse("daylight_hours[" + std::to_string(j) + "] = " + std::to_string(int(in.daylight_hours[j])) +
               " must be 0 or 1");
    if (std::count(in.daylight_hours.begin(), in.daylight_hours.end(), char(1)) == 0)
      refuse("daylight_hours selects no hour");
    basis = "given";
    return in.daylight_hours;
  }
  if (hours < 2)
    refuse("EN 17037 needs at least 2 hours to take the half with the most daylight, has " + std::to_string(hours));
  if (!in.external_horizontal_illuminance.empty()) {
    if (in.external_horizontal_illuminance.size() != hours)
      refuse("external_horizontal_illuminance has " + std::to_string(in.external_horizontal_illuminance.size()) +
             " values for " + std::to_string(hours) + " hours");
    basis = "external illuminance";
    return en17037_daylight_hours(in.external_horizontal_illuminance);
  }
  // Without the weather: rank the hours by the room's own area-mean illuminance.
  std::vector<double> interior(hours);
  const double total = w.sum();
  for (size_t j = 0; j < hours; ++j)
    interior[j] = w.dot(m.col(static_cast<Eigen::Index>(j)).template cast<double>()) / total;
  basis = "interior illuminance (approximation)";
  return en17037_daylight_hours(interior);
}

template <class Matrix>
En17037Result en17037(const Matrix& m, const AnnualMetricInputs& in, const Eigen::VectorXd& w,
                      const AnnualMetricSettings& s) {
  En17037Result r;
  r.openings = s.en17037_openings;
  const std::vector<char> daylight = daylight_hour_flags(m, in, w, r.daylight_hours_basis);
  const bool horizontal = s.en17037_openings == DaylightOpenings::Horizontal;
  const double target_area = horizontal ? kEnTargetAreaFractionHorizontal : kEnTargetAreaFractionVertical;
  const size_t levels = s.en17037_levels.size();
  std::vector<int> target_hours(levels, 0), minimum_hours(levels, 0);
  const double total = w.sum();
  const Eigen::Index n = m.rows();
  Eigen::ArrayXd column(n);
  const double* e = column.data();
  for (size_t j = 0; j < daylight.size(); ++j) {
    if (!daylight[j]) continue;
    ++r.daylight_hours;
    widen(m.col(static_cast<Eigen::Index>(j)).data(), n, column.data());
    for (size_t l = 0; l < levels; ++l) {
      const En17037Level& level = s.en17037_levels[l];
      if (area_at_or_above(e, w.data(), n, level.target_lux) / total >= target_area) ++target_hours[l];
      if (!horizontal && area_at_or_above(e, w.data(), n, level.minimum_target_lux) / total >= kEnMinimumAreaFraction)
        ++minimum_hours[l];
    }
  }
  r.level_reached = "none";
  bool all_lower_met = true;
  for (size_t l = 0; l < levels; ++l) {
    En17037LevelResult lr;
    lr.level = s.en17037_levels[l];
    lr.target_hours_fraction = double(target_hours[l]) / r.daylight_hours;
    lr.target_met = lr.target_hours_fraction >= s.en17037_time_fraction;
    lr.minimum_hours_fraction = horizontal ? kNaN : double(minimum_hours[l]) / r.daylight_hours;
    lr.minimum_met = horizontal || lr.minimum_hours_fraction >= s.en17037_time_fraction;
    lr.met = lr.target_met && lr.minimum_met;
    all_lower_met = all_lower_met && lr.met;
    if (all_lower_met) r.level_reached = lr.level.name;
    r.levels.push_back(lr);
  }
  return r;
}

template <class Matrix>
AnnualMetrics compute(const Matrix& m, const AnnualMetricInputs& in, const AnnualMetricSettings& s,
                      const Matrix* direct) {
  check_settings(s);
  if (m.rows() < 1 || m.cols() < 1)
    refuse("illuminance is " + std::to_string(m.rows()) + " x " + std::to_string(m.cols()) +
           ": it needs at least one sensor (row) and one hour (column)");
  if (static_cast<Eigen::Index>(in.hours.size()) != m.cols())
    refuse("hours has " + std::to_string(in.hours.size()) + " stamps for " + std::to_string(m.cols()) +
           " illuminance columns");
  if (direct && (direct->rows() != m.rows() || direct->cols() != m.cols()))
    refuse("direct_illuminance is " + std::to_string(direct->rows()) + " x " + std::to_string(direct->cols()) +
           ", illuminance is " + std::to_string(m.rows()) + " x " + std::to_string(m.cols()));
  check_stamps(in.hours);
  check_illuminance(m, "illuminance", in.hours);
  if (direct) check_illuminance(*direct, "direct_illuminance", in.hours);
  const Eigen::VectorXd w = sensor_weights(in.sensor_areas_m2, m.rows());
  const std::vector<Eigen::Index> columns = occupied_columns(in.hours, s);

  AnnualMetrics r;
  r.sensors = static_cast<int>(m.rows());
  r.hours = static_cast<int>(m.cols());
  r.occupied_hours = static_cast<int>(columns.size());
  const double hours = r.occupied_hours;
  const OccupiedSums sums = occupied_sums(m, columns, s);
  r.mean_illuminance_lux = sums.illuminance.matrix() / hours;
  r.daylight_autonomy = sums.at_threshold.matrix() / hours;
  r.continuous_daylight_autonomy = sums.continuous.matrix() / hours;
  r.space_mean_illuminance_lux = weighted_mean(w, r.mean_illuminance_lux);
  r.space_daylight_autonomy = weighted_mean(w, r.daylight_autonomy);
  r.space_continuous_daylight_autonomy = weighted_mean(w, r.continuous_daylight_autonomy);

  r.udi = udi_bands(s.udi_edges_lux);
  const size_t k = s.udi_edges_lux.size();
  for (size_t b = 0; b <= k; ++b) {
    Eigen::ArrayXd count;
    if (b == 0)
      count = hours - sums.at_or_above_edge[0];
    else if (b < k - 1)
      count = sums.at_or_above_edge[b - 1] - sums.at_or_above_edge[b];
    else if (b == k - 1)
      count = sums.at_or_above_edge[b - 1] - sums.above_last_edge;
    else
      count = sums.above_last_edge;
    r.udi[b].sensor_fraction = count.matrix() / hours;
    r.udi[b].space_fraction = weighted_mean(w, r.udi[b].sensor_fraction);
  }

  const Eigen::VectorXd passes = (r.daylight_autonomy.array() >= s.sda_time_fraction).cast<double>().matrix();
  r.spatial_daylight_autonomy = weighted_mean(w, passes);
  for (double level : s.sda_pass_levels) r.sda_levels.push_back({level, r.spatial_daylight_autonomy >= level});

  if (direct) {
    r.has_ase = true;
    r.ase_sensor_hours = hours_above(*direct, columns, s.ase_threshold_lux);
    const Eigen::VectorXd overlit = (r.ase_sensor_hours.cast<double>().array() > s.ase_hours).cast<double>().matrix();
    r.annual_sunlight_exposure = weighted_mean(w, overlit);
    r.ase_passes = r.annual_sunlight_exposure <= s.ase_pass_limit;
  }

  r.en17037 = en17037(m, in, w, s);
  return r;
}

}  // namespace

std::vector<char> en17037_daylight_hours(const std::vector<double>& external, int count) {
  const int n = static_cast<int>(external.size());
  if (count < 0) count = n / 2;
  if (count < 1 || count > n)
    refuse("EN 17037 daylight hours: cannot take " + std::to_string(count) + " of " + std::to_string(n) + " hours");
  for (int j = 0; j < n; ++j)
    if (!(std::isfinite(external[j]) && external[j] >= 0.0))
      refuse("external_horizontal_illuminance[" + std::to_string(j) + "] = " + decimal_text(external[j], 10) +
             " lux must be finite and >= 0");
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  // Brighter first, then earlier: a strict total order, so the first `count` are one definite set.
  const auto brighter = [&](int a, int b) {
    return external[a] > external[b] || (external[a] == external[b] && a < b);
  };
  std::nth_element(order.begin(), order.begin() + (count - 1), order.end(), brighter);
  std::vector<char> flags(n, 0);
  for (int i = 0; i < count; ++i) flags[order[i]] = 1;
  return flags;
}

AnnualMetrics annual_metrics(const Eigen::MatrixXf& illuminance, const AnnualMetricInputs& inputs,
                             const AnnualMetricSettings& settings, const Eigen::MatrixXf* direct_illuminance) {
  return compute(illuminance, inputs, settings, direct_illuminance);
}

AnnualMetrics annual_metrics(const Eigen::MatrixXd& illuminance, const AnnualMetricInputs& inputs,
                             const AnnualMetricSettings& settings, const Eigen::MatrixXd* direct_illuminance) {
  return compute(illuminance, inputs, settings, direct_illuminance);
}

std::string AnnualMetricSettings::describe() const {
  std::ostringstream s;
  s << "occupied " << clock(occupied_start_hour) << "-" << clock(occupied_end_hour) << " local standard time; DA "
    << da_threshold_lux << " lx; sDA " << da_threshold_lux << "/" << 100.0 * sda_time_fraction << "%; UDI edges";
  for (double e : udi_edges_lux) s << " " << e;
  s << " lx; ASE " << ase_threshold_lux << " lx, > " << ase_hours << " h, limit " << percent_text(ase_pass_limit)
    << "; EN 17037 " << (en17037_openings == DaylightOpenings::Horizontal ? "horizontal" : "vertical/inclined")
    << " openings, levels";
  for (const En17037Level& l : en17037_levels) s << " " << l.name << " " << l.target_lux << "/" << l.minimum_target_lux;
  s << " lx over " << percent_text(en17037_time_fraction) << " of daylight hours";
  return s.str();
}

std::string AnnualMetrics::to_string() const {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1);
  s << sensors << " sensors, " << occupied_hours << " of " << hours << " hours occupied; mean "
    << space_mean_illuminance_lux << " lx; DA " << percent_text(space_daylight_autonomy) << ", cDA "
    << percent_text(space_continuous_daylight_autonomy) << "; UDI";
  for (const UdiBand& b : udi) s << " [" << b.name << " " << percent_text(b.space_fraction) << "]";
  s << "; sDA " << percent_text(spatial_daylight_autonomy);
  for (const PassLevel& p : sda_levels) s << (p.passed ? " passes " : " misses ") << percent_text(p.level);
  if (has_ase)
    s << "; ASE " << percent_text(annual_sunlight_exposure) << (ase_passes ? " (passes)" : " (fails)");
  else
    s << "; ASE not computed (no direct-sun illuminance)";
  s << "; EN 17037 over " << en17037.daylight_hours << " daylight hours (" << en17037.daylight_hours_basis << "):";
  for (const En17037LevelResult& l : en17037.levels) {
    s << " " << l.level.name << " target " << percent_text(l.target_hours_fraction);
    if (en17037.openings == DaylightOpenings::VerticalOrInclined)
      s << ", minimum " << percent_text(l.minimum_hours_fraction);
    s << (l.met ? " met;" : " not met;");
  }
  s << " level reached: " << en17037.level_reached;
  return s.str();
}

}  // namespace fenestra
