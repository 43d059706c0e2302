#pragma once
// Checks of a study before it is traced: setups that run, but whose answer is not the one the user
// means (docs/outputs.md, "Setup warnings"). The command line, Python and the Blender add-on run
// these same checks; each front end words them for its user from the figures kept here.
//
// - All goals 0: the solve opens nothing and reports a perfect 0 % error.
// - Sensors outdoors, or outside every room: they see the sky in most directions, so no opening
//   changes their light much and their error stays large.
// - An open room: sensors that see the sky through gaps that are not opening domain (a missing
//   roof, an existing window); the light through them counts toward the goals.
// - Sensors facing downward: a sensor measures the light arriving on the side its normal points
//   to, so a sensor grid with flipped normals measures the floor's light.
// - Domain panels seen from the side the solver does not take for the room: the solver takes the
//   side of a flat panel's plane where most sensors are for its room; when the sensors that see
//   the panel are on the other side, a thick wall is measured and cut on the wrong side.
// - Sensors on the opening domain: within kNearSurface of a domain face that cuts through their
//   hemisphere (a grid whose edge rows lie in the window wall's plane). Half their view is the
//   opening itself: the records and a real cut disagree there by orders of magnitude.
// - Sensors on a surface: the same within kNearSurface of any other face (a wall, a column, a
//   ceiling); a floor or table under an upward sensor, parallel to it, is where sensors belong.
//
// Only geometry is looked at: rays against the scene's triangles with every element closed, a
// few dozen per sensor on at most kMaxCheckedSensors sensors (evenly spaced through the scene's
// order), so the checks take a fraction of a second. Positions are the scene's as loaded.
#include <string>
#include <vector>

#include "math/vec.h"

namespace fenestra {

struct Scene;

// What a study is checked for: a solve (every check), contributions (the geometric checks: they
// are a solve's input), or an evaluation of given openings (evaluate, annual: downward sensors and
// the domain's sides, which change what is measured; an open room or sensors outdoors are measured
// as they are).
enum class SetupStage { Solve, Contributions, Evaluate };

struct SetupWarning {
  enum class Kind { ZeroGoals, Outdoors, OpenRoom, Downward, DomainSide, OnDomain, NearSurface };
  Kind kind = Kind::ZeroGoals;
  std::string message;        // in the scene file's words, naming the first few sensors and their positions
  std::vector<int> sensors;   // the sensors it is about (in scene order)
  size_t checked = 0;         // sensors looked at (Outdoors, OpenRoom: the rays' sample; else all)
  size_t total = 0;           // sensors in the scene
  // OpenRoom: the share of their directions that reach the sky, on average, and the escaping
  // directions' mean (unit): where the gap is.
  double share = 0.0;
  Vec3 direction = Vec3::Zero();
  // DomainSide: per panel, the sensors that see it from outside (the side the solver does not take
  // for the room) and the sensors on the room's side of its plane.
  struct Panel {
    int panel = -1;
    std::vector<std::string> groups;  // its triangles' OBJ groups
    int seen_from_outside = 0, on_room_side = 0;
  };
  std::vector<Panel> panels;
};

inline constexpr size_t kMaxCheckedSensors = 10000;
inline constexpr float kNearSurface = 0.05f;  // meters: a sensor this close to a face lies on it

const char* setup_kind_name(SetupWarning::Kind kind);  // "zero_goals", "outdoors", ...
SetupStage setup_stage(const std::string& name);        // "solve", "contributions", "evaluate"

// Every check that applies to `stage`, in the order above; empty when the setup looks sound.
std::vector<SetupWarning> check_setup(const Scene& scene, SetupStage stage);

// The warnings' messages; with `strict`, throws std::invalid_argument listing them when there are any
// (--strict, strict=True): "scene 's': setup checks (strict): ...".
std::vector<std::string> setup_messages(const Scene& scene, const std::vector<SetupWarning>& warnings, bool strict);

}  // namespace fenestra
