"""Add Sensor Grid over rooms as architects model them, inside Blender (run by test_blender_addon.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_sensor_grid.py -- OUT_DIR

A room modelled as one solid (walls, floor and ceiling a single mesh around the room's cavity) gets
its sensors at the set height above the floor's upper face, kept off the walls and the domain, and
Check Setup finds nothing wrong with them; a solid holding two rooms gets a sensor object per room;
the inset can be set by hand; a grid that cannot be made is refused with the reason.
The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import os
import sys
import unittest

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402
from addon_holes import reset  # noqa: E402
from addon_study import select_only  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_grid_test"
BOX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]  # out
SOUTH = 2
WALL, SLAB = 0.3, 0.2  # m


def box(lo, hi, inward):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    return verts, [tuple(reversed(f)) if inward else f for f in BOX_FACES]


def solid(name, cavities, size=(4.0, 5.0), height=3.0, domain_cavity=0):
    """One mesh: a solid block around `cavities` (x ranges of rooms side by side, each size[1] deep,
    `height` tall), walls WALL and slabs SLAB thick; the south face of cavity `domain_cavity` (the
    south wall's inner face) is the opening domain. Faces face out of the solid: into the rooms."""
    x_lo, x_hi = min(c[0] for c in cavities), max(c[1] for c in cavities)
    verts, faces = box((x_lo - WALL, -WALL, -SLAB), (x_hi + WALL, size[1] + WALL, height + SLAB), False)
    domain = []
    for k, (a, b) in enumerate(cavities):
        v, f = box((a, 0.0, 0.0), (b, size[1], height), True)
        n = len(verts)
        if k == domain_cavity:
            domain.append(len(faces) + SOUTH)
        verts += v
        faces += [tuple(i + n for i in face) for face in f]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    flags = [i in domain for i in range(len(faces))]
    mesh.attributes.new("fenestra_domain", 'BOOLEAN', 'FACE').data.foreach_set("value", flags)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def grids():
    return sorted((o for o in bpy.data.objects if o.fenestra.is_sensor), key=lambda o: o.name)


def points(obj):
    co = np.empty(len(obj.data.vertices) * 3)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3) @ np.array(obj.matrix_world)[:3, :3].T + np.array(obj.matrix_world)[:3, 3]


def wall_distance(p, x0, x1, y0, y1):
    return np.minimum.reduce([p[:, 0] - x0, x1 - p[:, 0], p[:, 1] - y0, y1 - p[:, 1]])


def add_grid(height=0.8, spacing=0.5, inset=None):
    f = bpy.context.scene.fenestra
    f.sensor_height, f.sensor_spacing = height, spacing
    f.sensor_inset_auto = inset is None
    if inset is not None:
        f.sensor_inset = inset
    return bpy.ops.fenestra.add_sensor_grid()


def operators():
    return installed.blender("ui.operators")


class SensorGrid(unittest.TestCase):
    def setUp(self):
        reset()

    def test_a_solid_rooms_grid_lies_over_the_floors_upper_face(self):
        room = solid("Room", [(0.0, 4.0)])
        select_only(room)
        self.assertEqual(add_grid(), {'FINISHED'})
        (grid,) = grids()
        self.assertEqual(grid.name, "Fenestra Sensors")
        p = points(grid)
        self.assertEqual(len(p), 80)  # 8 x 10 at 0.5 m over 4 x 5 m, 0.25 m off the walls
        self.assertTrue(np.allclose(p[:, 2], 0.8, atol=1e-4), p[:, 2])  # not 0.6 (the slab's underside + 0.8)
        self.assertGreaterEqual(wall_distance(p, 0, 4, 0, 5).min(), 0.25 - 1e-4)
        self.assertAlmostEqual(p[:, 0].min(), 4.0 - p[:, 0].max(), places=4)  # centred
        self.assertEqual(len(grid.data.polygons), 7 * 9)  # faces to paint goals on
        self.assertIn("fenestra_goal", grid.data.color_attributes)
        # What the operator reports: the real height, from the floor's upper face.
        report = operators().grid_report(
            {"rooms": [{"points": p, "floor_z": p[:, 2] - 0.8}], "inset": 0.25, "enclosed": True}, [grid], 0.8)
        self.assertEqual(report, "80 sensors in 1 room, 0.80 m above the floor's upper face (z = 0.00 m), "
                                 "0.25 m off the walls")

    def test_check_setup_finds_nothing_wrong_with_it(self):
        room = solid("Room", [(0.0, 4.0)])
        select_only(room)
        add_grid()
        f = bpy.context.scene.fenestra
        f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'NORMALIZED', 0.5
        f.sky.type = 'UNIFORM'
        f.solve.study_directory = os.path.join(OUT, "study")
        self.assertEqual(bpy.ops.fenestra.check_setup(), {'FINISHED'})
        self.assertEqual(f.setup_warnings, "")
        self.assertTrue(f.setup_checked)
        # Sensors where a grid over the floor's whole extent has its edge rows: Check Setup names them.
        mesh = bpy.data.meshes.new("Edge rows")
        mesh.from_pydata([(2.0, 0.0, 0.8), (0.01, 2.0, 0.8), (2.0, 2.5, 0.8)], [], [])  # domain, west wall, inside
        edge = bpy.data.objects.new("Edge rows", mesh)
        edge.fenestra.is_sensor = True
        bpy.context.scene.collection.objects.link(edge)
        self.assertEqual(bpy.ops.fenestra.check_setup(), {'FINISHED'})
        warnings = [w for w in f.setup_warnings.split("\n") if " lie on " in w]  # some also see outdoors
        self.assertEqual(len(warnings), 2, warnings)
        self.assertTrue(warnings[0].startswith("1 of 3 sensors of 'Edge rows' lie on the opening domain"), warnings)
        self.assertTrue(warnings[1].startswith("1 of 3 sensors of 'Edge rows' lie on a wall"), warnings)

    def test_a_solve_over_it_is_confirmed_by_real_cutters(self):
        """The solve's predicted error and the check with real cutters through the 0.3 m wall agree
        within the check's noise (sensors in the domain's plane read orders of magnitude apart)."""
        room = solid("Room", [(0.0, 4.0)])
        select_only(room)
        add_grid(spacing=0.8)
        f = bpy.context.scene.fenestra
        f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'NORMALIZED', 0.4
        f.sky.type, f.sky.horizontal_illuminance = 'UNIFORM', 10000.0
        s = f.solve
        s.element_size, s.quality, s.paths, s.generations, s.population, s.seed = 0.5, 'CUSTOM', 1024, 30, 16, 3
        s.study_directory = os.path.join(OUT, "solve")
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        r = f.results
        self.assertTrue(r.valid)
        self.assertGreater(r.openings, 0)
        self.assertGreaterEqual(r.verified_rms, 0.0)
        print("predicted %.4f, checked %.4f +- %.4f" % (r.relative_rms, r.verified_rms, r.verified_noise))
        self.assertLess(abs(r.verified_rms - r.relative_rms), 3.0 * r.verified_noise + 0.02)

    def test_a_solid_with_two_rooms_gets_a_sensor_object_each(self):
        building = solid("Building", [(0.0, 3.0), (3.3, 7.3)])
        select_only(building)
        self.assertEqual(add_grid(spacing=0.6), {'FINISHED'})
        west, east = grids()
        self.assertEqual((west.name, east.name), ("Fenestra Sensors 1", "Fenestra Sensors 2"))
        pw, pe = points(west), points(east)
        self.assertGreaterEqual(wall_distance(pw, 0.0, 3.0, 0, 5).min(), 0.3 - 1e-4)  # half of 0.6 m
        self.assertGreaterEqual(wall_distance(pe, 3.3, 7.3, 0, 5).min(), 0.3 - 1e-4)
        self.assertTrue(np.allclose(np.concatenate([pw, pe])[:, 2], 0.8, atol=1e-4))

    def test_the_inset_set_by_hand(self):
        room = solid("Room", [(0.0, 4.0)])
        select_only(room)
        self.assertEqual(add_grid(inset=1.0), {'FINISHED'})
        p = points(grids()[0])
        self.assertGreaterEqual(wall_distance(p, 0, 4, 0, 5).min(), 1.0 - 1e-4)
        self.assertLess(wall_distance(p, 0, 4, 0, 5).min(), 1.0 + 0.5)

    def test_grids_that_cannot_be_made_are_refused_with_the_reason(self):
        room = solid("Room", [(0.0, 4.0)])
        select_only(room)
        with self.assertRaises(RuntimeError) as caught:  # bpy.ops raises on an ERROR report
            add_grid(height=2.99)
        self.assertIn("No floor of 'Room' has room for sensors 2.99 m above it", str(caught.exception))
        self.assertEqual(grids(), [])
        plane = bpy.data.meshes.new("Plaza")
        plane.from_pydata([(0, 0, 0), (60, 0, 0), (60, 60, 0), (0, 60, 0)], [], [(0, 1, 2, 3)])
        obj = bpy.data.objects.new("Plaza", plane)
        bpy.context.scene.collection.objects.link(obj)
        select_only(obj)
        with self.assertRaises(RuntimeError) as caught:
            add_grid(spacing=0.05)
        self.assertIn("use a spacing of at least 0.06 m", str(caught.exception))
        self.assertEqual(grids(), [])


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    reset()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
