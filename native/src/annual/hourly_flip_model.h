#pragma once
// The year as the climate goals see it, for a set of open elements S and for every single flip
// of S: each goal sensor's illuminance at each hour that can matter (lit hours of the occupied
// period and EN 17037's daylight hours), exact for S from the path records, and the exact change
// each element's flip alone brings (its daylight coefficients per source, times the sky matrix).
// A state S' then reads V(S) + sum over the elements S' flips of their changes: exact for one
// flip, the linear model about S for more. See docs/solver.md, "Climate goals".
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "trace/contributions.h"

namespace fenestra {

class Progress;

// Rows x hours of lux, each sensor's year contiguous (the metrics scan a sensor's hours).
using HourlyMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The hours a model keeps (columns), as indices of the sky matrix's hours, with what each counts for.
// The occupied ones come first, so the occupied period is the first `occupied_columns()` columns.
struct HourlyColumns {
  std::vector<int> hour;
  std::vector<uint8_t> occupied;  // in the occupied period (DA, sDA, UDI, ASE, mean)
  std::vector<uint8_t> daylight;  // one of EN 17037's daylight hours
  int occupied_hours = 0;         // of the year, lit or not: the denominator of DA and UDI
  int daylight_hours = 0;         // EN 17037's daylight hours of the year
  int occupied_columns() const;
};

// The occupied hours with light and, when `en17037`, EN 17037's daylight hours (the half of the
// year with the most external diffuse light, as annual studies count them).
HourlyColumns hourly_columns(const AnnualRecords& annual, bool en17037);

// One entry of the direct sun's change when an element flips (sparse: a sun ray crosses few elements).
struct DirectChange {
  int32_t row = 0, column = 0;
  float lux = 0.0f;
};

// An element's flip: the change of `total` at the rows it reaches (the sensors whose paths, or sun
// rays, meet it; a floor's element reaches its own room's), each row's hours.
struct FlipChange {
  std::vector<int32_t> rows;  // model rows, ascending
  HourlyMatrix values;        // rows.size() x columns, lux
  bool empty() const { return rows.empty(); }
  // Position of `row` in `rows`, or -1.
  int position(int32_t row) const;
};

// Adds `change` to `total` (its rows), or with sign < 0 takes it off.
void add_flip(const FlipChange& change, float sign, HourlyMatrix* total);

struct HourlyFlipModel {
  std::vector<uint8_t> about;  // S, per element
  std::vector<int> rows;       // the sensors, as scene indices
  HourlyColumns columns;
  HourlyMatrix total, direct;  // rows x columns, lux: every light, and the sun straight to the sensor
  // Per element: the change of `total` when it alone flips from S (empty: it changes nothing here),
  // and the part of that change that is direct sun.
  std::vector<FlipChange> flip_total;
  std::vector<std::vector<DirectChange>> flip_direct;
  size_t memory_bytes() const;
};

// Bytes a model of `rows` x `columns` holds when it keeps `pairs` (element, row) changes: the state's
// year and its direct sun, each change's hours and its row (4 bytes each). The sun's own changes,
// a few per sunny hour, are left out.
double hourly_flip_model_bytes(double rows, double columns, double pairs);

// Per row, the elements whose flips a model of these rows keeps (its sensor's paths meet them or
// its sun rays cross them, but the `excluded`): what the model will hold, counted from the records
// before it is built.
std::vector<size_t> hourly_flip_model_reach(const Contributions& c, const std::vector<int>& rows,
                                            const std::vector<uint8_t>& excluded = {});

// Throws CostError when the model would not fit in memory (util/memory_limit.h), naming the figure
// and what to reduce; std::invalid_argument without annual records. Polls `progress`.
// `excluded` (per element, or empty): elements whose flips the model leaves out (they change nothing
// in it: elements the constraints rule out).
HourlyFlipModel hourly_flip_model(const Contributions& c, const std::vector<uint8_t>& about,
                                  const std::vector<int>& rows, const HourlyColumns& columns,
                                  const Progress* progress = nullptr, const std::vector<uint8_t>& excluded = {});
// The same without the flips: the exact hourly illuminance of `open` alone (total and direct).
HourlyFlipModel hourly_state(const Contributions& c, const std::vector<uint8_t>& open, const std::vector<int>& rows,
                             const HourlyColumns& columns, const Progress* progress = nullptr);

}  // namespace fenestra
