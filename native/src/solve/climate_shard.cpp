#include "solve/climate_shard.h"

#include <set>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

namespace fenestra {

ClimateShard::ClimateShard(HourlyFlipModel part, std::vector<int> model_rows, const ClimateObjective& objective)
    : model_(std::move(part)), model_rows_(std::move(model_rows)), objective_(objective) {
  if (static_cast<Eigen::Index>(model_rows_.size()) != model_.total.rows())
    throw std::invalid_argument("climate shard: " + std::to_string(model_.total.rows()) + " rows of hours, " +
                                std::to_string(model_rows_.size()) + " model rows named");
  if (!objective_.needs_direct()) model_.direct.resize(0, 0);
}

const ClimateShard::Year& ClimateShard::settled(int slot) const {
  if (slot < 0 || static_cast<size_t>(slot) >= slots_.size() || !settled_[slot])
    throw std::invalid_argument("climate shard: slot " + std::to_string(slot) + " holds no settled state");
  return slots_[slot];
}

void ClimateShard::flip(Year* year, int k) const {
  // Away from the model's state the change adds; back toward it, it comes off again.
  const float sign = (year->open[k] != 0) == (model_.about[k] != 0) ? 1.0f : -1.0f;
  year->open[k] ^= 1;
  add_flip(model_.flip_total[k], sign, &year->total);
  if (year->direct.size())
    for (const DirectChange& d : model_.flip_direct[k]) year->direct(d.row, d.column) += sign * d.lux;
}

void ClimateShard::change_to(Year* year, const std::vector<uint8_t>& open) const {
  for (size_t k = 0; k < open.size(); ++k)
    if ((year->open[k] != 0) != (open[k] != 0)) flip(year, static_cast<int>(k));
}

std::vector<ClimateTally> ClimateShard::settle(const std::vector<ClimateRecipe>& batch) {
  // Recipes deriving from a slot written earlier in the batch are settled in order; a batch of
  // independent ones (a generation's children, from the parents' slots) in parallel.
  std::set<int> written;
  bool ordered = false;
  for (const ClimateRecipe& r : batch) {
    if (r.slot < 0) throw std::invalid_argument("climate shard: slot " + std::to_string(r.slot));
    if (r.open.size() != model_.about.size())
      throw std::invalid_argument("climate shard: a state of " + std::to_string(r.open.size()) + " elements for " +
                                  std::to_string(model_.about.size()));
    if (r.base != r.slot && written.count(r.base)) ordered = true;
    if (!written.insert(r.slot).second)
      throw std::invalid_argument("climate shard: slot " + std::to_string(r.slot) + " written twice in one batch");
    if (r.base != ClimateRecipe::kModelState && r.base != r.slot && !written.count(r.base)) settled(r.base);
    if (r.base == r.slot) settled(r.slot);
  }
  const size_t needed = static_cast<size_t>(*written.rbegin()) + 1;
  if (slots_.size() < needed) slots_.resize(needed), settled_.resize(needed, 0);
  std::vector<ClimateTally> out(batch.size());
  auto one = [&](size_t i) {
    const ClimateRecipe& r = batch[i];
    Year& to = slots_[r.slot];
    if (r.base == ClimateRecipe::kModelState) {
      to.open = model_.about;
      to.total = model_.total;
      to.direct = model_.direct;
    } else if (r.base != r.slot) {
      to = slots_[r.base];
    }
    change_to(&to, r.open);
    settled_[r.slot] = 1;
    out[i] = tally(to);
  };
  if (ordered) {
    for (size_t i = 0; i < batch.size(); ++i) one(i);
  } else {
    tbb::parallel_for(size_t(0), batch.size(), one);
  }
  return out;
}

std::vector<ClimateTally> ClimateShard::flip_tallies(int slot, const std::vector<int>& elements) const {
  const Year& year = settled(slot);
  for (int k : elements)
    if (k < 0 || static_cast<size_t>(k) >= year.open.size())
      throw std::invalid_argument("climate shard: element " + std::to_string(k) + " is not one of the " +
                                  std::to_string(year.open.size()));
  // Each flip changes the rows it reaches: their share of the state's tally is taken out and the
  // flipped rows' put in, computed as flip() computes them, so each tally equals a settled state's.
  const ClimateTally base = tally(year);
  const Eigen::Index columns = year.total.cols();
  std::vector<ClimateTally> out(elements.size());
  tbb::parallel_for(size_t(0), elements.size(), [&](size_t i) {
    const int k = elements[i];
    const FlipChange& change = model_.flip_total[k];
    const float sign = (year.open[k] != 0) == (model_.about[k] != 0) ? 1.0f : -1.0f;
    ClimateTally t = base;
    Eigen::Matrix<float, 1, Eigen::Dynamic> total(columns), direct(year.direct.size() ? columns : 0);
    const std::vector<DirectChange>& sun = model_.flip_direct[k];
    auto d = sun.begin();
    for (size_t p = 0; p < change.rows.size(); ++p) {
      const int32_t r = change.rows[p];
      const Eigen::Index at = static_cast<Eigen::Index>(p);
      if (sign > 0.0f) total = year.total.row(r) + change.values.row(at);
      else total = year.total.row(r) - change.values.row(at);
      const bool has_direct = direct.size() > 0;
      if (has_direct) direct = year.direct.row(r);
      for (; d != sun.end() && d->row <= r; ++d)  // sorted by row, then column
        if (d->row == r && has_direct) direct[d->column] += sign * d->lux;
      objective_.tally_row(&t, year.total.row(r).data(), has_direct ? year.direct.row(r).data() : nullptr,
                           model_rows_[r], true);
      objective_.tally_row(&t, total.data(), has_direct ? direct.data() : nullptr, model_rows_[r], false);
    }
    out[i] = std::move(t);
  });
  return out;
}

size_t ClimateShard::memory_bytes() const {
  size_t bytes = model_.memory_bytes();
  for (const Year& y : slots_) bytes += sizeof(float) * (y.total.size() + y.direct.size()) + y.open.size();
  return bytes;
}

}  // namespace fenestra
