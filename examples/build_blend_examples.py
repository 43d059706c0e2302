"""Builds the Blender examples procedurally and saves them as .blend files set up for Fenestra.

    blender -b --factory-startup --python examples/build_blend_examples.py -- OUTDIR [NAME ...]
            [--studies DIR] [--solve] [--render]

Each example NAME is saved as OUTDIR/NAME.blend with the add-on's settings in place (domain faces
marked with the `fenestra_domain` attribute through Mark Selected Faces, sensor grids made by Add
Sensor Grid, goals uniform or painted on the sensors' `fenestra_goal` colour attribute, sky, solve
settings), and exported, with the add-on's own export, as a study folder NAME_study/ (scene.json +
scene.obj, runnable with `fenestra solve`) under --studies (default OUTDIR). The museum's study
(about 6.5 MB of OBJ) is always written under OUTDIR.

room         a 5 x 4 x 2.8 m room on a ground plane; its south wall is the opening domain. Uniform
             goal, half the light of the wall fully open; Preetham sky and sun, 21 March 9-17 h, Paris;
             openings at least 0.5 m wide and 0.75 m high, sills at least 0.5 m up.
apartment    four 4 x 6 m rooms in a row joined by doors; the south and north facades are the
             opening domain. Goals painted as in the paper's Figure 1: bright (0.85 of the all-open
             light) in the two west rooms, dark (0.05) in the other two; Preetham sky and sun, sill
             and head heights constrained.
museum       a 12 x 12 x 9 m atrium with a gallery floor around a central void and three statues
             (subdivided heads on plinths, about 190 000 triangles in all); the roof is the opening
             domain. Goals painted: the most light around the statues, little on the rest of the
             ground floor, dark on the gallery (0.5, 0.15 and 0.05 of the all-open light); uniform sky.
thick_walls  the room with 0.3 m solid walls; the south wall is modelled by its inner face, a plane
             that is the opening domain, and Wall Thickness is 0.3 m: the estimate sees a
             zero-thickness wall (as in the paper), the cutters go 0.3 m deep and the solver's check
             path-traces the openings with real reveals (result.json: `predicted` against
             `verified`, the reveals' loss). CIE overcast sky, daylight-factor goal, at most two openings
             with their sills at least 0.75 m up.

--solve runs Solve Openings on each example (study folder OUTDIR/NAME_solved_study/) and saves
OUTDIR/NAME_solved.blend; --render also previews the study's sky in the World, adds the study's
suns as Sun lights, applies the openings as Boolean differences and renders OUTDIR/NAME_render.png
with Cycles (small and quick: a view of the openings and, with the ceiling hidden from the camera,
of the rooms). Needs the Fenestra add-on: the installed one (make install-addon), else this
checkout's addon/ folder.
"""

import argparse
import json
import math
import os
import sys
import time

import addon_utils
import bmesh
import bpy
import numpy as np
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = ("room", "apartment", "museum", "thick_walls")
LARGE = {"museum"}  # studies too large to keep in the repository


# The add-on ------------------------------------------------------------------------------------

def enable_addon():
    """Enables the installed add-on, else registers this checkout's addon/fenestra."""
    try:
        addon_utils.enable("fenestra", default_set=True, handle_error=None)
    except Exception:
        pass
    if not hasattr(bpy.types.Scene, "fenestra"):
        sys.path.insert(0, os.path.join(HERE, "..", "addon"))
        import fenestra
        fenestra.register()
    assert hasattr(bpy.types.Scene, "fenestra"), "the Fenestra add-on could not be enabled"


def new_file():
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.context.preferences.filepaths.save_version = 0  # no .blend1 backups
    enable_addon()


# Geometry --------------------------------------------------------------------------------------

def material(name, color, roughness=1.0, metallic=0.0):
    m = bpy.data.materials.get(name)
    if m is None:
        m = bpy.data.materials.new(name)
        m.use_nodes = True
        p = m.node_tree.nodes["Principled BSDF"]
        p.inputs["Base Color"].default_value = (*color, 1.0)
        p.inputs["Roughness"].default_value = roughness
        p.inputs["Metallic"].default_value = metallic
        m.diffuse_color = (*color, 1.0)
    return m


def mesh_object(name, verts, faces, mats, face_mats=None, recalc=True):
    """A mesh object from vertices and faces; with recalc, face normals made consistent (outward
    on a closed or open shell) so Boolean differences cut it cleanly."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(map(float, v)) for v in verts], [], [tuple(f) for f in faces])
    for m in mats:
        mesh.materials.append(m)
    if face_mats is not None:
        mesh.polygons.foreach_set("material_index", list(face_mats))
    bm = bmesh.new()
    bm.from_mesh(mesh)
    if recalc:
        bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    bm.to_mesh(mesh)
    bm.free()
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


BOX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
# indices in BOX_FACES: bottom, top, south (y lo), east (x hi), north (y hi), west (x lo)
BOTTOM, TOP, SOUTH, EAST, NORTH, WEST = range(6)


def box_verts(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
            (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]


def box(name, lo, hi, mat):
    return mesh_object(name, box_verts(lo, hi), BOX_FACES, [mat])


def ground(size=80.0, z=-0.05):
    h = size / 2
    return mesh_object("Ground", [(-h, -h, z), (h, -h, z), (h, h, z), (-h, h, z)], [(0, 1, 2, 3)],
                       [material("Ground", (0.2, 0.2, 0.2))])


def partition(name, x, y0, y1, h, door, mat):
    """A zero-thickness wall at x from y0 to y1 with a door opening (y from, y to, height)."""
    a, b, dh = door
    verts = [(x, y0, 0), (x, a, 0), (x, a, dh), (x, b, dh), (x, b, 0), (x, y1, 0),
             (x, y1, h), (x, b, h), (x, a, h), (x, y0, h)]
    faces = [(0, 1, 8, 9), (2, 3, 7, 8), (4, 5, 6, 7)]  # beside, above and beyond the door
    return mesh_object(name, verts, faces, [mat])


def ring_slab(name, outer, inner, z0, z1, mat):
    """A slab between two rectangles (x0, y0, x1, y1), outer around inner: a gallery floor."""
    def loop(r, z):
        x0, y0, x1, y1 = r
        return [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]
    verts = loop(outer, z0) + loop(inner, z0) + loop(outer, z1) + loop(inner, z1)
    faces = []
    for i in range(4):
        j = (i + 1) % 4
        faces.append((i, j, 4 + j, 4 + i))            # bottom
        faces.append((8 + i, 12 + i, 12 + j, 8 + j))  # top
        faces.append((i, 8 + i, 8 + j, j))            # outer side
        faces.append((4 + i, 4 + j, 12 + j, 12 + i))  # inner side
    return mesh_object(name, verts, faces, [mat])


# The add-on's setup, through its operators -----------------------------------------------------

def select_only(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def mark_domain(obj, faces):
    """Marks the given faces of obj as opening domain with Mark Selected Faces (Edit Mode)."""
    select_only(obj)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_mode(type='FACE')
    bpy.ops.mesh.select_all(action='DESELECT')
    bpy.ops.object.mode_set(mode='OBJECT')
    for i in faces:
        obj.data.polygons[i].select = True
    bpy.ops.object.mode_set(mode='EDIT')
    assert bpy.ops.fenestra.mark_domain() == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')


def sensor_grid(floor, name, height, spacing, keep=None):
    """Add Sensor Grid over floor; vertices where keep(x, y, z) is False are removed."""
    f = bpy.context.scene.fenestra
    f.sensor_height, f.sensor_spacing = height, spacing
    select_only(floor)
    assert bpy.ops.fenestra.add_sensor_grid() == {'FINISHED'}
    obj = bpy.data.objects["Fenestra Sensors"]
    obj.name = obj.data.name = name
    if keep is not None:
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        gone = [v for v in bm.verts if not keep(*v.co)]
        bmesh.ops.delete(bm, geom=gone, context='VERTS')
        bm.to_mesh(obj.data)
        bm.free()
    return obj


def paint_goals(obj, goal_of):
    """Paints the `fenestra_goal` colour attribute: grey level goal_of(x, y, z) per vertex."""
    mesh = obj.data
    attr = mesh.attributes["fenestra_goal"]
    co = np.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3) @ np.array(obj.matrix_world)[:3, :3].T + np.array(obj.matrix_world)[:3, 3]
    level = np.array([goal_of(*p) for p in co])
    rgba = np.repeat(level[:, None], 4, axis=1)
    rgba[:, 3] = 1.0
    attr.data.foreach_set("color_srgb", rgba.ravel())
    mesh.update()


def temporary_floor(x0, y0, x1, y1):
    """A plane to lay a sensor grid on (removed afterwards)."""
    return mesh_object("Sensor floor", [(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0)], [(0, 1, 2, 3)], [])


def remove(obj):
    mesh = obj.data
    bpy.data.objects.remove(obj)
    bpy.data.meshes.remove(mesh)


def preetham(sky, month=3, day=21, start=9.0, end=17.0, step=15.0):
    sky.type, sky.use_sun_position = 'PREETHAM', False
    sky.latitude, sky.longitude, sky.utc_offset, sky.north_offset = 48.85, 2.35, 1.0, 0.0
    sky.year, sky.month, sky.day = 2026, month, day
    sky.start_time, sky.end_time, sky.step_minutes = start, end, step
    sky.turbidity, sky.ground_reflectance, sky.map_width = 3.0, 0.2, 512


def camera(location, target, lens=24.0, name="Camera"):
    cam = bpy.data.objects.new(name, bpy.data.cameras.new(name))
    cam.data.lens = lens
    cam.data.clip_end = 500
    bpy.context.scene.collection.objects.link(cam)
    cam.location = location
    cam.rotation_euler = (Vector(target) - Vector(location)).to_track_quat('-Z', 'Y').to_euler()
    bpy.context.scene.camera = cam
    return cam


# The examples ----------------------------------------------------------------------------------

PLASTER = (0.6, 0.6, 0.6)


def build_room():
    w, d, h = 5.0, 4.0, 2.8
    shell = mesh_object("Room", box_verts((0, 0, 0), (w, d, h)), BOX_FACES[:1] + BOX_FACES[2:],
                        [material("Plaster", PLASTER), material("Floor", (0.35, 0.3, 0.25))],
                        face_mats=[1, 0, 0, 0, 0])
    ceiling = mesh_object("Ceiling", box_verts((0, 0, 0), (w, d, h))[4:], [(0, 1, 2, 3)],
                          [material("Ceiling", (0.8, 0.8, 0.8))])
    ground()
    mark_domain(shell, [SOUTH - 1])  # the south wall (the top face is the separate ceiling)
    sensor_grid(shell, "Sensors", 0.8, 0.5)
    f = bpy.context.scene.fenestra
    f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'NORMALIZED', 0.5
    preetham(f.sky)
    s = f.solve
    s.element_size, s.wall_thickness, s.quality = 0.25, 0.0, 'PREVIEW'
    s.constraints.min_width, s.constraints.min_height, s.constraints.sill_min = 0.5, 0.75, 0.5
    camera((w / 2 - 6.5, -7.5, 6.0), (w / 2, d / 2, 0.6))
    return {"cutaway": [ceiling.name]}


def build_apartment():
    rooms, d, h = 4, 6.0, 2.8
    w = 4.0 * rooms
    # Floor and the four outer walls (the facades south and north); the ceiling is its own object.
    shell = mesh_object("Apartment", box_verts((0, 0, 0), (w, d, h)), BOX_FACES[:1] + BOX_FACES[2:],
                        [material("Plaster", PLASTER), material("Floor", (0.35, 0.3, 0.25))],
                        face_mats=[1, 0, 0, 0, 0])
    ceiling = mesh_object("Ceiling", box_verts((0, 0, 0), (w, d, h))[4:], [(0, 1, 2, 3)],
                          [material("Ceiling", (0.8, 0.8, 0.8))])
    for i in range(1, rooms):
        partition("Partition %d" % i, 4.0 * i, 0.0, d, h, (2.6, 3.5, 2.1), material("Plaster", PLASTER))
    ground()
    mark_domain(shell, [SOUTH - 1, NORTH - 1])
    sensors = sensor_grid(shell, "Sensors", 0.8, 1.0)
    # The paper's Figure 1: bright in the two west rooms, dark in the others.
    paint_goals(sensors, lambda x, y, z: 0.85 if x < 8.0 else 0.05)
    f = bpy.context.scene.fenestra
    f.goals.source, f.goals.units, f.goals.scale = 'ATTRIBUTE', 'NORMALIZED', 1.0
    preetham(f.sky, step=60.0)
    s = f.solve
    s.element_size, s.wall_thickness, s.quality = 0.4, 0.0, 'PREVIEW'
    s.constraints.sill_min, s.constraints.head_max = 0.4, 2.4
    s.constraints.min_width, s.constraints.min_height, s.constraints.min_gap = 0.8, 0.8, 0.4
    camera((-1.5, -9.0, 11.0), (w / 2 - 0.5, d / 2 + 0.5, 0.0), lens=24.0)
    return {"cutaway": [ceiling.name]}


def statue(name, location, rotation, size, levels):
    """A head on a plinth: Suzanne subdivided `levels` times, modifiers applied."""
    bpy.ops.mesh.primitive_monkey_add(size=size, location=location, rotation=rotation)
    head = bpy.context.active_object
    head.name = head.data.name = name
    m = head.modifiers.new("Subdivision", 'SUBSURF')
    m.levels = m.render_levels = levels
    bpy.ops.object.modifier_apply(modifier=m.name)
    bpy.ops.object.shade_smooth()
    head.data.materials.append(material("Marble", (0.85, 0.83, 0.8), roughness=0.35))
    return head


def build_museum():
    w, h, gallery = 12.0, 9.0, 4.5
    void = (3.0, 3.0, 9.0, 9.0)
    stone = material("Stone", (0.55, 0.52, 0.48))
    shell = mesh_object("Atrium", box_verts((0, 0, 0), (w, w, h)), BOX_FACES,
                        [stone, material("Floor", (0.3, 0.28, 0.26)), material("Roof", (0.7, 0.7, 0.7))],
                        face_mats=[1, 2, 0, 0, 0, 0])
    # The gallery floor, 1 cm off the walls (no coplanar faces).
    slab = ring_slab("Gallery", (0.01, 0.01, w - 0.01, w - 0.01), void, gallery - 0.3, gallery, stone)
    ground()
    statues = [((4.5, 6.0), 0.0), ((7.5, 4.5), 2.2), ((7.5, 7.5), -2.2)]
    plinth = material("Plinth", (0.25, 0.25, 0.27))
    for i, ((x, y), turn) in enumerate(statues):
        box("Plinth %d" % (i + 1), (x - 0.4, y - 0.4, 0.0), (x + 0.4, y + 0.4, 1.0), plinth)
        statue("Statue %d" % (i + 1), (x, y, 1.55), (0.0, 0.0, turn), 1.1, 3)
    mark_domain(shell, [TOP])
    f = bpy.context.scene.fenestra

    def off_plinths(x, y, z):
        return all(max(abs(x - sx), abs(y - sy)) > 0.55 for (sx, sy), _ in statues)

    floor = temporary_floor(0.01, 0.01, w - 0.01, w - 0.01)
    ground_floor = sensor_grid(floor, "Ground floor sensors", 0.8, 1.0, keep=off_plinths)
    remove(floor)
    near = lambda x, y: min(math.hypot(x - sx, y - sy) for (sx, sy), _ in statues)
    paint_goals(ground_floor, lambda x, y, z: 0.5 if near(x, y) < 1.6 else 0.15)
    upper = sensor_grid(slab, "Gallery sensors", 0.8 + 0.3, 1.5)
    paint_goals(upper, lambda x, y, z: 0.05)
    f.goals.source, f.goals.units, f.goals.scale = 'ATTRIBUTE', 'NORMALIZED', 1.0
    f.sky.type, f.sky.horizontal_illuminance = 'UNIFORM', 10000.0
    s = f.solve
    s.element_size, s.wall_thickness, s.quality = 0.5, 0.0, 'PREVIEW'
    camera((-7.0, -9.0, 16.0), (w / 2, w / 2, 2.0), lens=20.0)
    return {"cutaway": []}


def build_thick_walls():
    w, d, h, t = 5.0, 4.0, 2.8, 0.3
    # Floor, ceiling and three walls as one 0.3 m solid around the room, open to the south; the
    # south wall is modelled at its inner face (a plane: the domain, zero thickness as the
    # estimate sees it) and Wall Thickness gives the cutters their depth and the check its reveals.
    inner = box_verts((0, 0, 0), (w, d, h))
    outer = box_verts((-t, 0, -t), (w + t, d + t, h + t))
    faces = [tuple(i + 8 for i in f) for k, f in enumerate(BOX_FACES) if k != SOUTH]   # outward
    faces += [tuple(reversed(f)) for k, f in enumerate(BOX_FACES) if k != SOUTH]       # into the room
    south_in, south_out = (0, 1, 5, 4), (8, 9, 13, 12)
    faces += [(south_out[i], south_out[(i + 1) % 4], south_in[(i + 1) % 4], south_in[i]) for i in range(4)]
    mesh_object("Walls", inner + outer, faces, [material("Plaster", PLASTER)])
    south = mesh_object("South wall", [inner[i] for i in south_in], [(0, 1, 2, 3)],
                        [material("Plaster", PLASTER)])
    ground(z=-t - 0.01)
    mark_domain(south, [0])
    floor = temporary_floor(0.0, 0.0, w, d)
    sensor_grid(floor, "Sensors", 0.8, 0.5)
    remove(floor)
    f = bpy.context.scene.fenestra
    f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'DAYLIGHT_FACTOR', 3.0
    f.goals.use_min, f.goals.min = True, 1.5
    f.sky.type, f.sky.horizontal_illuminance, f.sky.ground_reflectance = 'CIE_OVERCAST', 10000.0, 0.2
    f.sky.map_width = 512
    s = f.solve
    s.element_size, s.wall_thickness, s.quality = 0.25, t, 'PREVIEW'
    s.constraints.max_openings, s.constraints.sill_min = 2, 0.75
    camera((w / 2 - 5.0, -7.0, 3.5), (w / 2, 0.0, 1.2), lens=28.0)
    return {"cutaway": []}


BUILDERS = {"room": build_room, "apartment": build_apartment, "museum": build_museum,
            "thick_walls": build_thick_walls}


# Export, solve, render -------------------------------------------------------------------------

def export_study(directory):
    """The study as the add-on exports it for a solve: scene.json + scene.obj."""
    from fenestra.blender.study import export
    study = export.build(bpy.context)
    study.write(directory)
    return study


def triangles():
    depsgraph = bpy.context.evaluated_depsgraph_get()
    n = 0
    for obj in bpy.context.scene.objects:
        if obj.type == 'MESH' and not obj.fenestra.is_sensor and not obj.fenestra.is_opening:
            mesh = obj.evaluated_get(depsgraph).to_mesh()
            mesh.calc_loop_triangles()
            n += len(mesh.loop_triangles)
            obj.evaluated_get(depsgraph).to_mesh_clear()
    return n


def add_suns(study_dir):
    """The study's suns as Sun lights, each at its share of the interval, scaled as the World."""
    import fenestra
    f = bpy.context.scene.fenestra
    summary = fenestra.sky(fenestra.load_scene(os.path.join(study_dir, "scene.json")))
    for i, sun in enumerate(summary.get("suns", [])):
        light = bpy.data.lights.new("Sun %02d" % i, 'SUN')
        light.energy = sun["weight"] * sun["normal_illuminance"] * f.sky.preview_strength
        light.angle = math.radians(0.53)
        obj = bpy.data.objects.new(light.name, light)
        obj.rotation_euler = Vector(sun["direction"]).to_track_quat('Z', 'Y').to_euler()
        bpy.context.scene.collection.objects.link(obj)
    return len(summary.get("suns", []))


def render(path, cutaway, samples=128, resolution=(640, 360), exposure=-3.0):
    scene = bpy.context.scene
    for name in cutaway:  # lit by, but not seen through, the camera
        bpy.data.objects[name].visible_camera = False
    # The openings cut for good: the cutters are hidden from renders, so the result's modifiers
    # (the Boolean, then the one that opens the holes) are applied.
    from fenestra.blender.study import export
    for obj in list(scene.objects):
        for name in [m.name for m in obj.modifiers if export.is_result_modifier(m)]:
            select_only(obj)
            bpy.ops.object.modifier_apply(modifier=name)
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = True
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 6
    scene.cycles.sample_clamp_indirect = 5.0
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = 'AUTO'
    scene.view_settings.view_transform = 'Filmic'
    scene.view_settings.look = 'Medium High Contrast'
    scene.view_settings.exposure = exposure
    scene.render.image_settings.file_format = 'PNG'
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="build_blend_examples.py")
    parser.add_argument("outdir")
    parser.add_argument("names", nargs="*", default=list(EXAMPLES))
    parser.add_argument("--studies", help="where NAME_study/ folders go (default: OUTDIR)")
    parser.add_argument("--solve", action="store_true")
    parser.add_argument("--render", action="store_true")
    args = parser.parse_args(argv)
    outdir = os.path.abspath(args.outdir)
    os.makedirs(outdir, exist_ok=True)
    report = {}
    for name in args.names:
        if name not in BUILDERS:
            raise SystemExit("unknown example %r (one of %s)" % (name, ", ".join(EXAMPLES)))
        t0 = time.time()
        new_file()
        extra = BUILDERS[name]()
        blend = os.path.join(outdir, name + ".blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend, compress=True)
        base = outdir if (name in LARGE or not args.studies) else os.path.abspath(args.studies)
        study_dir = os.path.join(base, name + "_study")
        study = export_study(study_dir)
        info = {"blend": blend, "study": study_dir, "triangles": triangles(),
                "sensors": len(study.scene["sensors"]["points"]),
                "domain_area_m2": round(study.domain_area, 2), "seconds_build": round(time.time() - t0, 1)}
        print("%-12s %s (%d triangles, %d sensors, %.1f m2 of domain), study %s"
              % (name, blend, info["triangles"], info["sensors"], study.domain_area, study_dir))
        if args.solve:
            f = bpy.context.scene.fenestra
            f.solve.study_directory = os.path.join(outdir, name + "_solved_study")
            t1 = time.time()
            assert bpy.ops.fenestra.solve_openings() == {'FINISHED'}
            r = f.results
            info.update(openings=r.openings, open_elements=r.open_elements, elements=r.elements,
                        relative_rms=r.relative_rms, max_relative=r.max_relative,
                        seconds_solve=round(time.time() - t1, 1), result=os.path.join(
                            f.solve.study_directory, "result.json"))
            print("%-12s solved: %d openings, relative RMS error %.1f %%, worst sensor %.1f %%, %.1f s"
                  % (name, r.openings, 100 * r.relative_rms, 100 * r.max_relative, r.seconds_total))
            if args.render:
                t2 = time.time()
                assert bpy.ops.fenestra.preview_sky() == {'FINISHED'}
                add_suns(f.solve.study_directory)
                image = os.path.join(outdir, name + "_render.png")
                bpy.ops.wm.save_as_mainfile(filepath=os.path.join(outdir, name + "_solved.blend"), compress=True)
                render(image, extra["cutaway"])
                info.update(render=image, seconds_render=round(time.time() - t2, 1))
                print("%-12s rendered %s in %.1f s" % (name, image, time.time() - t2))
            else:
                bpy.ops.wm.save_as_mainfile(filepath=os.path.join(outdir, name + "_solved.blend"), compress=True)
            info["solved_blend"] = os.path.join(outdir, name + "_solved.blend")
        report[name] = info
    with open(os.path.join(outdir, "examples.json"), "w") as f:
        json.dump(report, f, indent=1)


if __name__ == "__main__":
    main()
