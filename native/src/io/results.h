#pragma once
// Files the CLI and Python read and write: contribution archives, openings, evaluations.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {

// The elements of the opening domain: index, panel, row, column and four corners (meters, in the
// scene's input coordinates).
nlohmann::json elements_json(const Scene& scene);

// What the tracer dropped (record_sink.h), as the outputs' "dropped": {"non_finite", "truncated_conditions"}.
nlohmann::json dropped_json(const DropCounts& dropped);

// Writes OUT.npz (arrays) and OUT.json (summary); `out` may end in .npz or be the stem.
// Returns the two paths written.
std::pair<std::string, std::string> write_contributions(const Scene& scene, const Contributions& c,
                                                        const std::string& out);

// Reads {"openings": [{"corners": [[x,y,z] x 4]}, ...]}; throws naming the file and opening.
// Corners are in the scene's input coordinates, read in double and returned in `frame` (the
// scene's local frame, Scene::site).
std::vector<OpeningInput> read_openings(const std::string& path, const SiteFrame& frame);
std::vector<OpeningInput> parse_openings(const nlohmann::json& j, const std::string& source, const SiteFrame& frame);
// The file read without a scene: in a frame around its own corners (SiteFrame::around), returned
// in `frame` (so that corners in site coordinates keep their precision).
std::vector<OpeningInput> read_openings_in_own_frame(const std::string& path, SiteFrame* frame);

// `horizontal_illuminance`: the sky's (and sun's) on an unobstructed horizontal surface, for
// daylight factors (sensors get "daylight_factor" in percent when it is positive). `warnings`: the
// setup checks' (study/setup_checks.h).
nlohmann::json evaluation_json(const SensorValues& values, size_t openings, int paths_per_sensor,
                               double horizontal_illuminance = 0.0, const std::vector<std::string>& warnings = {});
void write_json(const std::string& path, const nlohmann::json& j);

}  // namespace fenestra
