"""Evaluate: the openings where their cutters stand after the user moved them, inside Blender
(run by test_blender_addon.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_evaluate.py -- OUT_DIR

A real solve of the box room of addon_study.py; a cutter moved 0.5 m along the wall, or scaled,
is read back as its rectangle on the wall, path-traced, and the results change to values that
fenestra.evaluate gives for that rectangle (another seed, within the standard errors). A cutter
moved off the wall, or tilted out of it, and a curved opening's cutter once moved are refused
in plain words. The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import json
import os
import sys
import unittest

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_study  # noqa: E402  (the room, its sensor grid and settings)

OUT = addon_study.OUT
STEP = 0.5  # m along the wall


def study_file(name):
    return os.path.join(OUT, "study", name)


def solved():
    """The room solved with at most one opening at most 2 m wide; (its cutter, its corners)."""
    addon_study.reset()
    addon_study.study()
    c = bpy.context.scene.fenestra.solve.constraints
    c.max_openings, c.max_width = 1, 2.0
    assert bpy.ops.fenestra.solve_openings() == {'FINISHED'}
    result = load("result.json")
    assert len(result["openings"]) == 1, result["openings"]
    return bpy.data.objects["Fenestra Opening 001"], np.array(result["openings"][0]["corners"])


def achieved():
    return np.array([s.achieved for s in bpy.context.scene.fenestra.results.sensors])


def load(name):
    with open(study_file(name)) as f:
        return json.load(f)


def evaluated_openings():
    return load("openings.json")["openings"]


def evaluated_stderr():
    return np.array([s["stderr"] for s in load("evaluation.json")["sensors"]])


def refused():
    try:
        bpy.ops.fenestra.evaluate_openings()
    except RuntimeError as exc:  # bpy.ops raises on an ERROR report
        return str(exc)
    raise AssertionError("Evaluate was not refused")


class Evaluate(unittest.TestCase):
    def test_a_cutter_moved_along_the_wall(self):
        import fenestra
        cutter, corners = solved()
        before = achieved()
        step = STEP if corners[:, 0].max() + STEP <= addon_study.ROOM[0] else -STEP
        cutter.location.x += step
        self.assertEqual(bpy.ops.fenestra.evaluate_openings(), {'FINISHED'})
        moved = corners + [step, 0.0, 0.0]
        read = np.array(evaluated_openings()[0]["corners"])
        # The same rectangle, perhaps starting at another corner.
        self.assertTrue(np.allclose(np.sort(read, axis=0), np.sort(moved, axis=0), atol=1e-4), (read, moved))

        evaluation = load("evaluation.json")
        values = np.array([s["value"] for s in evaluation["sensors"]])
        stderr = np.array([s["stderr"] for s in evaluation["sensors"]])
        after = achieved()
        self.assertTrue(np.allclose(after, values))
        r = bpy.context.scene.fenestra.results
        self.assertTrue(r.evaluated)
        self.assertAlmostEqual(r.relative_rms, evaluation["error"]["relative_rms"], places=6)
        # The move changed the light, beyond the noise.
        self.assertGreater(np.max(np.abs(after - before) / np.maximum(stderr, 1e-9)), 5.0)

        # fenestra.evaluate on the moved rectangle, with other paths, agrees within standard errors.
        scene = fenestra.load_scene(study_file("scene.json"))
        scene.render.seed = 17
        check, check_stderr = fenestra.evaluate(scene, [moved])
        z = (values - check) / np.sqrt(stderr ** 2 + check_stderr ** 2)
        self.assertLess(np.mean(z ** 2), 3.0, z)
        self.assertLess(np.max(np.abs(z)), 5.0, z)

        # The study folder re-runs it: the same openings, the same seed, the same values.
        again, _ = fenestra.evaluate(fenestra.load_scene(study_file("scene.json")),
                                     fenestra.read_openings(study_file("openings.json")))
        self.assertTrue(np.allclose(again, values, rtol=1e-9, atol=1e-9))

    def test_a_scaled_cutter_is_a_wider_opening(self):
        cutter, corners = solved()
        cutter.scale.x = 0.5
        self.assertEqual(bpy.ops.fenestra.evaluate_openings(), {'FINISHED'})
        read = np.array(evaluated_openings()[0]["corners"])
        width = np.ptp(read[:, 0])
        self.assertAlmostEqual(width, np.ptp(corners[:, 0]) / 2, places=4)
        self.assertAlmostEqual(np.ptp(read[:, 2]), np.ptp(corners[:, 2]), places=4)
        self.assertTrue(np.allclose(read[:, 1], 0.0, atol=1e-6))  # on the wall

    def test_a_cutter_off_the_wall_is_refused(self):
        cutter, _ = solved()
        cutter.location.y += 1.0
        message = refused()
        self.assertIn("'Fenestra Opening 001' no longer lies flat across the opening domain", message)
        cutter.location.y -= 1.0
        cutter.rotation_euler.z = 0.5
        self.assertIn("'Fenestra Opening 001' no longer lies flat", refused())

    def test_a_curved_opening_is_read_where_the_solve_put_it(self):
        """A cutter kept as curved is read by its panel and parameter rectangle: unmoved, the
        values are those of the rectangle read from its box (within the noise: the box's corners
        are single precision); moved, it is refused."""
        cutter, _ = solved()
        self.assertEqual(bpy.ops.fenestra.evaluate_openings(), {'FINISHED'})
        by_corners, stderr = achieved(), evaluated_stderr()
        record = cutter["fenestra_opening"]
        record["curved"] = True
        self.assertEqual(bpy.ops.fenestra.evaluate_openings(), {'FINISHED'})
        solved_opening = load("result.json")["openings"][0]
        read = evaluated_openings()[0]
        self.assertEqual((read["panel"], read["parameter_rectangle"]),
                         (solved_opening["panel"], solved_opening["parameter_rectangle"]))
        z = (achieved() - by_corners) / np.sqrt(stderr ** 2 + evaluated_stderr() ** 2)
        self.assertLess(np.max(np.abs(z)), 4.0, z)
        cutter.location.x += STEP
        message = refused()
        self.assertIn("'Fenestra Opening 001' is on a curved part of the domain and was moved", message)

    def test_a_new_solve_replaces_the_evaluation(self):
        cutter, _ = solved()
        cutter.location.x += 0.1
        self.assertEqual(bpy.ops.fenestra.evaluate_openings(), {'FINISHED'})
        self.assertTrue(bpy.context.scene.fenestra.results.evaluated)
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertFalse(bpy.context.scene.fenestra.results.evaluated)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    addon_study.enable()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
