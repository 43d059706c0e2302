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
  const HourlyMatrix& change = model_.flip_total[k];
  if (change.size() == 0) return;
  if (sign > 0.0f) year->total += change;
  else year->total -= change;
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
  std::vector<ClimateTally> out(elements.size());
  tbb::parallel_for(size_t(0), elements.size(), [&](size_t i) {
    const int k = elements[i];
    if (model_.flip_total[k].size() == 0 && model_.flip_direct[k].empty()) {
      out[i] = tally(year);  // the flip changes nothing at these sensors
      return;
    }
    Year flipped = year;
    flip(&flipped, k);
    out[i] = tally(flipped);
  });
  return out;
}

size_t ClimateShard::memory_bytes() const {
  size_t bytes = model_.memory_bytes();
  for (const Year& y : slots_) bytes += sizeof(float) * (y.total.size() + y.direct.size()) + y.open.size();
  return bytes;
}

}  // namespace fenestra
