#pragma once
// A shard's records as a worker holds them during a solve on a cluster (fenestra._core.RecordQueries):
// its LocalRecordQueries, and for climate goals the problem and its shard of the hourly model
// (bind_climate_shards.cpp).
#include <Eigen/Core>
#include <memory>

#include "scene/scene.h"
#include "solve/climate_problem.h"
#include "solve/climate_shard.h"
#include "solve/record_queries.h"
#include "trace/contributions.h"

namespace fenestra {

struct ShardQueries {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const Contributions> contributions;
  LocalRecordQueries queries;
  // The climate problem of the per-sensor goals last given (`climate_goals` as they were sent), and
  // the shard of its hourly model being searched (built on it: dropped before it).
  Eigen::VectorXd climate_goals;
  std::unique_ptr<ClimateProblem> climate_problem;
  std::unique_ptr<ClimateShard> climate_shard;
  ShardQueries(std::shared_ptr<const Scene> s, std::shared_ptr<const Contributions> c, SensorRange sensors)
      : scene(std::move(s)), contributions(std::move(c)), queries(*scene, *contributions, nullptr, sensors) {}
};

}  // namespace fenestra
