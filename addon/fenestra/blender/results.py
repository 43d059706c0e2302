"""A solve's result in the model: cutter boxes, Boolean modifiers, achieved lux on the sensors."""

import bmesh
import bpy
import numpy as np

from .export import BOOLEAN_NAME

COLLECTION = "Fenestra Openings"
ACHIEVED_ATTRIBUTE = "fenestra_achieved"


def clear(scene):
    """Removes the cutters and Boolean modifiers of a previous result."""
    for obj in list(scene.objects):
        for m in [m for m in obj.modifiers if m.type == 'BOOLEAN' and m.name == BOOLEAN_NAME]:
            obj.modifiers.remove(m)
    for obj in [o for o in bpy.data.objects if o.fenestra.is_opening]:
        mesh = obj.data
        bpy.data.objects.remove(obj)
        if mesh is not None and mesh.users == 0:
            bpy.data.meshes.remove(mesh)
    scene.fenestra.results.valid = False
    scene.fenestra.results.sensors.clear()


def _collection(scene):
    coll = bpy.data.collections.get(COLLECTION)
    if coll is None:
        coll = bpy.data.collections.new(COLLECTION)
    if coll.name not in scene.collection.children:
        scene.collection.children.link(coll)
    return coll


def _cutter_mesh(name, corners, toward_sensors, depth, margin):
    """The rectangle extruded `depth + margin` away from the sensors and `margin` toward them,
    in coordinates about its centre; returns (mesh, centre)."""
    c = np.asarray(corners, np.float64)
    centre = c.mean(axis=0)
    n = np.cross(c[1] - c[0], c[3] - c[0])
    n /= np.linalg.norm(n)
    if np.dot(toward_sensors - centre, n) < 0:
        n = -n
    near, far = c + n * margin - centre, c - n * (depth + margin) - centre
    mesh = bpy.data.meshes.new(name)
    faces = [(0, 1, 2, 3), (7, 6, 5, 4), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]
    mesh.from_pydata([tuple(v) for v in np.concatenate([near, far])], [], faces)
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    bm.to_mesh(mesh)
    bm.free()
    return mesh, centre


def apply(context, study, result):
    """Replaces the previous result with this one (a dict as fenestra.solve returns)."""
    scene = context.scene
    settings = scene.fenestra
    clear(scene)
    coll = _collection(scene)
    solve = settings.solve
    for i, opening in enumerate(result["openings"]):
        name = "Fenestra Opening %03d" % (i + 1)
        mesh, centre = _cutter_mesh(name, opening["corners"], study.sensor_centroid,
                                    solve.wall_thickness, solve.cutter_margin)
        obj = bpy.data.objects.new(name, mesh)
        obj.location = centre
        obj.display_type = 'WIRE'
        obj.hide_render = True
        obj.fenestra.is_opening = True
        coll.objects.link(obj)
    if solve.use_booleans and result["openings"]:
        for name in study.domain_objects:
            obj = bpy.data.objects.get(name)
            if obj is None or obj.type != 'MESH':
                continue
            m = obj.modifiers.new(BOOLEAN_NAME, 'BOOLEAN')
            m.operation = 'DIFFERENCE'
            m.operand_type = 'COLLECTION'
            m.collection = coll
            m.solver = 'EXACT'

    # Per sensor: goal and achieved lux, on the results and as a vertex attribute for false colour.
    achieved = np.array([s["predicted"] for s in result["sensors"]], np.float64)
    start = 0
    for name, count in study.sensor_objects:
        obj = bpy.data.objects.get(name)
        values = achieved[start:start + count]
        start += count
        if obj is None or obj.type != 'MESH' or len(obj.data.vertices) != count:
            continue  # a modifier changed the vertex count: nothing to attach the values to
        mesh = obj.data
        attr = mesh.attributes.get(ACHIEVED_ATTRIBUTE)
        if attr is not None and (attr.domain != 'POINT' or attr.data_type != 'FLOAT'):
            mesh.attributes.remove(attr)
            attr = None
        attr = attr or mesh.attributes.new(ACHIEVED_ATTRIBUTE, 'FLOAT', 'POINT')
        attr.data.foreach_set("value", values.astype(np.float32))
        mesh.update()

    r = settings.results
    r.sensors.clear()
    for s in result["sensors"]:
        item = r.sensors.add()
        item.goal = s["goal"] if s["goal"] is not None else -1.0
        item.achieved = s["predicted"]
    timings = result.get("timings_s", {})
    r.relative_rms = result["error"]["relative_rms"]
    r.max_relative = result["error"].get("max_relative", 0.0)
    verified = result["error"].get("verified")
    r.verified_rms = verified["relative_rms"] if verified else -1.0
    r.warnings = "\n".join(result.get("warnings", []))
    r.openings = len(result["openings"])
    r.open_elements = len(result.get("open_elements", []))
    r.elements = result.get("element_count", 0)
    r.seconds_total = timings.get("total", 0.0)
    r.seconds_contributions = timings.get("contributions", 0.0)
    r.seconds_solver = r.seconds_total - r.seconds_contributions
    r.study_path = study.scene_path
    r.valid = True
    settings.domain_faces = study.domain_faces
    settings.domain_area = study.domain_area
