"""Messages in the user's words and the setup checks, inside Blender (run by test_blender_addon.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_checks.py -- OUT_DIR

Bad setups are refused with messages that name objects and fields, never scene-file keys or
paths; hidden marked objects are named as hidden; the goal fields hold only goals the solver
takes; Check Setup (and Solve Openings) warn, with counts, about goals all 0, sensors outdoors,
rooms open to the sky, sensors facing down, domain faces whose room the solver cannot tell and
sensors lying on the domain or on a wall.
The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import os
import re
import sys
import unittest

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from addon_holes import mesh_object, reset  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_checks_test"
BOX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
BOTTOM, TOP, SOUTH = 0, 1, 2
# What a message must not show: a scene-file key (dotted, indexed or snake_case) or a file path.
KEY = re.compile(r"\b[a-z]+_[a-z_]+\b|\b[a-z_]+\.[a-z_]+|\[\d+\]\.|\bgoals\[")
PATH = re.compile(r"(?<![\w.])/\w")


def room(name="Room", origin=(0.0, 0.0), size=(4.0, 4.0), height=2.7, faces=range(6), domain=(SOUTH,),
         collection=None):
    """A zero-thickness box room; its south face (y = origin y) the domain."""
    (x0, y0), (w, d) = origin, size
    verts = [(x0, y0, 0), (x0 + w, y0, 0), (x0 + w, y0 + d, 0), (x0, y0 + d, 0),
             (x0, y0, height), (x0 + w, y0, height), (x0 + w, y0 + d, height), (x0, y0 + d, height)]
    chosen = [BOX_FACES[i] for i in faces]
    marked = {chosen.index(BOX_FACES[i]) for i in domain if BOX_FACES[i] in chosen}
    return mesh_object(name, verts, chosen, domain=marked, collection=collection)


def sensor_grid(name="Sensors", origin=(0.0, 0.0), size=(4.0, 4.0), n=4, z=0.8, flip=False, collection=None):
    """n x n sensors (a grid of faces, so that they have normals: up, or down when flipped)."""
    (x0, y0), (w, d) = origin, size
    verts = [(x0 + w * (i + 0.5) / n, y0 + d * (j + 0.5) / n, z) for i in range(n) for j in range(n)]
    faces = [(i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1)
             for i in range(n - 1) for j in range(n - 1)]
    obj = mesh_object(name, verts, faces, flip=flip, collection=collection)
    obj.fenestra.is_sensor = True
    return obj


def settings():
    f = bpy.context.scene.fenestra
    f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'NORMALIZED', 0.5
    f.sky.type = 'UNIFORM'
    s = f.solve
    s.element_size, s.quality, s.paths, s.generations, s.population = 0.5, 'CUSTOM', 256, 10, 8
    s.study_directory = os.path.join(OUT, "study")
    return f


def check():
    """Check Setup's warnings."""
    assert bpy.ops.fenestra.check_setup() == {'FINISHED'}
    return [w for w in bpy.context.scene.fenestra.setup_warnings.split("\n") if w]


def refusal():
    """The message of a refused solve."""
    try:
        bpy.ops.fenestra.solve_openings()
    except RuntimeError as exc:  # bpy.ops raises on an ERROR report
        return str(exc)
    raise AssertionError("the solve was not refused")


class Messages(unittest.TestCase):
    """Refusals in the user's words: objects and fields, no keys, no paths."""

    def setUp(self):
        reset()

    def assert_plain(self, message, *words):
        self.assertIsNone(KEY.search(message), message)
        self.assertIsNone(PATH.search(message), message)
        for word in words:
            self.assertIn(word, message)

    def test_element_size_larger_than_an_l_shaped_panel(self):
        """An L of 0.3 m arms in an 8 x 9 m box: the box is not mentioned, the object is."""
        mesh_object("Wall", [(0, 0, 0), (8, 0, 0), (8, 0, 0.3), (0.3, 0, 0.3), (0.3, 0, 9), (0, 0, 9)],
                    [(0, 1, 2, 3), (0, 3, 4, 5)], domain={0, 1})
        sensor_grid(origin=(1, 1), size=(4, 4))
        settings()
        message = refusal()
        self.assert_plain(message, "Element Size 0.5 m is too large", "the domain faces of 'Wall'")
        self.assertNotIn("8 m x 9 m", message)

    def test_painted_goal_above_one_names_the_vertex(self):
        room()
        grid = sensor_grid(name="Floor grid")
        f = settings()
        f.goals.source, f.goals.scale = 'ATTRIBUTE', 1.0
        values = [0.5] * len(grid.data.vertices)
        values[5] = 1.5
        grid.data.attributes.new("fenestra_goal", 'FLOAT', 'POINT').data.foreach_set("value", values)
        self.assert_plain(refusal(), "vertex 5 of 'Floor grid'", "1.5", "at most 1")

    def test_cost_model_refusals(self):
        room()
        sensor_grid()
        f = settings()
        f.solve.paths = 2 ** 24
        self.assert_plain(refusal(), "fewer paths", "Quality")
        # About 17 min at population 16 (the limit is 10): refused before any work.
        f.solve.paths, f.solve.generations, f.solve.population = 256, 10 ** 7, 16
        self.assert_plain(refusal(), "fewer Generations", "Population")

    def test_a_night_sky(self):
        room()
        sensor_grid()
        f = settings()
        f.sky.type, f.sky.use_sun_position, f.sky.start_time, f.sky.end_time = 'PREETHAM', False, 1.0, 2.0
        message = refusal()
        self.assert_plain(message, "The sky: the sun is below the horizon")
        self.assertNotIn("EnvironmentMap", message)

    def test_hidden_domain_object(self):
        wall = room(name="Wall")
        sensor_grid()
        settings()
        wall.hide_set(True)
        self.assert_plain(refusal(), "The domain faces of 'Wall' are on a hidden object", "Alt+H")

    def test_domain_in_an_excluded_collection(self):
        collection = bpy.data.collections.new("Walls")
        bpy.context.scene.collection.children.link(collection)
        room(name="Wall", collection=collection)
        sensor_grid()
        settings()
        bpy.context.view_layer.layer_collection.children["Walls"].exclude = True
        self.assert_plain(refusal(), "'Wall' are on a hidden object", "collection 'Walls' is excluded")

    def test_hidden_sensors(self):
        room()
        grid = sensor_grid(name="Floor grid")
        settings()
        grid.hide_viewport = True
        self.assert_plain(refusal(), "The sensors of 'Floor grid' are on a hidden object", "disabled in viewports")


class GoalFields(unittest.TestCase):
    def setUp(self):
        reset()

    def test_normalized_goal_at_most_one(self):
        g = bpy.context.scene.fenestra.goals
        g.units, g.level = 'NORMALIZED', 1.5
        self.assertAlmostEqual(g.level, 1.0)

    def test_daylight_factor_at_most_100_and_lux_unbounded_above(self):
        g = bpy.context.scene.fenestra.goals
        g.units, g.level = 'DAYLIGHT_FACTOR', 150.0
        self.assertAlmostEqual(g.level, 100.0)
        g.units, g.level = 'LUX', 5000.0
        self.assertAlmostEqual(g.level, 5000.0)
        g.units = 'NORMALIZED'  # a lux goal kept would be refused: clamped
        self.assertLessEqual(g.level, 1.0)
        g.level = -1.0
        self.assertEqual(g.level, 0.0)

    def test_minimum_and_maximum_keep_the_goal_between_them(self):
        g = bpy.context.scene.fenestra.goals
        g.units, g.level, g.min, g.max = 'NORMALIZED', 0.5, 0.3, 0.8
        g.min = 0.6          # above the goal: the goal follows
        self.assertAlmostEqual(g.level, 0.6)
        g.level = 0.9        # above the maximum: the maximum follows
        self.assertAlmostEqual(g.max, 0.9)
        g.max = 0.2          # below both: they follow
        self.assertAlmostEqual(g.level, 0.2)
        self.assertAlmostEqual(g.min, 0.2)
        self.assertTrue(g.min <= g.level <= g.max)


class Checks(unittest.TestCase):
    """Check Setup's warnings, with counts; a sound setup gets none."""

    def setUp(self):
        reset()

    def test_a_closed_room_is_sound(self):
        room()
        sensor_grid()
        settings()
        self.assertEqual(check(), [])
        self.assertTrue(bpy.context.scene.fenestra.setup_checked)

    def test_all_goals_zero(self):
        room()
        sensor_grid()
        settings().goals.level = 0.0
        self.assertEqual([w for w in check() if "goals are 0" in w],
                         ["All 16 sensor goals are 0: the solve opens nothing and reports 0 % error. "
                          "Set a Goal above 0"])

    def test_sensors_outdoors(self):
        room()
        sensor_grid()
        sensor_grid(name="Garden", origin=(6.0, 0.0), size=(2.0, 2.0), n=2)
        settings()
        warnings = check()
        self.assertEqual(len(warnings), 1, warnings)
        self.assertTrue(warnings[0].startswith("4 of 20 sensors are outdoors"), warnings)

    def test_a_room_without_a_ceiling_is_open_upward(self):
        room(faces=[i for i in range(6) if i != TOP])
        sensor_grid()
        settings()
        warnings = check()
        self.assertEqual(len(warnings), 1, warnings)
        self.assertTrue(warnings[0].startswith("16 of 16 sensors see the sky through gaps"), warnings)
        self.assertIn("mostly upward", warnings[0])

    def test_sensors_facing_down(self):
        room()
        sensor_grid(name="Floor grid", flip=True)
        settings()
        warnings = check()
        self.assertEqual(len(warnings), 1, warnings)
        self.assertTrue(warnings[0].startswith("16 of 16 sensors of 'Floor grid' face downward"), warnings)

    def test_domain_seen_from_the_side_the_solver_does_not_take_for_the_room(self):
        """Room A's south wall (y = 0) is seen by A's 16 sensors from y > 0; room B, south of it,
        has 36 sensors at y < 0, so the solver takes y < 0 for A's wall's room."""
        room(name="Room A")
        sensor_grid(name="Sensors A")
        room(name="Room B", origin=(0.0, -10.0), size=(6.0, 6.0), domain=())
        sensor_grid(name="Sensors B", origin=(0.0, -10.0), size=(6.0, 6.0), n=6)
        settings()
        warnings = check()
        self.assertEqual(len(warnings), 1, warnings)
        self.assertTrue(warnings[0].startswith("The domain faces of 'Room A' (1 flat part) are seen by 16 sensors "
                                               "from one side, but 36 of 52 sensors lie on the other side"), warnings)

    def test_sensors_on_the_domain_and_on_the_walls(self):
        """A 5 x 5 grid from wall to wall (rows in the wall planes, as a grid over the floor's whole
        extent has): the south row lies on the domain, the others' edge rows on the walls."""
        room()
        verts = [(float(i), float(j), 0.8) for i in range(5) for j in range(5)]
        faces = [(i * 5 + j, (i + 1) * 5 + j, (i + 1) * 5 + j + 1, i * 5 + j + 1) for i in range(4) for j in range(4)]
        mesh_object("Edge rows", verts, faces).fenestra.is_sensor = True
        settings()
        warnings = [w for w in check() if " lie on " in w]  # in the wall planes, many also see outdoors
        self.assertEqual(len(warnings), 2, warnings)
        self.assertTrue(warnings[0].startswith("5 of 25 sensors of 'Edge rows' lie on the opening domain"), warnings)
        self.assertTrue(warnings[1].startswith("11 of 25 sensors of 'Edge rows' lie on a wall, ceiling or other "
                                               "surface"), warnings)
        for w in warnings:
            self.assertIsNone(KEY.search(w), w)

    def test_hidden_marked_objects_left_out(self):
        room()
        sensor_grid()
        room(name="Annex", origin=(10.0, 0.0)).hide_set(True)
        sensor_grid(name="Annex sensors", origin=(10.0, 0.0)).hide_set(True)
        settings()
        self.assertEqual(check(), [
            "The 1 domain face of 'Annex' is on a hidden object (it is hidden, Alt+H shows it) and is left "
            "out of the study",
            "The 16 sensors of 'Annex sensors' are on a hidden object (it is hidden, Alt+H shows it) and are "
            "left out of the study"])

    def test_solve_warns_too(self):
        room()
        sensor_grid()
        settings().goals.level = 0.0
        bpy.context.scene.fenestra.setup_warnings = ""
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertIn("All 16 sensor goals are 0", bpy.context.scene.fenestra.setup_warnings)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    reset()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
