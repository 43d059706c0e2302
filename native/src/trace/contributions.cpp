#include "trace/contributions.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "trace/parallel.h"
#include "trace/path_tracer.h"
#include "trace/replicates.h"
#include "trace/transport_matrix.h"
#include "util/release_in_background.h"

namespace fenestra {
namespace {


struct Touched {
  int element;
  double light_alone = 0.0;  // light whose shadow rays cross only this element (before it escapes)
  int escape_event = -1;     // first escape event through this element
  int escape_end = -1;       // the event after its last part
  double through = 0.0;      // its value and its parts' that need no other element open
};

// Per-path analysis: E's row, A, T and the closed / all-open values from the event list.
void analyse_sensor(const SensorRecord& rec, size_t sensor, size_t elements, Contributions* out,
                    const Progress* progress = nullptr) {
  const size_t n_paths = rec.path_count();
  std::vector<double> e_sum(elements * kReplicates, 0.0), a_sum(elements, 0.0);
  ReplicateSums closed, open;
  std::vector<Touched> touched;
  std::vector<double> base_suffix, all_suffix;
  const std::vector<uint8_t> all_open_mask(elements, 1);
  for (size_t p = 0; p < n_paths; ++p) {
    if (cancelled_at(progress, p)) progress->throw_if_cancelled();  // a sensor's record may be huge
    const uint32_t b = rec.path_begin[p], e = rec.path_begin[p + 1];
    const size_t m = e - b;
    base_suffix.assign(m + 1, 0.0);
    all_suffix.assign(m + 1, 0.0);
    for (size_t j = m; j-- > 0;) {
      const PathEvent& ev = rec.events[b + j];
      base_suffix[j] = base_suffix[j + 1] + (ev.is_light() && !ev.own_condition() && !ev.stored_conditions() ? ev.value() : 0.0);
      all_suffix[j] = all_suffix[j + 1] + ev.value();
    }
    closed.add(p, base_suffix[0]);

    touched.clear();
    auto entry = [&](int k) -> Touched& {
      for (auto& t : touched)
        if (t.element == k) return t;
      touched.push_back(Touched{k});
      return touched.back();
    };
    int gathering = -1;  // the entry whose first escape the parts now read belong to
    rec.walk(p, [&](uint32_t i, const PathEvent& ev, const EventConditions& c) {
      const int j = static_cast<int>(i - b);
      if (ev.is_escape_part()) {  // taken with its escape
        if (gathering >= 0) {
          Touched& t = touched[gathering];
          if (c.open == 0) t.through += ev.value();
          t.escape_end = j + 1;
        }
        return true;
      }
      gathering = -1;
      if (ev.is_escape()) {
        Touched& t = entry(ev.element());
        if (t.escape_event < 0) {
          t.escape_event = j, t.escape_end = j + 1;
          t.through = ev.value();
          a_sum[ev.element()] += all_suffix[j + 1];
          gathering = static_cast<int>(&t - touched.data());
        }
        return true;
      }
      if (c.open == 0) return true;
      // Light that needs only element k open (k alone open closes all others: closed conditions hold).
      const int k = c[0];
      bool single = true;
      for (int n = 1; n < c.open; ++n) single = single && c[n] == k;
      for (int n = c.open; n < c.count(); ++n) single = single && c[n] != k;
      if (single) {
        Touched& t = entry(k);
        if (t.escape_event < 0) t.light_alone += ev.value();
      }
      return true;
    });
    open.add(p, path_value(rec, p, all_open_mask));
    for (const Touched& t : touched) {
      double c = t.light_alone;
      // Alone open, k's escape gathers the parts that need other elements closed, not open.
      if (t.escape_event >= 0) c += t.through - base_suffix[t.escape_end];
      e_sum[t.element * kReplicates + replicate_of(p)] += c;
    }
  }
  for (size_t k = 0; k < elements; ++k) {
    replicate_estimate(&e_sum[k * kReplicates], n_paths, &out->E(sensor, k), &out->E_stderr(sensor, k));
    out->A(sensor, k) = a_sum[k] / static_cast<double>(n_paths);
  }
  closed.estimate(n_paths, &out->closed.value[sensor], &out->closed.standard_error[sensor]);
  open.estimate(n_paths, &out->all_open.value[sensor], &out->all_open.standard_error[sensor]);
}

}  // namespace

namespace {

// Value and standard error per sensor, with path p's value from path_value_in_region(is_open).
template <typename IsOpen>
SensorValues evaluate_records(const std::vector<SensorRecord>& records, IsOpen is_open, const Progress* progress) {
  SensorValues out;
  out.value.resize(records.size());
  out.standard_error.resize(records.size());
  for_each_sensor(records.size(), progress, [&](size_t i) {
    ReplicateSums sums;
    for (size_t p = 0; p < records[i].path_count(); ++p) {
      if (cancelled_at(progress, p)) return;
      sums.add(p, path_value_in_region(records[i], p, is_open));
    }
    sums.estimate(records[i].path_count(), &out.value[i], &out.standard_error[i]);
  });
  return out;
}

}  // namespace

SensorValues Contributions::evaluate(const std::vector<uint8_t>& open, const Progress* progress) const {
  if (open.size() != element_count())
    throw std::invalid_argument("open-element mask has " + std::to_string(open.size()) + " entries, expected " +
                                std::to_string(element_count()));
  return evaluate_records(records, [&](int32_t k, const CellPoint&) { return open[k] != 0; }, progress);
}

SensorValues Contributions::evaluate(const OpenRegion& region, const Progress* progress) const {
  if (region.element_count() != element_count())
    throw std::invalid_argument("open region of a domain with " + std::to_string(region.element_count()) +
                                " elements, expected " + std::to_string(element_count()));
  return evaluate_records(records, [&](int32_t k, const CellPoint& p) { return region.is_open(k, p); }, progress);
}

size_t Contributions::memory_bytes() const {
  size_t bytes = sizeof(double) * (E.size() * 3 + T.size());
  for (const auto& r : records) bytes += r.memory_bytes();
  bytes += annual_bytes;
  return bytes;
}

Contributions trace_contributions(const Scene& scene, Progress* progress, bool transport, SensorRange range,
                                  SourcedPass* pass) {
  if (scene.climate && !pass)
    throw std::logic_error("a climate sky is traced as many sources: annual/annual_contributions.h");
  range = range.within(scene.sensors.size());
  const auto start = std::chrono::steady_clock::now();
  // A sky of many sources (a climate's patches and sun clusters) is traced as unit sources: the
  // records then hold daylight coefficients beside their values under the pass's design sky.
  PathTracer tracer(pass ? pass->traced_scene() : scene, {}, Mesh{}, pass ? pass->patches() : nullptr);
  tracer.check_sensors(range);
  if (scene.render.sampler == RenderSettings::Sampler::kSobol) tracer.prepare_portal_selection(scene.render.threads, range);

  const size_t sensors = range.size();
  const size_t elements = scene.domain.element_count();
  const int paths = scene.render.paths_per_sensor;
  const size_t tasks_per_sensor = path_tasks_per_sensor(paths);
  std::vector<SensorRecord> chunks(sensors * tasks_per_sensor);
  std::vector<DropCounts> dropped(chunks.size());  // per task: the same totals for any thread count
  Contributions c;
  try {
    if (progress) progress->start("tracing contribution paths", chunks.size());
    parallel_path_tasks(range, paths, scene.render.threads, progress, [&](const PathTask& task) {
      SensorRecord& rec = chunks[task.index];
      rec.sourced = pass != nullptr;
      task.for_each_path(scene.render, scene.render.seed, [&](size_t p, Rng& rng, const PathSamples* samples) {
        tracer.record_sensor_path(task.sensor, p, samples, rng, &rec, &dropped[task.index]);
      });
      if (pass) pass->chunk_traced(&rec);
    });

    c.paths_per_sensor = paths;
    c.records.resize(sensors);
    c.E.setZero(sensors, elements);
    c.E_stderr.setZero(sensors, elements);
    c.A.setZero(sensors, elements);
    c.closed.value.setZero(sensors), c.closed.standard_error.setZero(sensors);
    c.all_open.value.setZero(sensors), c.all_open.standard_error.setZero(sensors);
    if (progress) progress->start("assembling the contribution matrix", sensors);
    parallel_tasks(sensors, scene.render.threads, progress, [&](size_t i) {
      SensorRecord& rec = c.records[i];
      rec.reserve_for(&chunks[i * tasks_per_sensor], tasks_per_sensor);  // exact: no slack kept
      for (size_t t = 0; t < tasks_per_sensor; ++t) {
        if (progress && t % 64 == 0) progress->throw_if_cancelled();  // a sensor's paths may be many chunks
        rec.append(chunks[i * tasks_per_sensor + t]);
        chunks[i * tasks_per_sensor + t] = SensorRecord();  // frees the chunk
      }
      analyse_sensor(rec, i, elements, &c, progress);
    });
    if (transport) c.T = transport_matrix(c.records, elements, paths, scene.render.threads, progress);
    if (pass) pass->tracing_done(tracer, scene.render.threads, range, &c);
  } catch (const Cancelled&) {
    release_in_background(std::move(chunks));  // the path records: hundreds of megabytes
    release_in_background(std::move(c));
    throw;
  }
  for (const auto& r : c.records) c.events += r.events.size();
  for (const DropCounts& d : dropped) c.dropped += d;
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

}  // namespace fenestra
