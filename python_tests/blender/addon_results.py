"""A result made visible and cleared, inside Blender (run by test_blender_results.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_results.py -- OUT_DIR

False colour values and scales, each sensor found by object and vertex, the goal plot, Preview
Sky's exposure and live strength, the domain highlight's faces (cut by the result, in Edit Mode
too), Clear Results and Clear Domain. The add-on must be on Blender's add-on path."""

import json
import math
import os
import sys
import unittest

import bmesh
import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402
import addon_study  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_results_test"
addon_study.OUT = OUT
WALL_AREA = addon_study.ROOM[0] * addon_study.ROOM[2]  # the south wall, the domain


def solved():
    room = addon_study.study()
    assert bpy.ops.fenestra.solve_openings() == {'FINISHED'}
    return room


def achieved_attribute(obj):
    attr = obj.data.attributes["fenestra_achieved"]
    values = np.zeros(len(attr.data))
    attr.data.foreach_get("value", values)
    return values


def edit_selecting(obj, vertices=(), faces=()):
    """Edit Mode on obj alone, with exactly these vertices or faces selected."""
    addon_study.select_only(obj)
    bpy.ops.object.mode_set(mode='EDIT')
    bm = bmesh.from_edit_mesh(obj.data)
    for element in list(bm.verts) + list(bm.faces):
        element.select = False
    bm.verts.ensure_lookup_table()
    bm.faces.ensure_lookup_table()
    for i in faces:
        bm.faces[i].select = True
    for i in vertices:
        bm.verts[i].select = True
    if vertices:
        bm.select_history.add(bm.verts[vertices[-1]])
    bmesh.update_edit_mesh(obj.data)
    return bm


def triangles_area(corners):
    t = corners.reshape(-1, 3, 3)
    return float(0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1).sum())


class SensorValues(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_each_sensor_is_found_by_object_and_vertex(self):
        sensor_results = installed.blender("result.sensor_results")
        solved()
        r = bpy.context.scene.fenestra.results
        sensors = bpy.data.objects["Fenestra Sensors"]
        self.assertEqual([s.object_name for s in r.sensors], ["Fenestra Sensors"] * len(r.sensors))
        self.assertEqual([s.vertex for s in r.sensors], list(range(len(sensors.data.vertices))))
        goal, achieved = sensor_results.per_vertex(r, sensors.name, len(sensors.data.vertices))
        np.testing.assert_allclose(achieved, achieved_attribute(sensors), rtol=1e-6)
        self.assertTrue(np.all(goal > 0))
        # The active vertex in Edit Mode is the selected sensor shown in the Results panel.
        edit_selecting(sensors, vertices=(2, 5))
        obj, vertex, g, a = sensor_results.active_sensor(bpy.context)
        self.assertEqual((obj.name, vertex), (sensors.name, 5))
        self.assertAlmostEqual(a, r.sensors[5].achieved, places=3)
        self.assertAlmostEqual(g, r.sensors[5].goal, places=3)
        bpy.ops.object.mode_set(mode='OBJECT')
        # The table lists the sensors farthest from their goals first.
        rows = sensor_results.farthest_from_goal(r, 3)
        errors = [abs(s.achieved - s.goal) / s.goal for s in r.sensors]
        self.assertAlmostEqual(abs(rows[0].achieved - rows[0].goal) / rows[0].goal, max(errors), places=6)

    def test_false_colour_quantities_and_scales(self):
        false_colour = installed.blender("com.false_colour")
        result_display = installed.blender("result.result_display")
        solved()
        display = bpy.context.scene.fenestra.display
        r = bpy.context.scene.fenestra.results
        achieved = np.array([s.achieved for s in r.sensors])
        goal = np.array([s.goal for s in r.sensors])

        self.assertEqual(display.false_colour, 'ACHIEVED')  # shown by default after a solve
        scale, shown = result_display.current(bpy.context)
        np.testing.assert_allclose(shown["Fenestra Sensors"], achieved)
        self.assertGreaterEqual(scale.top, achieved.max())
        self.assertLess(scale.top, 2.0 * achieved.max())
        self.assertEqual(scale.title, "Achieved illuminance (lx)")
        labels = [label for _, label in scale.ticks()]
        self.assertEqual(labels[0], "0")
        colours = scale.colours(achieved)
        self.assertEqual(colours.shape, (len(achieved), 4))
        np.testing.assert_allclose(scale.colours([0.0])[0, :3], false_colour.SEQUENTIAL[0])
        np.testing.assert_allclose(scale.colours([scale.top])[0, :3], false_colour.SEQUENTIAL[-1])
        display.colour_max = 123.0  # set by the user: the scale's top
        self.assertEqual(result_display.current(bpy.context)[0].top, 123.0)
        display.colour_max = 0.0

        display.false_colour = 'RATIO'
        scale, shown = result_display.current(bpy.context)
        np.testing.assert_allclose(shown["Fenestra Sensors"], achieved / goal)
        self.assertEqual([label for _, label in scale.ticks()], ["0.25", "0.5", "1", "2", "4"])
        np.testing.assert_allclose(scale.colours([1.0])[0, :3], false_colour.DIVERGING[3])  # white on the goal
        self.assertTrue(np.allclose(scale.colours([np.nan])[0, :3], false_colour.NO_VALUE))

        # Daylight factor: of the solved sky's unobstructed horizontal illuminance, asked of the
        # native core when chosen (a uniform sky of 10 000 lux).
        display.false_colour = 'DAYLIGHT_FACTOR'
        self.assertAlmostEqual(r.horizontal_illuminance, 10000.0, delta=10000.0 * 0.01)
        scale, shown = result_display.current(bpy.context)
        np.testing.assert_allclose(shown["Fenestra Sensors"], 100.0 * achieved / r.horizontal_illuminance)
        self.assertEqual(scale.title, "Daylight factor (%)")
        # Solving again keeps daylight factors known.
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertGreater(bpy.context.scene.fenestra.results.horizontal_illuminance, 0.0)

        display.false_colour = 'NONE'
        self.assertIsNone(result_display.current(bpy.context))

    def test_nice_scales(self):
        false_colour = installed.blender("com.false_colour")
        self.assertEqual(false_colour.nice_top(3712.0), 4000.0)
        self.assertEqual(false_colour.nice_top(41.0), 50.0)
        self.assertEqual(false_colour.nice_top(0.37), 0.4)
        self.assertEqual(false_colour.nice_top(0.0), 1.0)
        ticks = false_colour.Scale('ACHIEVED', 4000.0).ticks()
        self.assertEqual([label for _, label in ticks], ["0", "1000", "2000", "3000", "4000"])

    def test_goal_plot_is_written_to_the_study_folder(self):
        solved()
        path = os.path.join(OUT, "study", "goals_vs_achieved.png")
        if os.path.exists(path):
            os.remove(path)
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            with self.assertRaises(RuntimeError) as failure:
                bpy.ops.fenestra.show_goal_plot()
            self.assertIn("matplotlib", str(failure.exception))
            return
        self.assertEqual(bpy.ops.fenestra.show_goal_plot(), {'FINISHED'})
        self.assertTrue(os.path.getsize(path) > 1000)
        image = bpy.data.images["goals_vs_achieved.png"]
        self.assertEqual(tuple(image.size), (600, 500))


class PreviewSky(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_exposure_brings_the_zenith_to_mid_grey_and_strength_applies_at_once(self):
        sky_preview = installed.blender("result.sky_preview")
        addon_study.study()
        scene = bpy.context.scene
        s = scene.fenestra.sky
        s.type, s.horizontal_illuminance, s.map_width = 'CIE_OVERCAST', 10000.0, 256
        self.assertAlmostEqual(s.preview_strength, 0.001)
        self.assertEqual(bpy.ops.fenestra.preview_sky(), {'FINISHED'})
        zenith = 10000.0 * 9.0 / (7.0 * math.pi)  # CIE overcast: E_h = 7 pi / 9 L_z
        shown = zenith * s.preview_strength * 2.0 ** scene.view_settings.exposure
        self.assertAlmostEqual(shown, sky_preview.MID_GREY, delta=0.02 * sky_preview.MID_GREY)
        background = scene.world.node_tree.nodes["Background"].inputs["Strength"]
        self.assertAlmostEqual(background.default_value, 0.001)

        path = os.path.join(OUT, "study", "sky.exr")
        written = os.path.getmtime(path)
        image = scene.world.node_tree.nodes["Fenestra Sky"].image
        exposure = scene.view_settings.exposure
        s.preview_strength = 0.004  # the World follows, nothing is computed again
        self.assertAlmostEqual(background.default_value, 0.004, places=6)
        self.assertEqual(os.path.getmtime(path), written)
        self.assertEqual(scene.world.node_tree.nodes["Fenestra Sky"].image, image)
        self.assertEqual(scene.view_settings.exposure, exposure)

    def test_strength_before_any_preview_changes_nothing(self):
        bpy.context.scene.fenestra.sky.preview_strength = 0.01
        world = bpy.context.scene.world
        self.assertTrue(world is None or not world.use_nodes or "Fenestra Sky" not in world.node_tree.nodes)


class DomainHighlight(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_highlight_leaves_the_openings_uncovered_and_follows_edit_mode(self):
        overlay = installed.blender("draw.overlay")
        room = addon_study.study()
        depsgraph = bpy.context.evaluated_depsgraph_get()
        self.assertAlmostEqual(triangles_area(overlay.domain_triangles(room, depsgraph)), WALL_AREA, places=4)
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        with open(os.path.join(OUT, "study", "result.json")) as f:
            cut = sum(o["width"] * o["height"] for o in json.load(f)["openings"])
        self.assertGreater(cut, 0.0)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        area = triangles_area(overlay.domain_triangles(room, depsgraph))
        self.assertAlmostEqual(area, WALL_AREA - cut, delta=0.01 * WALL_AREA)
        # Edit Mode: the edit mesh's marks, also once one more face is marked there. Blender shows
        # a Boolean in Edit Mode only when asked to (show_in_editmode): the highlight is of the
        # mesh as shown.
        edit_selecting(room, faces=(3,))
        self.assertEqual(bpy.ops.fenestra.mark_domain(), {'FINISHED'})
        side = addon_study.ROOM[1] * addon_study.ROOM[2]
        boolean = room.modifiers["Fenestra Openings"]
        for shown in (False, True):
            boolean.show_in_editmode = room.modifiers["Fenestra Open Through"].show_in_editmode = shown
            depsgraph = bpy.context.evaluated_depsgraph_get()
            self.assertAlmostEqual(triangles_area(overlay.domain_triangles(room, depsgraph)),
                                   WALL_AREA - (cut if shown else 0.0) + side, delta=0.01 * WALL_AREA)
        bpy.ops.object.mode_set(mode='OBJECT')


class Clearing(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_clear_results_removes_everything_the_result_made(self):
        room = solved()
        sensors = bpy.data.objects["Fenestra Sensors"]
        self.assertIn("fenestra_achieved", sensors.data.attributes)
        self.assertEqual(bpy.ops.fenestra.clear_results(), {'FINISHED'})
        self.assertEqual([o for o in bpy.data.objects if o.fenestra.is_opening], [])
        self.assertNotIn("Fenestra Openings", bpy.data.collections)
        self.assertEqual([m.name for m in room.modifiers], [])
        self.assertNotIn("Fenestra Open Through", bpy.data.node_groups)
        self.assertNotIn("fenestra_achieved", sensors.data.attributes)
        r = bpy.context.scene.fenestra.results
        self.assertFalse(r.valid)
        self.assertEqual((r.openings, r.open_elements, r.elements, len(r.sensors)), (0, 0, 0, 0))
        self.assertEqual((r.relative_rms, r.verified_rms, r.warnings, r.study_path), (0.0, -1.0, "", ""))
        # The domain and the sensors are the user's: kept.
        self.assertEqual(bpy.context.scene.fenestra.domain_faces, 1)
        self.assertIn("fenestra_domain", room.data.attributes)
        # A solve after a clear works as the first one.
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertIn("Fenestra Openings", bpy.data.collections)

    def test_clear_domain_counts_and_unmarks_only_marked_selected_faces(self):
        operators = installed.blender("ui.operators")
        room = addon_study.box_room()
        other = addon_study.box_room()
        for obj in (room, other):
            edit_selecting(obj, faces=(2, 3))
            self.assertEqual(operators._mark_selected(bpy.context, True), 2)
            self.assertEqual(operators._mark_selected(bpy.context, True), 0)  # already marked
            bpy.ops.object.mode_set(mode='OBJECT')
        edit_selecting(room, faces=range(6))  # 6 selected, 2 of them marked
        self.assertEqual(operators._mark_selected(bpy.context, False), 2)
        self.assertEqual(bpy.ops.fenestra.clear_domain(), {'FINISHED'})  # nothing left: 0, no error
        bpy.ops.object.mode_set(mode='OBJECT')
        flags = np.zeros(6, bool)
        room.data.attributes["fenestra_domain"].data.foreach_get("value", flags)
        self.assertFalse(flags.any())
        other.data.attributes["fenestra_domain"].data.foreach_get("value", flags)
        self.assertEqual(flags.tolist(), [False, False, True, True, False, False])  # not selected: kept
        self.assertEqual(bpy.context.scene.fenestra.domain_faces, 2)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    addon_study.enable()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
