"""Undo and redo of the add-on's operators, headless (run by test_blender_addon.py in each
Blender): a solve's cutters, Boolean modifiers and results go with its undo step and come back with
redo; a marked opening domain is undone. An operator called from a script pushes no undo step (the
window manager does, for the user's clicks), so the steps are pushed here as a click would."""

import os
import sys
import unittest

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_study  # noqa: E402  (the room, its sensor grid and settings)


def state():
    scene = bpy.context.scene
    return (len(addon_study.cutters()),
            sorted(m.name for o in scene.objects for m in o.modifiers),
            scene.fenestra.results.valid, len(scene.fenestra.results.sensors))


class Undo(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_solve_undone_and_redone(self):
        addon_study.study()
        bpy.ops.ed.undo_push(message="Set up")
        before = state()
        self.assertEqual(before, (0, [], False, 0))
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        bpy.ops.ed.undo_push(message="Solve Openings")
        solved = state()
        self.assertGreater(solved[0], 0)
        self.assertTrue(solved[1] and solved[2] and solved[3] == 16, solved)
        self.assertEqual(bpy.ops.ed.undo(), {'FINISHED'})
        self.assertEqual(state(), before)
        self.assertEqual(bpy.ops.ed.redo(), {'FINISHED'})
        self.assertEqual(state(), solved)

    def test_mark_domain_undone(self):
        room = addon_study.box_room()
        bpy.ops.ed.undo_push(message="Room")
        addon_study.mark_south_wall(room)
        bpy.ops.ed.undo_push(message="Mark")
        marked = bpy.data.objects["Room"].data.attributes.get("fenestra_domain")
        self.assertIsNotNone(marked)
        self.assertEqual(bpy.ops.ed.undo(), {'FINISHED'})
        self.assertIsNone(bpy.data.objects["Room"].data.attributes.get("fenestra_domain"))


if __name__ == "__main__":
    os.makedirs(addon_study.OUT, exist_ok=True)
    addon_study.enable()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
