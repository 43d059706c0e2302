"""The solve's life cycle, headless, inside Blender (run by test_blender_solve.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_solve.py -- OUT_DIR

Solve's refusals in Edit Mode and Vertex Paint; the study folder replaced only by a solve that
succeeds (a refused one leaves scene.json, scene.obj and result.json as they were, and files the
solve does not write are kept); the cost model's refusal of a study too large for the memory, in
the panel's words, with the element size that fits; the contributions kept for a re-solve when
only goals or solver settings change, and computed again when anything they depend on changes.
The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import hashlib
import os
import re
import sys
import time
import unittest

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import installed  # noqa: E402
sys.path.insert(0, os.path.join(HERE, "..", "..", "examples"))
import addon_study  # noqa: E402
import build_blend_examples as examples  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_solve_test"
addon_study.OUT = OUT


def study_dir():
    return bpy.path.abspath(bpy.context.scene.fenestra.solve.study_directory)


def folder_digest():
    """Every file of the study folder and its digest; the hidden staging folders beside it."""
    d = study_dir()
    files = {n: hashlib.sha256(open(os.path.join(d, n), "rb").read()).hexdigest() for n in sorted(os.listdir(d))}
    staging = sorted(n for n in os.listdir(os.path.dirname(d)) if n.startswith("."))
    return files, staging


def solve():
    """Solve Openings; (seconds, results)."""
    start = time.monotonic()
    assert bpy.ops.fenestra.solve_openings() == {'FINISHED'}
    return time.monotonic() - start, bpy.context.scene.fenestra.results


class Refusals(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def assert_poll_says(self, words):
        with self.assertRaises(RuntimeError) as failure:
            bpy.ops.fenestra.solve_openings()
        self.assertIn(words, str(failure.exception))

    def test_solve_needs_object_mode(self):
        room = addon_study.study()
        addon_study.select_only(room)
        bpy.ops.object.mode_set(mode='EDIT')
        self.assert_poll_says("Solve needs Object Mode")
        bpy.ops.object.mode_set(mode='OBJECT')
        addon_study.select_only(bpy.data.objects["Fenestra Sensors"])
        bpy.ops.object.mode_set(mode='VERTEX_PAINT')
        self.assert_poll_says("Solve needs Object Mode")
        bpy.ops.object.mode_set(mode='OBJECT')
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})

    def test_a_refused_solve_leaves_the_study_folder_and_the_model(self):
        addon_study.study()
        solve()
        with open(os.path.join(study_dir(), "sky.exr"), "w") as f:
            f.write("a previewed sky")  # not written by a solve: kept by every solve
        before, model = folder_digest(), addon_study.snapshot()
        solve_settings = bpy.context.scene.fenestra.solve
        solve_settings.paths = 2 ** 24  # the cost model refuses it, after the study is written
        with self.assertRaises(RuntimeError) as failure:
            bpy.ops.fenestra.solve_openings()
        message = str(failure.exception)
        for words in ("paths per sensor", "fewer paths", "Quality"):
            self.assertIn(words, message)
        for words in ("--max-memory", ".solving-", "scene.json"):
            self.assertNotIn(words, message)
        self.assertEqual(folder_digest(), before)
        self.assertEqual(addon_study.snapshot(), model)
        # A solve that succeeds replaces the study and keeps the rest.
        solve_settings.paths, solve_settings.seed = 512, 4
        solve()
        files, staging = folder_digest()
        self.assertEqual(staging, [])
        self.assertEqual(files["sky.exr"], before[0]["sky.exr"])
        self.assertNotEqual(files["scene.json"], before[0]["scene.json"])
        self.assertNotEqual(files["result.json"], before[0]["result.json"])

    def test_too_many_elements_for_the_memory_are_refused_with_the_size_that_fits(self):
        # 76 m² of wall at 0.04 m: 47 500 elements, whose matrix T alone needs 18 GB twice over.
        import fenestra
        if fenestra.available_memory()["bytes"] > 30e9:
            self.skipTest("this machine has the memory for it")
        room = addon_study.study()
        room.scale = (5.0, 1.0, 3.8 / addon_study.ROOM[2])  # a 20 x 4 x 3.8 m room
        solve_settings = bpy.context.scene.fenestra.solve
        solve_settings.element_size, solve_settings.paths = 0.04, 256
        with self.assertRaises(RuntimeError) as failure:
            bpy.ops.fenestra.solve_openings()
        message = str(failure.exception)
        for words in ("0.04 m gives about 47 500 elements", "GB", "available", "m or more", "Element Size"):
            self.assertIn(words, message)
        for words in ("--max-memory", ".solving-"):
            self.assertNotIn(words, message)
        suggested = float(re.search(r"([\d.]+) m or more", message).group(1))
        print("refused: %s" % message)
        self.assertGreater(suggested, 0.04)
        self.assertLessEqual(suggested, 0.1)
        # The size it names is accepted by the cost model (the solve itself is not run here).
        export = installed.blender("study.export")
        solve_settings.element_size = suggested
        staging = os.path.join(OUT, "suggested")
        path = export.build(bpy.context).write(staging)
        scene = fenestra.load_scene(path)
        self.assertTrue(fenestra.estimate_cost(scene, "solve")["fits"])


class Resolve(unittest.TestCase):
    """The contributions are kept between solves while what they depend on does not change."""

    def setUp(self):
        addon_study.reset()

    def assert_reused(self, reused):
        seconds, r = solve()
        self.assertEqual(r.seconds_contributions == 0.0, reused, r.seconds_contributions)
        return seconds

    def test_goals_and_solver_settings_reuse_them_the_rest_does_not(self):
        room = addon_study.study()
        f = bpy.context.scene.fenestra
        self.assert_reused(False)
        f.goals.level = 0.3
        self.assert_reused(True)
        f.solve.generations, f.solve.constraints.max_openings = 30, 1
        self.assert_reused(True)
        f.solve.element_size = 0.4
        self.assert_reused(False)
        f.sky.horizontal_illuminance = 20000.0
        self.assert_reused(False)
        room.data.vertices[6].co.z += 0.2  # a corner of the ceiling up
        room.data.update()
        self.assert_reused(False)
        bpy.data.objects["Fenestra Sensors"].location.x += 0.1
        self.assert_reused(False)
        f.solve.seed += 1  # the paths' seed
        self.assert_reused(False)
        f.goals.use_max = True
        self.assert_reused(True)

    def test_repainted_goals_solve_again_at_preview_quality_on_the_room_example(self):
        bpy.ops.wm.read_homefile(use_empty=True)
        examples.enable_addon()
        examples.build_room()
        f = bpy.context.scene.fenestra
        f.solve.study_directory = os.path.join(OUT, "room_study")
        first = self.assert_reused(False)
        contributions = f.results.seconds_contributions
        sensors = bpy.data.objects["Sensors"]
        f.goals.source = 'ATTRIBUTE'
        examples.paint_goals(sensors, lambda x, y, z: 0.8 if x < 2.5 else 0.2)
        again = self.assert_reused(True)
        print("room example at Preview: first solve %.2f s (contributions %.2f s), after repainting %.2f s "
              "(solver %.2f s)" % (first, contributions, again, f.results.seconds_solver))
        goals = np.array([s.goal for s in f.results.sensors])
        self.assertGreater(goals.max(), 2 * goals.min())  # the painted goals were used
        self.assertLess(again, first - 0.5 * contributions)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    addon_study.enable()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
