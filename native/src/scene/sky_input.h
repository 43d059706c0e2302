#pragma once
// The scene file's "sky" section (docs/sky.md): a uniform sky, an environment map, a daylight sky
// (preetham, cie_clear, cie_overcast, perez) or a climate sky, read and built.
#include <nlohmann/json_fwd.hpp>

#include <filesystem>

#include "scene/scene.h"
#include "scene/scene_json.h"

namespace fenestra {

class Progress;  // util/progress.h

// Sets scene->sky, and for the daylight and climate skies scene->suns, scene->daylight and
// scene->climate; files it reads (a map, a weather file; relative to `base`) join
// scene->input_files. A daylight or climate sky's build reports to `progress` (may be null).
void parse_sky(const scene_json::ScenePath& sp, const nlohmann::json& j, const std::filesystem::path& base,
               Scene* scene, Progress* progress);

}  // namespace fenestra
