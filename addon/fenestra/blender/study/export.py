"""The Blender scene as a Fenestra study: scene.json + scene.obj (docs/scene-format.md).

A pure conversion: evaluated meshes (modifiers and transforms applied) read with foreach_get into
NumPy, nothing in the .blend is changed. Errors are StudyError with a message for the user.
"""

import json
import os
import re

import bpy
import numpy as np

from ..com.names import BOOLEAN_NAME, DOMAIN_ATTRIBUTE, GOAL_ATTRIBUTE, OPEN_THROUGH_NAME
from ..com.study_error import StudyError
from . import climate_goals, materials, sky, visibility

GEOMETRY_TYPES = {'MESH', 'CURVE', 'SURFACE', 'META', 'FONT'}
MAX_ELEMENTS = 50000


class Study:
    """What was exported: the scene-file dict, the OBJ text, and how to map results back."""

    def __init__(self):
        self.scene = None
        self.obj_text = ""
        self.sensor_objects = []   # (object name, vertex count) in sensor order
        self.domain_objects = []   # names of the objects with domain faces
        self.group_objects = {}    # OBJ group -> the name of the object it was written from
        self.triangles = []        # (object name, world vertices, triangles, domain flags), as written
        self.sensor_centroid = np.zeros(3)
        self.domain_area = 0.0
        self.domain_faces = 0
        self.directory = ""

    @property
    def scene_path(self):
        return os.path.join(self.directory, "scene.json")

    def write(self, directory):
        """Writes scene.json and scene.obj (runnable with `fenestra solve scene.json -o result.json`)."""
        os.makedirs(directory, exist_ok=True)
        self.directory = directory
        with open(os.path.join(directory, "scene.obj"), "w") as f:
            f.write(self.obj_text)
        with open(self.scene_path, "w") as f:
            json.dump(self.scene, f, indent=1)
        return self.scene_path


def study_directory(scene):
    """The study folder: the setting, else `<blend name>_fenestra/` next to the .blend file, else
    Blender's temporary folder."""
    chosen = scene.fenestra.solve.study_directory
    if chosen:
        return bpy.path.abspath(chosen)
    if bpy.data.filepath:
        stem = os.path.splitext(bpy.path.basename(bpy.data.filepath))[0]
        return os.path.join(os.path.dirname(bpy.data.filepath), stem + "_fenestra")
    return os.path.join(bpy.app.tempdir or "/tmp", "fenestra_study")


def _safe(name, taken):
    """An OBJ group or material name (no white space), unique among `taken`."""
    base = re.sub(r"\s+", "_", name.strip()) or "unnamed"
    candidate, n = base, 1
    while candidate in taken:
        n += 1
        candidate = "%s.%d" % (base, n)
    taken.add(candidate)
    return candidate


def world_vertices(mesh, matrix):
    co = np.empty(len(mesh.vertices) * 3, np.float64)
    mesh.vertices.foreach_get("co", co)
    m = np.array(matrix, np.float64)
    return co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]


def _world_normals(mesh, matrix):
    """Vertex normals in world space; up for a vertex on no face (Blender gives such a vertex its
    position's direction, which would point a sensor anywhere)."""
    n = np.empty(len(mesh.vertices) * 3, np.float64)
    mesh.vertex_normals.foreach_get("vector", n)
    n = n.reshape(-1, 3) @ np.linalg.inv(np.array(matrix, np.float64)[:3, :3])  # inverse transpose
    corners = np.empty(len(mesh.loops), np.int64)
    mesh.loops.foreach_get("vertex_index", corners)
    n[np.bincount(corners, minlength=len(mesh.vertices)) == 0] = 0.0
    length = np.linalg.norm(n, axis=1)
    n[length < 1e-9] = (0.0, 0.0, 1.0)
    length[length < 1e-9] = 1.0
    return n / length[:, None]


def _corner_uvs(mesh):
    """The active UV map at the loop triangles' corners: (its distinct coordinates as written, the
    index of each corner's among them, shape (triangles, 3)), or None without a UV map. Blender
    keeps a UV per face corner; corners with the same coordinates share one OBJ `vt`."""
    layer = mesh.uv_layers.active
    if layer is None or len(mesh.loops) == 0:
        return None
    uv = np.empty(len(mesh.loops) * 2, np.float64)
    layer.data.foreach_get("uv", uv)
    loops = np.empty(len(mesh.loop_triangles) * 3, np.int64)
    mesh.loop_triangles.foreach_get("loops", loops)
    coordinates, index = np.unique(np.round(uv.reshape(-1, 2)[loops], 6), axis=0, return_inverse=True)
    return coordinates, index.reshape(-1, 3)


def _face_flags(mesh, name):
    """Per polygon booleans of a FACE attribute (all False without it)."""
    flags = np.zeros(len(mesh.polygons), bool)
    attr = mesh.attributes.get(name)
    if attr is not None and attr.domain == 'FACE' and attr.data_type == 'BOOLEAN' and len(flags):
        attr.data.foreach_get("value", flags)
    return flags


def _point_goals(mesh, obj_name, scale):
    """Per vertex goals from the 'fenestra_goal' attribute: a colour's brightness (HSV value of the
    colour as painted) or a float value, times scale; corner values are averaged per vertex."""
    attr = mesh.attributes.get(GOAL_ATTRIBUTE)
    if attr is None:
        raise StudyError("No goals: sensor object '%s' has no '%s' attribute (paint it in Vertex Paint, "
                         "or choose uniform goals)" % (obj_name, GOAL_ATTRIBUTE))
    n = len(attr.data)
    if attr.data_type in {'FLOAT_COLOR', 'BYTE_COLOR'}:
        rgba = np.empty(n * 4, np.float64)
        attr.data.foreach_get("color_srgb", rgba)
        values = rgba.reshape(-1, 4)[:, :3].max(axis=1)
    elif attr.data_type == 'FLOAT':
        values = np.empty(n, np.float64)
        attr.data.foreach_get("value", values)
    else:
        raise StudyError("Sensor object '%s': '%s' must be a colour or float attribute"
                         % (obj_name, GOAL_ATTRIBUTE))
    if attr.domain == 'CORNER':
        vertex = np.empty(len(mesh.loops), np.int64)
        mesh.loops.foreach_get("vertex_index", vertex)
        total = np.bincount(vertex, weights=values, minlength=len(mesh.vertices))
        count = np.bincount(vertex, minlength=len(mesh.vertices))
        values = np.where(count > 0, total / np.maximum(count, 1), 0.0)
    elif attr.domain != 'POINT':
        raise StudyError("Sensor object '%s': '%s' must be on vertices or face corners"
                         % (obj_name, GOAL_ATTRIBUTE))
    return values * scale


def _group_members(obj, mesh, name):
    """The vertices of the (evaluated) mesh in the object's vertex group `name` with a weight above
    0, as indices; every vertex when `name` is the object's own (a room's sensor grid) and it has no
    such vertex group; none otherwise."""
    index = obj.vertex_groups.find(name)
    if index < 0:
        return np.arange(len(mesh.vertices), dtype=np.int64) if obj.name == name else np.zeros(0, np.int64)
    return np.array([v.index for v in mesh.vertices if any(g.group == index and g.weight > 0 for g in v.groups)],
                    np.int64)


def evaluated(obj, depsgraph):
    """(evaluated object, its temporary mesh with loop triangles, or None); free with to_mesh_clear()."""
    obj_eval = obj.evaluated_get(depsgraph)
    mesh = obj_eval.to_mesh()
    if mesh is not None:
        mesh.calc_loop_triangles()
    return obj_eval, mesh


def is_result_modifier(m):
    """A modifier made by a solve: the Boolean with the cutters or the one opening its holes."""
    return ((m.type == 'BOOLEAN' and m.name == BOOLEAN_NAME)
            or (m.type == 'NODES' and m.name == OPEN_THROUGH_NAME))


def _result_modifiers(scene):
    return [m for obj in scene.objects for m in obj.modifiers if is_result_modifier(m)]


def build(context):
    """Converts the scene into a Study. Raises StudyError for a setup that cannot be solved.

    The modifiers of a previous result are switched off while reading the meshes, so the
    domain and the walls are read uncut."""
    scene = context.scene
    modifiers = [m for m in _result_modifiers(scene) if m.show_viewport]
    for m in modifiers:
        m.show_viewport = False
    try:
        return _build(context, context.evaluated_depsgraph_get())
    finally:
        for m in modifiers:
            m.show_viewport = True


def _build(context, depsgraph):
    scene = context.scene
    settings = scene.fenestra
    solve = settings.solve
    study = Study()
    problem = sky.climate_problem(settings.sky)
    if problem:  # before anything is read or written
        raise StudyError(problem)
    climate_goals.check_setup(settings)
    objects = [o for o in scene.objects if o.type in GEOMETRY_TYPES and o.visible_get()
               and not o.fenestra.is_opening]
    sensor_objects = [o for o in objects if o.fenestra.is_sensor]
    if not sensor_objects:
        raise StudyError(visibility.no_sensors_message(context) or
                         "No sensors: mark an object as sensors (Sensors > Sensor Object) or add a sensor grid")

    # Sensors, and their goals, first (cheap, so a bad setup fails fast).
    points, normals, goals = [], [], []
    group_names = climate_goals.group_names(settings.goals)
    groups, first = {name: [] for name in group_names}, 0
    for obj in sensor_objects:
        obj_eval, mesh = evaluated(obj, depsgraph)
        try:
            if mesh is None or len(mesh.vertices) == 0:
                raise StudyError("Sensor object '%s' has no vertices" % obj.name)
            points.append(world_vertices(mesh, obj_eval.matrix_world))
            normals.append(_world_normals(mesh, obj_eval.matrix_world))
            if settings.goals.source == 'ATTRIBUTE':
                goals.append(_point_goals(mesh, obj.name, settings.goals.scale))
            for name in group_names:
                groups[name] += (_group_members(obj, mesh, name) + first).tolist()
            study.sensor_objects.append((obj.name, len(mesh.vertices)))
            first += len(mesh.vertices)
        finally:
            obj_eval.to_mesh_clear()
    points, normals = np.concatenate(points), np.concatenate(normals)
    study.sensor_centroid = points.mean(axis=0)

    # Geometry: one OBJ group per object, its domain faces in a group of their own.
    taken_groups, material_names, material_defs = set(), {}, {}
    lines, offset, uv_offset, domain_groups = [], 0, 0, []
    for obj in objects:
        if obj.fenestra.is_sensor:
            continue
        obj_eval, mesh = evaluated(obj, depsgraph)
        if mesh is None:
            continue
        try:
            n_tris = len(mesh.loop_triangles)
            if n_tris == 0:
                continue
            verts = world_vertices(mesh, obj_eval.matrix_world)
            tris = np.empty(n_tris * 3, np.int64)
            mesh.loop_triangles.foreach_get("vertices", tris)
            tris = tris.reshape(-1, 3)
            polygon = np.empty(n_tris, np.int64)
            mesh.loop_triangles.foreach_get("polygon_index", polygon)
            mat_index = np.empty(n_tris, np.int64)
            mesh.loop_triangles.foreach_get("material_index", mat_index)
            area = np.empty(n_tris, np.float64)
            mesh.loop_triangles.foreach_get("area", area)
            domain = _face_flags(mesh, DOMAIN_ATTRIBUTE)[polygon] if len(polygon) else np.zeros(0, bool)
            # Areas are in the mesh's own space; scale them by the object's (uniform part of) scale.
            scale = abs(np.linalg.det(np.array(obj_eval.matrix_world, np.float64)[:3, :3])) ** (2.0 / 3.0)
            slots = [s.material for s in obj_eval.material_slots]
            # The UV map parameterises a curved domain for dicing; written for every object that has one.
            uvs = _corner_uvs(mesh)

            lines.append("v " + "\nv ".join(" ".join("%.6f" % c for c in v) for v in verts))
            if uvs is not None:
                lines.append("vt " + "\nvt ".join("%.6f %.6f" % tuple(t) for t in uvs[0]))
            group = _safe(obj.name, taken_groups)
            study.group_objects[group] = obj.name
            study.triangles.append((obj.name, verts, tris, domain))
            for is_domain in (False, True):
                chosen = domain == is_domain
                if not chosen.any():
                    continue
                if is_domain:
                    group_name = _safe(obj.name + ".domain", taken_groups)
                    study.group_objects[group_name] = obj.name
                    domain_groups.append(group_name)
                    study.domain_objects.append(obj.name)
                    study.domain_faces += int(len(np.unique(polygon[chosen])))
                    study.domain_area += float(area[chosen].sum()) * scale
                else:
                    group_name = group
                lines.append("g " + group_name)
                for index in np.unique(mat_index[chosen]):
                    material = slots[index] if 0 <= index < len(slots) else None
                    key = material.name if material is not None else None
                    if key not in material_names:
                        name = _safe(key or "default", set(material_names.values()))
                        material_names[key] = name
                        material_defs[name] = materials.material_dict(material)
                    selected = chosen & (mat_index == index)
                    faces = tris[selected] + offset + 1
                    lines.append("usemtl " + material_names[key])
                    if uvs is None:
                        lines.append("f " + "\nf ".join("%d %d %d" % tuple(f) for f in faces))
                    else:  # v/vt per corner
                        corners = np.stack([faces, uvs[1][selected] + uv_offset + 1], axis=2).reshape(-1, 6)
                        lines.append("f " + "\nf ".join("%d/%d %d/%d %d/%d" % tuple(f) for f in corners))
            offset += len(verts)
            uv_offset += len(uvs[0]) if uvs is not None else 0
        finally:
            obj_eval.to_mesh_clear()

    if not domain_groups:
        raise StudyError(visibility.no_domain_message(context) or
                         "No opening domain: select faces in Edit Mode and use Opening Domain > Mark")
    if not (solve.element_size > 0):
        raise StudyError("The element size must be positive")
    estimate = study.domain_area / solve.element_size ** 2
    if estimate > MAX_ELEMENTS:
        raise StudyError("Element size %.3g m is too small for %.3g m² of opening domain (about %d elements, "
                         "at most %d): use a larger element size" % (solve.element_size, study.domain_area,
                                                                   estimate, MAX_ELEMENTS))

    paths, generations, population = solve.budget()
    study.obj_text = "\n".join(lines) + "\n"
    sensors = {"points": np.round(points, 6).tolist(), "normals": np.round(normals, 6).tolist()}
    scene_dict = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": material_defs,
        "opening_domain": {"groups": domain_groups, "element_size": solve.element_size},
        "sensors": sensors,
        "sky": sky.sky_dict(scene),
        "render": {"paths_per_sensor": paths, "seed": solve.seed},
        "solver": {"paths": paths, "generations": generations, "population": population,
                   "seed": solve.seed},
    }
    if solve.edges_on_grid:
        scene_dict["solver"]["refine_edges"] = False
    if solve.verify_paths() > 0:
        scene_dict["solver"]["verify_paths"] = solve.verify_paths()
    if solve.wall_thickness > 0:  # else the native core measures each panel's wall
        scene_dict["opening_domain"]["thickness"] = solve.wall_thickness
    units = settings.goals.units.lower()
    if settings.goals.source == 'ATTRIBUTE':
        sensors["goals"] = np.round(np.concatenate(goals), 6).tolist()
        sensors["goal_units"] = units
    elif settings.goals.source == 'UNIFORM':
        g = settings.goals
        uniform = {"sensors": "all", "level": g.level}
        if g.use_min:
            uniform["min"] = g.min
        if g.use_max:
            uniform["max"] = g.max
        scene_dict["goals"] = {"units": units, "uniform": [uniform]}
    if len(settings.goals.climate):  # Climate goals (climate sky; checked above): on all sensors or a group
        sensors_groups = climate_goals.checked_groups(settings.goals, groups, [n for n, _ in study.sensor_objects])
        if sensors_groups:
            sensors["groups"] = sensors_groups
        scene_dict.setdefault("goals", {}).update(climate_goals.goals_dict(settings.goals))
    constraints = solve.constraints.as_dict()
    if constraints:
        from ..com import native
        if native.accepts_constraints():
            scene_dict["solver"]["constraints"] = constraints
    study.scene = scene_dict
    return study
