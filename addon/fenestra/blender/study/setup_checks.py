"""Checks of a study before it is solved, in the user's words: setups that solve, but whose answer
is not the one the user means. Each warning says how many sensors or faces it is about and what to
change.

- Objects left out because they are hidden (visibility.py): Blender's own concern, checked here.
- The rest are the native core's setup checks (fenestra.check_setup, native/src/study/
  setup_checks.h), the same that `fenestra solve` and fenestra.solve() run: all goals 0, sensors
  outdoors or outside every room, an open room (sensors that see the sky through gaps that are
  not opening domain), sensors facing downward, domain faces seen from the side the solver
  does not take for their room, and sensors lying on the opening domain or on another surface. The core finds them and counts them; this module only words them
  with the objects' names (the sensors and OBJ groups it names map to objects through the study).
"""

import json
import os
import tempfile

from . import visibility


def _of(count, total, checked):
    """'3 of 40 sensors', or '3 of the 400 sensors checked (of 9000)'."""
    if checked < total:
        return "%d of the %d sensors checked (of %d)" % (count, checked, total)
    return "%d of %d sensors" % (count, total)


def core_findings(study):
    """The core's setup checks on the exported study (export.build), loaded with a plain sky: the
    checks look at geometry and goals only, so a daylight or climate sky is not built for them (and
    climate goals, which need one, are left out: with them no goal is 'all 0')."""
    from ... import _core, cost
    scene = dict(study.scene)
    scene["sky"] = {"type": "uniform", "radiance": 1.0}
    goals = {k: v for k, v in scene.get("goals", {}).items() if k not in ("climate", "least_glazing")}
    if goals:
        scene["goals"] = goals
    else:
        scene.pop("goals", None)
    climate = bool(study.scene.get("goals", {}).get("climate"))
    with tempfile.TemporaryDirectory(prefix="fenestra_checks_") as directory:
        with open(os.path.join(directory, "scene.obj"), "w") as f:
            f.write(study.obj_text)
        with cost.loading(None, "evaluate"):  # the checks need no element matrices
            native = _core.Scene.from_json(json.dumps(scene), directory, "the study", _core.Progress())
        found = _core.check_setup(native, "solve")
    return [w for w in found if not (climate and w["kind"] == "zero_goals")]


def _zero_goals(study, finding):
    n = len(finding["sensors"])
    if "goals" in study.scene["sensors"]:
        return ("All %d painted goals are 0 ('fenestra_goal' black, or Scale 0): the solve opens nothing "
                "and reports 0 %% error. Paint the goals, or raise Scale" % n)
    return "All %d sensor goals are 0: the solve opens nothing and reports 0 %% error. Set a Goal above 0" % n


def _outdoors(study, finding):
    return ("%s are outdoors or outside every room (they see the sky in most directions): no opening changes "
            "their light much, so their error stays large. Move them into the rooms, or remove them"
            % _of(len(finding["sensors"]), finding["total"], finding["checked"]))


def _open_room(study, finding):
    z = finding["direction"][2]
    where = ("mostly upward: a missing roof or ceiling?" if z > 0.5 else
             "mostly downward: a missing floor?" if z < -0.5 else
             "mostly sideways: a missing wall, a door or window that is not opening domain?")
    return ("%s see the sky through gaps that are not opening domain (%.0f %% of their directions on average, %s): "
            "daylight through them counts toward the goals. Close the model there if the room is closed"
            % (_of(len(finding["sensors"]), finding["total"], finding["checked"]), 100 * finding["share"], where))


def _per_sensor_object(study, finding, text):
    """One warning per sensor object with sensors in the finding: text(n, count, name)."""
    found, warnings, start = set(finding["sensors"]), [], 0
    for name, count in study.sensor_objects:
        n = sum(1 for i in range(start, start + count) if i in found)
        start += count
        if n:
            warnings.append(text(n, count, name))
    return warnings


def _downward(study, finding):
    return _per_sensor_object(study, finding, lambda n, count, name: (
        "%d of %d sensors of '%s' face downward: a sensor measures the light on the side its normal points to, "
        "here the light from below. If they should face up, flip the normals of '%s' (Edit Mode: Mesh > Normals > "
        "Flip)" % (n, count, name, name)))


def _on_domain(study, finding):
    return _per_sensor_object(study, finding, lambda n, count, name: (
        "%d of %d sensors of '%s' lie on the opening domain (within 5 cm of it): half their view is the opening "
        "itself, so their light is nothing a person in the room would read and the solve chases it. Move them into "
        "the room, or make the grid again with Add Sensor Grid, which keeps sensors off the walls" % (n, count, name)))


def _near_surface(study, finding):
    return _per_sensor_object(study, finding, lambda n, count, name: (
        "%d of %d sensors of '%s' lie on a wall, ceiling or other surface (within 5 cm of it): part of their view "
        "is inside it, so their light depends on millimetres. Move them off every surface but the floor under them, "
        "or make the grid again with Add Sensor Grid" % (n, count, name)))


def _domain_side(study, finding):
    """One warning per object whose domain faces are seen from the side the solver does not take for
    their room: its flat parts (the core's panels), the most sensors that see one from that side, and
    the sensors on the room's side."""
    objects = {}
    for panel in finding["panels"]:
        names = {study.group_objects.get(g, g) for g in panel["groups"]} or {"the opening domain"}
        for name in sorted(names):
            o = objects.setdefault(name, [0, 0, 0])
            o[0] += 1
            o[1] = max(o[1], panel["seen_from_outside"])
            o[2] = max(o[2], panel["on_room_side"])
    return ["The domain faces of '%s' (%d flat part%s) are seen by %d sensors from one side, but %d of %d sensors "
            "lie on the other side of their plane, which the solver takes for the room: a thick wall would be "
            "measured and cut toward those sensors. Solve the rooms on either side as separate studies, or leave "
            "Wall Thickness at 0 with single-face walls" % (name, parts, "s" if parts > 1 else "", seen, room,
                                                            finding["total"])
            for name, (parts, seen, room) in objects.items()]


_WORDING = {"zero_goals": _zero_goals, "outdoors": _outdoors, "open_room": _open_room, "downward": _downward,
            "domain_side": _domain_side, "on_domain": _on_domain, "near_surface": _near_surface}


def worded(study, findings):
    """The core's findings in the user's words, in the core's order."""
    warnings = []
    for finding in findings:
        wording = _WORDING.get(finding["kind"])
        text = wording(study, finding) if wording else finding["message"]
        warnings += text if isinstance(text, list) else [text]
    return warnings


def hidden_objects(context):
    """Marked objects left out of the study because they are hidden (the others are in it)."""
    def left_out(count, what, name, reason):
        one = count == 1
        return ("The %d %s%s of '%s' %s on a hidden object (%s) and %s left out of the study"
                % (count, what, "" if one else "s", name, "is" if one else "are", reason, "is" if one else "are"))
    return ([left_out(faces, "domain face", obj.name, reason) for obj, faces, reason in visibility.hidden_domain(context)]
            + [left_out(n, "sensor", obj.name, reason) for obj, n, reason in visibility.hidden_sensors(context)])


def run(context, study):
    """Every check's warnings for an exported study (export.build)."""
    return hidden_objects(context) + worded(study, core_findings(study))
