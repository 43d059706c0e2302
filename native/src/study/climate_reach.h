#pragma once
// How many elements each climate-goal sensor's rows of the hourly model will hold, estimated
// before any path is traced (docs/cost.md, "Climate goals"). The model keeps an element's change
// of a sensor's year only where the sensor's paths met the element: on a floor of closed rooms, a
// room's own facade. The estimate counts the elements a sensor sees with the whole domain open
// (light reaches an element the sensor sees at the first bounce, and walls hide the others), times
// kClimateReachMargin for what only bounces reach (a door, an element behind a jamb).
#include <vector>

namespace fenestra {

struct Scene;

// Measured: the model's (element, sensor) pairs against the seen elements, 1 024 paths per sensor
// (docs/cost.md): 1.00 on the office floor (closed rooms with doors), ...
inline constexpr double kClimateReachMargin = 1.25;

// Per sensor of the scene, the elements of the opening domain its rows are estimated to hold (the
// seen elements times the margin, at most the domain's elements); 0 for sensors no climate goal
// looks at. One shadow ray per (goal sensor, element), on all threads.
std::vector<double> climate_reach(const Scene& scene);

}  // namespace fenestra
