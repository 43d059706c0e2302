#pragma once
// The contributions of any scene: a climate sky's traced as unit sources through its annual pass
// (trace/contributions.h's SourcedPass), so that the records hold daylight coefficients beside
// their values under the mean sky of the occupied hours; other skies' as they are.
#include "trace/contributions.h"

namespace fenestra {

// With `transport` false, T is left empty (a records-only pass: the edges of thick walls).
// `sensors`: only that block of the scene's sensors (a shard); the rows and records are theirs, in
// order, and equal those of the whole scene's pass bit for bit.
Contributions compute_contributions(const Scene& scene, Progress* progress = nullptr, bool transport = true,
                                    SensorRange sensors = {});

}  // namespace fenestra
