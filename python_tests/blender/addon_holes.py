"""The result's cutters open real holes through the walls, inside Blender (run by
test_blender_addon.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_holes.py -- OUT_DIR

Rooms modelled as an architect does: a closed box with zero-thickness walls, an open mesh, and a
south wall modelled as a 0.3 m solid (its inner face the opening domain; its outer face and edge
strips in the same object or in another one). The add-on's results.apply puts a result with two
openings into the model; rays cast on the evaluated depsgraph from inside the room along each
opening's outward normal must reach the sky through the opening, and hit the wall just beside it.
The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import json
import os
import sys
import unittest

import bmesh
import bpy
import numpy as np
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_holes_test"
W, D, H = 4.0, 4.0, 2.7  # the room: x along the south wall, y into the room, z up
SOLID = 0.3              # the solid south wall's thickness, outside the room (y < 0)
OUTWARD = (0.0, -1.0, 0.0)
# Two openings on the south wall's inner face (y = 0): x from, x to, z from, z to.
OPENINGS = [(0.6, 1.6, 0.9, 2.1), (2.2, 3.4, 0.5, 1.5)]

BOX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
BOTTOM, TOP, SOUTH, EAST, NORTH, WEST = range(6)  # face indices in BOX_FACES


def box_verts(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
            (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]


def mesh_object(name, verts, faces, domain=(), flip=False, collection=None):
    """A mesh object, normals made consistent (all turned over with flip); the faces listed in
    domain marked as opening domain; linked to collection (the scene's by default)."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(map(float, v)) for v in verts], [], [tuple(f) for f in faces])
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    if flip:
        bmesh.ops.reverse_faces(bm, faces=bm.faces)
    bm.to_mesh(mesh)
    bm.free()
    if domain:
        flags = [i in domain for i in range(len(faces))]
        mesh.attributes.new("fenestra_domain", 'BOOLEAN', 'FACE').data.foreach_set("value", flags)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def closed_room():
    """A closed box with zero-thickness walls; its south face is the domain."""
    return [mesh_object("Room", box_verts((0, 0, 0), (W, D, H)), BOX_FACES, domain={SOUTH})]


def open_room():
    """The box without a ceiling (an open mesh); its south face is the domain."""
    faces = [f for i, f in enumerate(BOX_FACES) if i != TOP]
    return [mesh_object("Room", box_verts((0, 0, 0), (W, D, H)), faces, domain={faces.index(BOX_FACES[SOUTH])})]


def solid_wall_one_object():
    """One object: zero-thickness floor, ceiling and walls, and a 0.3 m solid south wall whose
    inner face (y = 0) is the domain."""
    faces = [f for i, f in enumerate(BOX_FACES) if i != SOUTH]
    slab = [tuple(i + 8 for i in f) for f in BOX_FACES]
    verts = box_verts((0, 0, 0), (W, D, H)) + box_verts((0, -SOLID, 0), (W, 0, H))
    return [mesh_object("Room", verts, faces + slab, domain={len(faces) + NORTH})]


def solid_wall_two_objects():
    """A closed zero-thickness box whose south face (the wall's inner face) is the domain, and the
    rest of the 0.3 m south wall (outer face and edge strips) in another object."""
    room = mesh_object("Room", box_verts((0, 0, 0), (W, D, H)), BOX_FACES, domain={SOUTH})
    outer = mesh_object("South wall", box_verts((0, -SOLID, 0), (W, 0, H)),
                        [f for i, f in enumerate(BOX_FACES) if i != NORTH])
    return [room, outer]


def sensors():
    obj = mesh_object("Sensors", [(x, y, 0.8) for x in (1.0, 2.0, 3.0) for y in (1.0, 2.0, 3.0)], [])
    obj.fenestra.is_sensor = True
    return obj


def result_dict(depth, count):
    """A result as fenestra.solve returns it, written by hand: the openings on the inner face."""
    openings = []
    for x0, x1, z0, z1 in OPENINGS:
        corners = [[x0, 0.0, z0], [x1, 0.0, z0], [x1, 0.0, z1], [x0, 0.0, z1]]
        opening = {"corners": corners, "centre": np.mean(corners, axis=0).tolist(), "width": x1 - x0,
                   "height": z1 - z0, "normal": list(OUTWARD), "panel": 0}
        if depth is not None:
            opening["depth"] = depth
        openings.append(opening)
    return {"openings": openings, "sensors": [{"goal": 100.0, "predicted": 90.0}] * count,
            "error": {"relative_rms": 0.1}, "open_elements": [], "element_count": 0}


def reset():
    bpy.ops.wm.read_homefile(use_empty=True)
    installed.enable()
    assert hasattr(bpy.types.Scene, "fenestra"), "the add-on did not register"


def setup(build, wall_thickness=0.0):
    """The scene, the study as the add-on exports it."""
    export = installed.blender("study.export")
    reset()
    walls = build()
    sensors()
    f = bpy.context.scene.fenestra
    f.solve.element_size, f.solve.wall_thickness = 0.25, wall_thickness
    f.sky.type = 'UNIFORM'
    return walls, export.build(bpy.context)


def cast(origin, direction):
    """The first visible object hit from origin along direction on the evaluated depsgraph, or
    None (the sky). The cutters (drawn as wire, not rendered) and the sensors are hidden."""
    hidden = [o for o in bpy.context.view_layer.objects
              if (o.fenestra.is_opening or o.fenestra.is_sensor) and not o.hide_get()]
    for obj in hidden:
        obj.hide_set(True)
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        hit, location, _, _, obj, _ = bpy.context.scene.ray_cast(depsgraph, Vector(origin), Vector(direction))
    finally:
        for o in hidden:
            o.hide_set(False)
    return (obj.name, tuple(location)) if hit else None


class Holes(unittest.TestCase):
    def check_holes(self, walls, cut=None):
        """Rays from 1 m inside the room, along the outward normal: through 9 points of each opening
        they reach the sky; 5 cm beyond each edge they hit the wall."""
        n = np.array(OUTWARD)
        for x0, x1, z0, z1 in OPENINGS:
            for x in np.linspace(x0 + 0.05, x1 - 0.05, 3):
                for z in np.linspace(z0 + 0.05, z1 - 0.05, 3):
                    origin = np.array([x, 0.0, z]) - n
                    self.assertIsNone(cast(origin, n), "a face across the opening at x %.2f z %.2f" % (x, z))
            xm, zm = (x0 + x1) / 2, (z0 + z1) / 2
            for x, z in ((x0 - 0.05, zm), (x1 + 0.05, zm), (xm, z0 - 0.05), (xm, z1 + 0.05)):
                hit = cast(np.array([x, 0.0, z]) - n, n)
                self.assertIsNotNone(hit, "no wall beside the opening at x %.2f z %.2f" % (x, z))
                self.assertAlmostEqual(hit[1][1], 0.0, places=4)  # the wall's inner face
        modified = sorted(o.name for o in bpy.data.objects if any(m.name == "Fenestra Openings" for m in o.modifiers))
        self.assertEqual(modified, sorted(cut or [w.name for w in walls]))

    def apply(self, study, depth):
        results = installed.blender("result.results")
        count = sum(c for _, c in study.sensor_objects)
        results.apply(bpy.context, study, result_dict(depth, count))

    def check_cutters(self, depth):
        """Each cutter reaches depth + margin outward from the inner face and margin into the room."""
        cutters = [o for o in bpy.data.objects if o.fenestra.is_opening]
        self.assertEqual(len(cutters), len(OPENINGS))
        margin = bpy.context.scene.fenestra.solve.cutter_margin
        for obj in cutters:
            y = [(obj.matrix_world @ v.co).y for v in obj.data.vertices]
            self.assertAlmostEqual(min(y), -depth - margin, places=5)
            self.assertAlmostEqual(max(y), margin, places=5)

    def test_closed_box_room(self):
        walls, study = setup(closed_room)
        self.apply(study, 0.0)
        self.check_holes(walls)
        self.check_cutters(0.0)
        self.assertNotIn("thickness", study.scene["opening_domain"])  # measured by the core

    def test_open_mesh_room(self):
        walls, study = setup(open_room)
        self.apply(study, 0.0)
        self.check_holes(walls)
        self.check_cutters(0.0)

    def test_solid_wall_in_the_room_object(self):
        walls, study = setup(solid_wall_one_object)
        self.apply(study, SOLID)
        self.check_holes(walls)
        self.check_cutters(SOLID)

    def test_solid_wall_outer_faces_in_another_object(self):
        walls, study = setup(solid_wall_two_objects)
        self.assertEqual(study.domain_objects, ["Room"])
        self.apply(study, SOLID)
        self.check_holes(walls, cut=["Room", "South wall"])
        self.check_cutters(SOLID)

    def test_depth_defaults_to_the_wall_thickness_set(self):
        walls, study = setup(solid_wall_two_objects, wall_thickness=SOLID)
        self.assertAlmostEqual(study.scene["opening_domain"]["thickness"], SOLID, places=6)
        self.apply(study, None)
        self.check_holes(walls, cut=["Room", "South wall"])
        self.check_cutters(SOLID)

    def test_clear_results_removes_the_holes(self):
        walls, study = setup(solid_wall_two_objects)
        self.apply(study, SOLID)
        self.assertEqual(bpy.ops.fenestra.clear_results(), {'FINISHED'})
        self.assertEqual([m.name for w in walls for m in w.modifiers], [])
        self.assertNotIn("Fenestra Open Through", bpy.data.node_groups)
        x0, x1, z0, z1 = OPENINGS[0]
        self.assertIsNotNone(cast(((x0 + x1) / 2, 1.0, (z0 + z1) / 2), OUTWARD))

    def test_solve_then_save_and_reload(self):
        """A real Preview solve cuts through the solid wall; the holes survive a save and reload,
        and a second solve reads the walls uncut."""
        walls, _ = setup(solid_wall_two_objects, wall_thickness=SOLID)
        s = bpy.context.scene.fenestra.solve
        s.element_size, s.quality, s.paths, s.generations, s.population = 0.5, 'CUSTOM', 256, 20, 16
        s.constraints.max_openings = 1
        s.study_directory = os.path.join(OUT, "study")
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        path = os.path.join(OUT, "solved.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.open_mainfile(filepath=path)
        result = json.load(open(os.path.join(OUT, "study", "result.json")))
        self.assertGreaterEqual(len(result["openings"]), 1)
        for opening in result["openings"]:
            n = np.array(opening["normal"])
            self.assertIsNone(cast(np.array(opening["centre"]) - n, n))
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        scene_json = json.load(open(os.path.join(OUT, "study", "scene.json")))
        self.assertEqual(scene_json["opening_domain"]["groups"], ["Room.domain"])
        obj_text = open(os.path.join(OUT, "study", "scene.obj")).read()
        self.assertEqual(len([l for l in obj_text.splitlines() if l.startswith("f ")]), 12 + 10)  # uncut


    def solve_at(self, offset, folder):
        """A Preview solve of the closed room with every object moved by offset (meters); the result."""
        walls, _ = setup(closed_room)
        for obj in bpy.data.objects:
            obj.location = offset
        bpy.context.view_layer.update()
        s = bpy.context.scene.fenestra.solve
        s.element_size, s.quality, s.paths, s.generations, s.population = 0.5, 'CUSTOM', 256, 20, 16
        s.constraints.max_openings = 1
        s.study_directory = os.path.join(OUT, folder)
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        return json.load(open(os.path.join(OUT, folder, "result.json")))

    def test_a_model_far_from_the_origin_is_solved_and_cut_where_it_lies(self):
        """A model placed in site coordinates (tens of kilometres out, where Blender's floats still
        keep millimetres): moved by whole meters, the solve is the same bit for bit, its openings
        lie on the moved wall, and rays pass through the holes they cut."""
        a, b = (61000.0, 32000.0, 150.0), (73000.0, 45000.0, 280.0)
        first = self.solve_at(a, "site_a")
        second = self.solve_at(b, "site_b")
        self.assertGreaterEqual(len(second["openings"]), 1)
        self.assertEqual([s["predicted"] for s in first["sensors"]], [s["predicted"] for s in second["sensors"]])
        for o1, o2 in zip(first["openings"], second["openings"]):
            np.testing.assert_allclose(np.array(o2["corners"]) - b, np.array(o1["corners"]) - a, atol=1e-6)
            corners = np.array(o2["corners"]) - b
            self.assertLess(np.abs(corners[:, 1]).max(), 1e-6)  # on the south wall's plane
            self.assertTrue(np.all((corners[:, 0] > -1e-6) & (corners[:, 0] < W + 1e-6)))
            n = np.array(o2["normal"])
            self.assertIsNone(cast(np.array(o2["centre"]) - n, n), "no hole at the opening's centre")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    reset()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
