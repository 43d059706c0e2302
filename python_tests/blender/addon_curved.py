"""A curved opening domain inside Blender: its UV map is exported, and the result's curved openings
are cut along the surface (run by test_blender_addon.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_curved.py -- OUT_DIR

A closed room, a quarter of a cylinder: floor, ceiling, two flat walls from the axis and the
curved wall, 90 degrees of a cylinder of radius 4 m in 16 facets, which is the opening domain. The
room has a UV map (on the curved wall, the facets unfolded: u the length along them, v the
height); so has a plinth exported before it; a shelf in the room has none. The add-on's
results.apply puts a hand-written result into the model: a curved opening (its surface grid on
the facets, normals interpolated between the facets' edges) and a flat one on a flat wall. Rays
cast on the evaluated depsgraph from inside the room along the surface's normal must leave the
room through the openings and hit the wall just beside them. The add-on must be on Blender's
add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import json
import os
import re
import sys
import unittest

import bmesh
import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402
from addon_holes import cast, mesh_object, reset  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_curved_test"
RADIUS, FACETS, ARC, H = 4.0, 16, np.pi / 2, 2.7
FACET = 2 * RADIUS * np.sin(ARC / FACETS / 2)  # a facet's width, m
# The curved opening: u from, u to (along the facets, m), v from, v to (height), and its grid
# (columns not on the facets' edges, so the cutter's faces cross them).
CURVED = (1.6, 3.6, 0.8, 2.0)
ROWS, COLUMNS = 4, 7
# The flat opening on the wall along the x axis (y = 0, outward -y): x from, x to, z from, z to.
FLAT = (1.0, 2.0, 0.8, 1.8)
FLAT_OUTWARD = np.array([0.0, -1.0, 0.0])


def ring(k):
    """The curved wall's k-th vertical edge (0..FACETS), at floor height."""
    angle = k * ARC / FACETS
    return np.array([RADIUS * np.cos(angle), RADIUS * np.sin(angle), 0.0])


def surface(u, v):
    """(point, outward unit normal) on the curved wall at u along the facets and height v; the
    normal is interpolated between the facet edges' (radial) normals."""
    k = min(int(u // FACET), FACETS - 1)
    t = u / FACET - k
    a, b = ring(k), ring(k + 1)
    point = (1 - t) * a + t * b + np.array([0.0, 0.0, v])
    normal = (1 - t) * a + t * b
    return point, normal / np.linalg.norm(normal)


def room():
    """The quarter-cylinder room, closed, its curved wall the domain and unfolded in its UV map
    (the other faces projected on a plane, so the map has seams)."""
    bottom = [ring(k) for k in range(FACETS + 1)]
    verts = bottom + [p + (0, 0, H) for p in bottom] + [(0, 0, 0), (0, 0, H)]
    top, axis = FACETS + 1, 2 * (FACETS + 1)
    curved = [(k, k + 1, top + k + 1, top + k) for k in range(FACETS)]
    faces = curved + [
        tuple([axis] + list(range(FACETS, -1, -1))),                   # floor
        tuple([axis + 1] + [top + k for k in range(FACETS + 1)]),      # ceiling
        (axis, 0, top, axis + 1),                                      # the wall along x
        (axis, axis + 1, top + FACETS, FACETS),                        # the wall along y
    ]
    obj = mesh_object("Room", verts, faces, domain=set(range(FACETS)))
    mesh = obj.data
    polygon_of = np.empty(len(mesh.loops), int)
    for p in mesh.polygons:
        polygon_of[p.loop_start:p.loop_start + p.loop_total] = p.index
    uv = []
    for loop in mesh.loops:
        p, i = mesh.polygons[polygon_of[loop.index]], loop.vertex_index
        x, y, z = mesh.vertices[i].co
        if p.index < FACETS:
            uv.append(((i % top) * FACET, z))
        elif abs(p.normal.z) > 0.5:
            uv.append((x, y))
        else:
            uv.append((x + y, z))
    mesh.uv_layers.new(name="Unfolded").data.foreach_set("uv", np.ravel(uv))
    mesh.update()
    return obj


def box(name, lo, hi, uv_map):
    """A box near the axis, out of the rays' way; with uv_map, each face mapped to the unit square."""
    verts = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (1, 3, 7, 5), (3, 2, 6, 7), (2, 0, 4, 6)]
    obj = mesh_object(name, verts, faces)
    if uv_map:
        square = [(0, 0), (1, 0), (1, 1), (0, 1)] * len(faces)
        obj.data.uv_layers.new(name="Faces").data.foreach_set("uv", np.ravel(square))
    return obj


def setup():
    export = installed.blender("study.export")
    reset()
    box("Plinth", (0.3, 0.9, 0.0), (0.6, 1.2, 0.3), uv_map=True)  # before the room: its vt come first
    room()
    box("Shelf", (0.3, 0.3, 0.0), (0.8, 0.8, 0.4), uv_map=False)
    sensors = mesh_object("Sensors", [(1.0, 1.0, 0.8), (2.0, 1.0, 0.8), (1.0, 2.0, 0.8), (2.0, 2.0, 0.8)], [])
    sensors.fenestra.is_sensor = True
    f = bpy.context.scene.fenestra
    f.solve.element_size = 0.25
    f.sky.type = 'UNIFORM'
    return export.build(bpy.context)


def curved_opening():
    """The curved opening as the solver gives it."""
    u0, u1, v0, v1 = CURVED
    grid = [surface(u, v) for v in np.linspace(v0, v1, ROWS) for u in np.linspace(u0, u1, COLUMNS)]
    points, normals = np.array([g[0] for g in grid]), np.array([g[1] for g in grid])
    corners = [surface(u, v)[0].tolist() for u, v in ((u0, v0), (u1, v0), (u1, v1), (u0, v1))]
    centre, normal = surface((u0 + u1) / 2, (v0 + v1) / 2)
    return {"corners": corners, "centre": centre.tolist(), "width": u1 - u0, "height": v1 - v0,
            "normal": normal.tolist(), "depth": 0.0, "panel": 0, "curved": True,
            "parameter_rectangle": {"u0": u0, "u1": u1, "v0": v0, "v1": v1},
            "surface_grid": {"rows": ROWS, "columns": COLUMNS, "points": points.tolist(),
                             "normals": normals.tolist()}}


def flat_opening():
    x0, x1, z0, z1 = FLAT
    corners = [[x0, 0.0, z0], [x1, 0.0, z0], [x1, 0.0, z1], [x0, 0.0, z1]]
    return {"corners": corners, "centre": np.mean(corners, axis=0).tolist(), "width": x1 - x0,
            "height": z1 - z0, "normal": FLAT_OUTWARD.tolist(), "depth": 0.0, "panel": 1, "curved": False,
            "parameter_rectangle": {"u0": x0, "u1": x1, "v0": z0, "v1": z1}}


def apply(study):
    results = installed.blender("result.results")
    count = sum(c for _, c in study.sensor_objects)
    results.apply(bpy.context, study, {
        "openings": [curved_opening(), flat_opening()],
        "sensors": [{"goal": 100.0, "predicted": 90.0}] * count,
        "error": {"relative_rms": 0.1}, "open_elements": [], "element_count": 0})


def parse_obj(text):
    """{group: [triangle corners as (v, vt or None)]}, the v and vt coordinates, and {group: index
    of its object's first v}."""
    v, vt, groups, group, first, start, previous = [], [], {}, None, {}, 0, None
    for line in text.splitlines():
        word, *rest = line.split()
        if word == "v":
            start = len(v) if previous != "v" else start
            v.append([float(x) for x in rest])
        elif word == "vt":
            vt.append([float(x) for x in rest])
        elif word == "g":
            group, first[rest[0]] = groups.setdefault(rest[0], []), start
        elif word == "f":
            corners = [tuple(int(i) - 1 for i in c.split("/")) for c in rest]
            group.append([(c[0], c[1] if len(c) > 1 else None) for c in corners])
        previous = word
    return groups, np.array(v), np.array(vt), first


def by_vertices(triangles):
    """{vertex indices from the least one: UVs of those corners} of [(vertex indices, UVs)]."""
    table = {}
    for vertices, uvs in triangles:
        start = int(np.argmin(vertices))
        table[tuple(np.roll(vertices, -start))] = np.roll(uvs, -start, axis=0)
    return table


def blender_triangles(mesh):
    """The mesh's loop triangles: (vertex indices, UVs of their corners)."""
    mesh.calc_loop_triangles()
    uv = mesh.uv_layers.active.data
    return [(list(t.vertices), np.array([uv[i].uv for i in t.loops])) for t in mesh.loop_triangles]


class CurvedWall(unittest.TestCase):
    def test_export_writes_the_uv_map(self):
        """The triangles of the room and the plinth come back from the OBJ with their UVs at every
        corner; the shelf, without a UV map, has plain faces; vertices and faces are written as
        without UVs, and the native module reads the file."""
        study = setup()
        groups, v, vt, first = parse_obj(study.obj_text)
        self.assertEqual(sorted(groups), ["Plinth", "Room", "Room.domain", "Shelf"])
        self.assertEqual(study.scene["opening_domain"]["groups"], ["Room.domain"])
        self.assertTrue(all(t is None for f in groups["Shelf"] for _, t in f))
        for name, names in (("Plinth", ["Plinth"]), ("Room", ["Room", "Room.domain"])):
            faces, base = [f for g in names for f in groups[g]], first[names[0]]
            self.assertTrue(all(t is not None for f in faces for _, t in f))
            # The object's vertices in their order; its triangles with their corners' UVs.
            mesh = bpy.data.objects[name].data
            np.testing.assert_allclose(v[base:base + len(mesh.vertices)], [p.co for p in mesh.vertices], atol=1e-6)
            exported = by_vertices([([i - base for i, _ in f], vt[[t for _, t in f]]) for f in faces])
            expected = by_vertices(blender_triangles(mesh))
            self.assertEqual(sorted(exported), sorted(expected))
            for key, uvs in expected.items():
                np.testing.assert_allclose(exported[key], uvs, atol=1e-6)
        room_faces = groups["Room"] + groups["Room.domain"]
        # The domain's corners: u along the facets and v the height, as mapped.
        for f in groups["Room.domain"]:
            for i, t in f:
                angle = np.arctan2(v[i][1], v[i][0])
                self.assertAlmostEqual(vt[t][0], round(angle / (ARC / FACETS)) * FACET, places=5)
                self.assertAlmostEqual(vt[t][1], v[i][2], places=5)
        # One vt per distinct UV of an object (the plinth's 4; the room's corners share them along
        # the facets' edges, and more at the seams).
        self.assertEqual(len(vt), 4 + len({tuple(vt[t]) for f in room_faces for _, t in f}))
        self.assertLess(len(vt), 4 + sum(len(f) for f in room_faces))
        import fenestra
        study.write(os.path.join(OUT, "export"))
        self.assertEqual(fenestra.load_scene(study.scene_path).triangle_count, len(sum(groups.values(), [])))
        # Without UV maps the same v and f lines are written, minus the vt.
        for name in ("Plinth", "Room"):
            mesh = bpy.data.objects[name].data
            mesh.uv_layers.remove(mesh.uv_layers.active)
            mesh.update()  # (4.5 does not tag the mesh for the depsgraph on its own; the UI's edits do)
        export = installed.blender("study.export")
        plain = export.build(bpy.context).obj_text
        stripped = "\n".join(re.sub(r"/\d+", "", line) for line in study.obj_text.splitlines()
                             if not line.startswith("vt ")) + "\n"
        self.assertEqual(stripped, plain)
        self.assertNotIn("vt ", plain)

    def check_curved_hole(self):
        """From 1 m inside along the surface's normal: through 12 points of the curved opening and
        through the facets' edges in it the rays reach the sky, 5 cm beyond each of its edges they
        hit the wall at the surface."""
        u0, u1, v0, v1 = CURVED
        um, vm = (u0 + u1) / 2, (v0 + v1) / 2
        through = [(u, v) for u in np.linspace(u0 + 0.05, u1 - 0.05, 4)
                   for v in np.linspace(v0 + 0.05, v1 - 0.05, 3)]
        through += [(k * FACET, vm) for k in range(FACETS) if u0 + 0.05 < k * FACET < u1 - 0.05]
        for u, v in through:
            p, n = surface(u, v)
            self.assertIsNone(cast(p - n, n), "a face across the opening at u %.2f v %.2f" % (u, v))
        for u, v in ((u0 - 0.05, vm), (u1 + 0.05, vm), (um, v0 - 0.05), (um, v1 + 0.05)):
            p, n = surface(u, v)
            hit = cast(p - n, n)
            self.assertIsNotNone(hit, "no wall beside the opening at u %.2f v %.2f" % (u, v))
            self.assertEqual(hit[0], "Room")
            np.testing.assert_allclose(hit[1], p, atol=1e-4)
        modified = [o.name for o in bpy.data.objects if any(m.name == "Fenestra Openings" for m in o.modifiers)]
        self.assertEqual(modified, ["Room"])  # not the shelf nor the plinth

    def test_rays_leave_through_the_curved_opening(self):
        apply(setup())
        self.check_curved_hole()

    def test_the_least_margin_reaches_through_the_facets(self):
        """With no margin set, the cutter still spans the wall where its faces cut across the
        facets' edges, which stand out from them."""
        study = setup()
        bpy.context.scene.fenestra.solve.cutter_margin = 0.0
        apply(study)
        self.check_curved_hole()

    def test_rays_leave_through_the_flat_opening(self):
        apply(setup())
        x0, x1, z0, z1 = FLAT
        n = FLAT_OUTWARD
        for x in np.linspace(x0 + 0.05, x1 - 0.05, 3):
            for z in np.linspace(z0 + 0.05, z1 - 0.05, 3):
                self.assertIsNone(cast(np.array([x, 0.0, z]) - n, n), "a face across at x %.2f z %.2f" % (x, z))
        xm, zm = (x0 + x1) / 2, (z0 + z1) / 2
        for x, z in ((x0 - 0.05, zm), (x1 + 0.05, zm), (xm, z0 - 0.05), (xm, z1 + 0.05)):
            hit = cast(np.array([x, 0.0, z]) - n, n)
            self.assertIsNotNone(hit, "no wall beside the opening at x %.2f z %.2f" % (x, z))
            self.assertAlmostEqual(hit[1][1], 0.0, places=4)

    def test_curved_cutter_follows_the_surface(self):
        """A closed solid through the grid: each grid point's normal line carries a room-side vertex
        (on the room side, flagged faces only) and a far one, the grid's outline the surface."""
        results = installed.blender("result.results")
        apply(setup())
        obj = bpy.data.objects["Fenestra Opening 001"]
        mesh = obj.data
        verts = np.array([obj.matrix_world @ v.co for v in mesh.vertices])
        ring = 2 * (ROWS - 1) + 2 * (COLUMNS - 1)
        self.assertEqual(len(verts), 2 * ROWS * COLUMNS + ring)
        self.assertEqual(len(mesh.polygons), 2 * (ROWS - 1) * (COLUMNS - 1) + 2 * ring)
        bm = bmesh.new()
        bm.from_mesh(mesh)
        self.assertTrue(all(len(e.link_faces) == 2 for e in bm.edges))  # watertight
        bm.free()
        grid = curved_opening()["surface_grid"]
        points, normals = np.array(grid["points"]), np.array(grid["normals"])
        margin = bpy.context.scene.fenestra.solve.cutter_margin
        offsets = []
        for p, n in zip(points, normals):
            d = verts - p
            along = d @ n
            a = np.sort(along[np.linalg.norm(d - along[:, None] * n, axis=1) < 1e-5])
            self.assertIn(len(a), (2, 3))  # the outline's points are on the surface too
            self.assertAlmostEqual(a[0], -a[-1], places=5)  # depth 0: as far out as in
            if len(a) == 3:
                self.assertAlmostEqual(a[1], 0.0, places=5)
            offsets.append(a[-1])
        # Margin, plus the surface's bow between grid points (facet edges between the columns).
        self.assertGreater(min(offsets), margin)
        self.assertLess(max(offsets), margin + 0.02)
        flags = np.zeros(len(mesh.polygons), bool)
        mesh.attributes[installed.blender("com.names").ROOM_SIDE_ATTRIBUTE].data.foreach_get("value", flags)
        self.assertEqual(flags.sum(), (ROWS - 1) * (COLUMNS - 1) + ring)
        radius = np.linalg.norm(verts[:, :2], axis=1)
        for polygon, flag in zip(mesh.polygons, flags):
            r = radius[list(polygon.vertices)]
            # Flagged: toward the axis from the facets (within their chords); the rest beyond them.
            if flag:
                self.assertLess(r.max(), RADIUS + 1e-5)
            else:
                self.assertGreater(r.max(), RADIUS)

    def test_real_solve_cuts_the_curved_wall(self):
        """A real Preview solve on the curved wall (diced in its UV map): the result's openings are
        curved, their surface grid on the facets, and rays through them leave the room."""
        setup()
        s = bpy.context.scene.fenestra.solve
        s.element_size, s.quality, s.paths, s.generations, s.population = 0.4, 'CUSTOM', 512, 20, 16
        s.study_directory = os.path.join(OUT, "solve_study")
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        with open(os.path.join(OUT, "solve_study", "result.json")) as f:
            result = json.load(f)
        self.assertGreaterEqual(len(result["openings"]), 1)
        for opening in result["openings"]:
            self.assertTrue(opening["curved"])
            points = np.array(opening["surface_grid"]["points"])
            normals = np.array(opening["surface_grid"]["normals"])
            # On the facets: between the chord's distance from the axis and the radius.
            radius = np.linalg.norm(points[:, :2], axis=1)
            self.assertTrue(np.all(radius <= RADIUS + 1e-4))
            self.assertTrue(np.all(radius >= RADIUS * np.cos(ARC / FACETS / 2) - 1e-4))
            self.assertTrue(np.all(np.einsum("ij,ij->i", normals, points * [1, 1, 0]) > 0))  # outward
            # Rays along the normal from inside the room through points well within the opening.
            r = opening["parameter_rectangle"]
            rows, cols = opening["surface_grid"]["rows"], opening["surface_grid"]["columns"]
            inner = [i * cols + j for i in range(1, rows - 1) for j in range(1, cols - 1)] or [0]
            for k in inner[:6]:
                self.assertIsNone(cast(points[k] - 0.5 * normals[k], normals[k]),
                                  "the wall is still across the opening at %s (u %.2f..%.2f)" % (points[k], r["u0"], r["u1"]))

    def test_flat_opening_gets_a_box(self):
        """A flat opening's cutter is the box it always was: 12 vertices, 10 faces, 5 on the room side."""
        results = installed.blender("result.results")
        apply(setup())
        obj = bpy.data.objects["Fenestra Opening 002"]
        mesh = obj.data
        corner = lambda p: tuple(np.round(p, 4))  # noqa: E731  (the order; 5.0's matrices are float32)
        verts = sorted((tuple(obj.matrix_world @ v.co) for v in mesh.vertices), key=corner)
        margin = bpy.context.scene.fenestra.solve.cutter_margin
        x0, x1, z0, z1 = FLAT
        box = sorted(((x, y, z) for x in (x0, x1) for y in (margin, 0.0, -margin) for z in (z0, z1)), key=corner)
        np.testing.assert_allclose(verts, box, atol=1e-6)
        self.assertEqual(len(mesh.polygons), 10)
        flags = np.zeros(10, bool)
        mesh.attributes[installed.blender("com.names").ROOM_SIDE_ATTRIBUTE].data.foreach_get("value", flags)
        self.assertEqual(flags.tolist(), [True] * 5 + [False] * 5)
        for polygon, flag in zip(mesh.polygons, flags):  # the room is at y > 0
            y = [obj.matrix_world @ mesh.vertices[i].co for i in polygon.vertices]
            self.assertTrue(all(p.y >= 0 for p in y) if flag else all(p.y <= 0 for p in y))


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    reset()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
