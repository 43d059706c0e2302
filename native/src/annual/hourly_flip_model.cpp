#include "annual/hourly_flip_model.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include "annual/annual_records.h"
#include "daylight/annual_metrics.h"
#include "util/cost_error.h"
#include "util/memory_limit.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr size_t kPollPaths = 4096;

bool is_occupied(const HourStamp& h, const AnnualMetricSettings& s) {
  return h.clock_hour >= s.occupied_start_hour && h.clock_hour < s.occupied_end_hour;
}

// One path's light per source (unit coefficients; the sun straight to the sensor left out: the
// exact hourly sun replaces it) when the domain is open where `open` says.
template <typename Open>
void add_path_sources(const SensorRecord& r, size_t p, Open open, double sign, double* row) {
  for_each_counting_event_in_region(r, p, [&](int32_t k, const CellPoint&) { return open(k); }, [&](uint32_t e) {
    const uint16_t source = r.event_sources[e];
    if (!(source & AnnualSources::kDirect)) row[source] += sign * r.event_coefficients[e];
  });
}

// A sensor's daylight coefficients: for S, and for each element S's flip of it changes.
struct SensorCoefficients {
  Eigen::VectorXd base;             // sources
  std::vector<int32_t> elements;    // touched, sorted
  Eigen::MatrixXd flips;            // touched x sources: change when that element flips
};

bool is_excluded(const std::vector<uint8_t>& excluded, int32_t k) {
  return static_cast<size_t>(k) < excluded.size() && excluded[k];
}

// Adds to `out` the elements the records' paths meet, but the excluded; sorted and distinct.
void add_reach(const SensorRecord& r, const std::vector<uint8_t>& excluded, std::vector<int32_t>* out) {
  std::vector<int32_t> elements;
  for (size_t p = 0; p < r.path_count(); ++p) {
    path_elements(r, p, &elements);
    for (int32_t k : elements)
      if (!is_excluded(excluded, k)) out->push_back(k);
  }
  std::sort(out->begin(), out->end());
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

// The elements a sensor's paths meet, but the excluded (sorted): its coefficients' flips.
std::vector<int32_t> path_reach(const SensorRecord& r, const std::vector<uint8_t>& excluded) {
  std::vector<int32_t> touched;
  add_reach(r, excluded, &touched);
  return touched;
}

// `touched`: path_reach(r), or empty without the flips.
SensorCoefficients sensor_coefficients(const SensorRecord& r, const std::vector<uint8_t>& about, int sources,
                                       const std::vector<int32_t>& touched, bool with_flips,
                                       const Progress* progress) {
  SensorCoefficients out;
  out.base = Eigen::VectorXd::Zero(sources);
  out.elements = touched;
  out.flips = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched.size()), sources);
  Eigen::VectorXd path_base(sources), flipped(sources);
  std::vector<int32_t> elements;
  for (size_t p = 0; p < r.path_count(); ++p) {
    if (progress && p % kPollPaths == 0 && progress->cancelled()) return out;
    if (with_flips) path_elements(r, p, &elements);
    path_base.setZero();
    add_path_sources(r, p, [&](int32_t k) { return about[k] != 0; }, 1.0, path_base.data());
    out.base += path_base;
    for (int32_t flip : elements) {
      const auto at = std::lower_bound(touched.begin(), touched.end(), flip);
      if (at == touched.end() || *at != flip) continue;  // excluded
      flipped = -path_base;
      add_path_sources(r, p, [&](int32_t k) { return (about[k] != 0) != (k == flip); }, 1.0, flipped.data());
      out.flips.row(at - touched.begin()) += flipped.transpose();
    }
  }
  const double n = static_cast<double>(std::max<size_t>(1, r.path_count()));
  out.base /= n;
  out.flips /= n;
  return out;
}

// Lux per column from coefficients per source: the patches through the sky matrix's columns, the
// sun clusters' reflected light at each sunny column's cluster.
class ColumnSky {
 public:
  ColumnSky(const AnnualRecords& a, const HourlyColumns& columns) : annual_(a) {
    const SkyMatrix& sky = *a.climate->sky;
    std::vector<int> day_column(sky.hours.size(), -1);
    for (size_t j = 0; j < a.day_hours.size(); ++j) day_column[a.day_hours[j]] = static_cast<int>(j);
    const Eigen::Index n = static_cast<Eigen::Index>(columns.hour.size());
    patches_.setZero(a.sources.patch_count, n);
    for (Eigen::Index c = 0; c < n; ++c) {
      const int h = columns.hour[c];
      if (day_column[h] >= 0) patches_.col(c) = a.day_sky.col(day_column[h]);
      const int cluster = a.sources.suns.cluster_of_hour[h];
      if (sky.sun_normal_illuminance[h] > 0.0f && cluster >= 0)
        sun_.push_back({static_cast<int>(c), a.sources.sun_source(cluster), sky.sun_normal_illuminance[h]});
    }
  }

  // rows of `coefficients` (x sources) -> rows x columns, lux.
  Eigen::MatrixXf lux(const Eigen::MatrixXd& coefficients) const {
    Eigen::MatrixXf out = coefficients.leftCols(annual_.sources.patch_count).cast<float>() * patches_;
    for (const Sun& s : sun_) out.col(s.column) += coefficients.col(s.source).cast<float>() * s.lux;
    return out;
  }

 private:
  struct Sun {
    int column, source;
    float lux;
  };
  const AnnualRecords& annual_;
  Eigen::MatrixXf patches_;  // patches x columns, cd/m^2
  std::vector<Sun> sun_;
};

}  // namespace

HourlyColumns hourly_columns(const AnnualRecords& annual, bool en17037) {
  const SkyMatrix& sky = *annual.climate->sky;
  HourlyColumns out;
  std::vector<char> daylight;
  if (en17037) daylight = en17037_daylight_hours(sky.diffuse_horizontal_lux);
  std::vector<char> lit(sky.hours.size(), 0);
  for (int h : annual.day_hours) lit[h] = 1;
  for (int pass = 0; pass < 2; ++pass)  // the occupied hours first
    for (size_t h = 0; h < sky.hours.size(); ++h) {
      const bool occupied = is_occupied(sky.hours[h], annual.metric_settings);
      const bool day = en17037 && daylight[h];
      if (pass == 0) out.occupied_hours += occupied, out.daylight_hours += day;
      if (!lit[h] || occupied != (pass == 0) || !(occupied || day)) continue;
      out.hour.push_back(static_cast<int>(h));
      out.occupied.push_back(occupied);
      out.daylight.push_back(day);
    }
  return out;
}

int HourlyColumns::occupied_columns() const {
  return static_cast<int>(std::count(occupied.begin(), occupied.end(), 1));
}

int FlipChange::position(int32_t row) const {
  const auto at = std::lower_bound(rows.begin(), rows.end(), row);
  return at != rows.end() && *at == row ? static_cast<int>(at - rows.begin()) : -1;
}

void add_flip(const FlipChange& change, float sign, HourlyMatrix* total) {
  for (size_t i = 0; i < change.rows.size(); ++i) {
    if (sign > 0.0f) total->row(change.rows[i]) += change.values.row(static_cast<Eigen::Index>(i));
    else total->row(change.rows[i]) -= change.values.row(static_cast<Eigen::Index>(i));
  }
}

size_t HourlyFlipModel::memory_bytes() const {
  size_t bytes = sizeof(float) * (total.size() + direct.size());
  for (const auto& m : flip_total) bytes += sizeof(float) * m.values.size() + sizeof(int32_t) * m.rows.size();
  for (const auto& d : flip_direct) bytes += sizeof(DirectChange) * d.capacity();
  return bytes;
}

double hourly_flip_model_bytes(double rows, double columns, double pairs) {
  return 4.0 * columns * (pairs + 2.0 * rows) + 4.0 * pairs;
}

namespace {

// A row's reach: the elements its paths meet (`touched`) and those its sensor's sun rays cross, but
// the excluded, sorted.
std::vector<int32_t> row_reach(const Contributions& c, int sensor, const std::vector<int32_t>& touched,
                               const std::vector<uint8_t>& excluded) {
  std::vector<int32_t> elements = touched;
  add_reach(c.annual->direct[sensor], excluded, &elements);
  return elements;
}

// `reached`: the (element, row) pairs whose changes the model keeps.
void check_model_fits(size_t rows, size_t columns, size_t reached) {
  const double bytes =
      hourly_flip_model_bytes(static_cast<double>(rows), static_cast<double>(columns), static_cast<double>(reached));
  const MemoryLimit limit = memory_limit();
  if (bytes > 0.8 * static_cast<double>(limit.bytes))
    throw CostError(memory_refusal("the climate goals' hourly model (" + std::to_string(rows) + " sensors x " +
                                       std::to_string(columns) + " hours, and " + std::to_string(reached) +
                                       " changes of a sensor's year by an element's flip, 4 bytes an hour)",
                                   bytes, bytes, limit,
                                   "use a larger element_size, fewer sensors in the climate goals, or a shorter "
                                   "occupied period"));
}

HourlyFlipModel build_model(const Contributions& c, const std::vector<uint8_t>& about, const std::vector<int>& rows,
                            const HourlyColumns& columns, bool with_flips, const Progress* progress,
                            const std::vector<uint8_t>& excluded) {
  if (!c.annual) throw std::invalid_argument("climate goals need the contributions of a climate sky");
  if (about.size() != c.element_count())
    throw std::invalid_argument("open-element mask has " + std::to_string(about.size()) + " entries, expected " +
                                std::to_string(c.element_count()));
  const AnnualRecords& annual = *c.annual;
  const int sources = annual.sources.count();
  const Eigen::Index n_rows = static_cast<Eigen::Index>(rows.size());
  const Eigen::Index n_columns = static_cast<Eigen::Index>(columns.hour.size());
  HourlyFlipModel m;
  m.about = about;
  m.rows = rows;
  m.columns = columns;

  // The rows each element reaches: the sensors whose paths meet it, and those whose sun rays cross it.
  std::vector<std::vector<int32_t>> touched(rows.size());
  m.flip_total.resize(c.element_count());
  m.flip_direct.resize(c.element_count());
  size_t reached = 0;
  if (with_flips) {
    tbb::parallel_for(size_t(0), rows.size(), [&](size_t r) { touched[r] = path_reach(c.records[rows[r]], excluded); });
    for (size_t r = 0; r < rows.size(); ++r) {
      const std::vector<int32_t> elements = row_reach(c, rows[r], touched[r], excluded);
      for (int32_t k : elements) m.flip_total[k].rows.push_back(static_cast<int32_t>(r));  // ascending
      reached += elements.size();
    }
  }
  check_model_fits(rows.size(), columns.hour.size(), reached);

  m.total.setZero(n_rows, n_columns);
  m.direct.setZero(n_rows, n_columns);
  for (FlipChange& f : m.flip_total) f.values.setZero(static_cast<Eigen::Index>(f.rows.size()), n_columns);

  std::vector<int> column_of_hour(annual.climate->sky->hours.size(), -1);
  for (Eigen::Index j = 0; j < n_columns; ++j) column_of_hour[columns.hour[j]] = static_cast<int>(j);
  const ColumnSky sky(annual, columns);
  std::mutex direct_lock;
  tbb::parallel_for(size_t(0), rows.size(), [&](size_t r) {
    if (progress && progress->cancelled()) return;
    // Each row's coefficients are made and spent here: only the threads' rows are held at once.
    const SensorCoefficients s =
        sensor_coefficients(c.records[rows[r]], about, sources, touched[r], with_flips, progress);
    const Eigen::Index row = static_cast<Eigen::Index>(r);
    m.total.row(row) = sky.lux(s.base.transpose());
    const Eigen::MatrixXf flips = sky.lux(s.flips);
    for (size_t t = 0; t < s.elements.size(); ++t) {
      FlipChange& f = m.flip_total[s.elements[t]];
      f.values.row(f.position(static_cast<int32_t>(r))) = flips.row(t);
    }
    // The sun straight to the sensor, at each sunny hour's exact position.
    const SensorRecord& d = annual.direct[rows[r]];
    std::vector<std::pair<int32_t, DirectChange>> changes;
    std::vector<int32_t> elements;
    for (size_t j = 0; j < d.path_count(); ++j) {
      const int hour = annual.sun_hours[j];
      const int column = column_of_hour[hour];
      if (column < 0) continue;
      const float sun = annual.climate->sky->sun_normal_illuminance[hour];
      const float factor = annual.direct_factor[rows[r]][j];
      auto value = [&](int32_t flip) {
        return factor * static_cast<float>(path_value_in_region(
                            d, j, [&](int32_t k, const CellPoint&) { return (about[k] != 0) != (k == flip); }));
      };
      const float base = value(-1) * sun;
      m.direct(row, column) = base;
      m.total(row, column) += base;
      if (with_flips) path_elements(d, j, &elements);
      for (int32_t k : elements) {
        if (is_excluded(excluded, k)) continue;
        const float change = value(k) * sun - base;
        if (change == 0.0f) continue;
        FlipChange& f = m.flip_total[k];
        f.values(f.position(static_cast<int32_t>(r)), column) += change;
        changes.push_back({k, {static_cast<int32_t>(row), column, change}});
      }
    }
    std::lock_guard<std::mutex> hold(direct_lock);
    for (const auto& [k, change] : changes) m.flip_direct[k].push_back(change);
  });
  if (progress) progress->throw_if_cancelled();
  // Sorted, so the model does not depend on which thread finished first.
  for (auto& list : m.flip_direct)
    std::sort(list.begin(), list.end(), [](const DirectChange& a, const DirectChange& b) {
      return a.row != b.row ? a.row < b.row : a.column < b.column;
    });
  return m;
}

}  // namespace

std::vector<size_t> hourly_flip_model_reach(const Contributions& c, const std::vector<int>& rows,
                                            const std::vector<uint8_t>& excluded) {
  if (!c.annual) throw std::invalid_argument("climate goals need the contributions of a climate sky");
  std::vector<size_t> out(rows.size());
  tbb::parallel_for(size_t(0), rows.size(), [&](size_t r) {
    out[r] = row_reach(c, rows[r], path_reach(c.records[rows[r]], excluded), excluded).size();
  });
  return out;
}

HourlyFlipModel hourly_flip_model(const Contributions& c, const std::vector<uint8_t>& about,
                                  const std::vector<int>& rows, const HourlyColumns& columns,
                                  const Progress* progress, const std::vector<uint8_t>& excluded) {
  return build_model(c, about, rows, columns, true, progress, excluded);
}

HourlyFlipModel hourly_state(const Contributions& c, const std::vector<uint8_t>& open, const std::vector<int>& rows,
                             const HourlyColumns& columns, const Progress* progress) {
  return build_model(c, open, rows, columns, false, progress, {});
}

}  // namespace fenestra
