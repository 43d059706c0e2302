// fenestra._core: the setup checks (study/setup_checks.h) and the goals a solve needs.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "scene/scene.h"
#include "solve/goals.h"
#include "study/setup_checks.h"

namespace py = pybind11;
using namespace fenestra;

void bind_setup_checks(py::module_& m) {
  m.def(
      "check_setup",
      [](const Scene& scene, const std::string& command) {
        const SetupStage stage = setup_stage(command);
        std::vector<SetupWarning> found;
        {
          py::gil_scoped_release release;
          found = check_setup(scene, stage);
        }
        py::list out;
        for (const SetupWarning& w : found) {
          py::dict d;
          d["kind"] = setup_kind_name(w.kind);
          d["message"] = w.message;
          d["sensors"] = w.sensors;
          d["checked"] = w.checked;
          d["total"] = w.total;
          if (w.kind == SetupWarning::Kind::OpenRoom) {
            d["share"] = w.share;
            d["direction"] = std::vector<float>{w.direction.x(), w.direction.y(), w.direction.z()};
          }
          if (w.kind == SetupWarning::Kind::DomainSide) {
            py::list panels;
            for (const SetupWarning::Panel& p : w.panels) {
              py::dict q;
              q["panel"] = p.panel;
              q["groups"] = p.groups;
              q["seen_from_outside"] = p.seen_from_outside;
              q["on_room_side"] = p.on_room_side;
              panels.append(q);
            }
            d["panels"] = panels;
          }
          out.append(d);
        }
        return out;
      },
      py::arg("scene"), py::arg("command") = "solve",
      "The setup checks for `command` (\"solve\", \"contributions\" or \"evaluate\"): a list of dicts with "
      "\"kind\", \"message\", \"sensors\", \"checked\", \"total\" and the kind's figures (docs/outputs.md).");
  m.def("require_goals", &require_goals, py::arg("scene"),
        "Raises ValueError when no sensor has a goal and there is no climate goal (a solve would trace for nothing).");
}
