"""A solve's result in the model: cutters (cutter.py), Boolean modifiers that cut through the
walls, achieved lux on the sensors."""

import bmesh
import bpy
import numpy as np

from .. import compat
from ..com.cutter import Cutter
from ..com.names import (ACHIEVED_ATTRIBUTE, BOOLEAN_NAME, COLLECTION, CUTTER_NAME, OPEN_THROUGH_NAME,
                         ROOM_SIDE_ATTRIBUTE)
from ..study.export import is_result_modifier
from ..study.opening_cutters import remember
from . import annual_results, climate_results, sky_reference

MIN_MARGIN = 0.001     # m: a cutter reaches at least this far beyond the wall on both sides
TOUCH_TOLERANCE = 0.001  # m: geometry this close to a cutter's edge only touches it


def clear(scene):
    """Removes everything a result put into the file: the cutters, the modifiers and their node
    group, the cutters' collection, the `fenestra_achieved` attribute, and the result's figures
    (an Annual Daylight run's too: it was of these openings). Returns the number of cutters removed."""
    for obj in list(scene.objects):
        for m in [m for m in obj.modifiers if is_result_modifier(m)]:
            obj.modifiers.remove(m)
    group = bpy.data.node_groups.get(OPEN_THROUGH_NAME)
    if group is not None and group.users == 0:
        bpy.data.node_groups.remove(group)
    cutters = [o for o in bpy.data.objects if o.fenestra.is_opening]
    for obj in cutters:
        mesh = obj.data
        bpy.data.objects.remove(obj)
        if mesh is not None and mesh.users == 0:
            bpy.data.meshes.remove(mesh)
    coll = bpy.data.collections.get(COLLECTION)
    if coll is not None and not coll.objects and not coll.children:  # kept if the user put things in it
        bpy.data.collections.remove(coll)
    for obj in scene.objects:
        if obj.type == 'MESH' and obj.data is not None:
            attr = obj.data.attributes.get(ACHIEVED_ATTRIBUTE)
            if attr is not None:
                obj.data.attributes.remove(attr)
    results = scene.fenestra.results
    for key in results.bl_rna.properties.keys():
        if key not in {"rna_type", "name", "sensors", "climate"}:
            results.property_unset(key)  # back to its default: no old count is left on show
    results.sensors.clear()
    climate_results.clear(results.climate)
    annual_results.clear(scene)
    return len(cutters)


def _collection(scene):
    coll = bpy.data.collections.get(COLLECTION)
    if coll is None:
        coll = bpy.data.collections.new(COLLECTION)
    if coll.name not in scene.collection.children:
        scene.collection.children.link(coll)
    return coll


def _open_through_group():
    """The node group of the "Fenestra Open Through" modifier: deletes the faces that carry
    ROOM_SIDE_ATTRIBUTE (what the Boolean keeps of the cutters' room-side part) and drops the
    attribute."""
    group = bpy.data.node_groups.get(OPEN_THROUGH_NAME)
    if group is not None and group.bl_idname == 'GeometryNodeTree':
        return group
    group = bpy.data.node_groups.new(OPEN_THROUGH_NAME, 'GeometryNodeTree')
    compat.new_group_socket(group, 'INPUT', 'NodeSocketGeometry', "Geometry")
    compat.new_group_socket(group, 'OUTPUT', 'NodeSocketGeometry', "Geometry")
    nodes, links = group.nodes, group.links
    given, out = nodes.new('NodeGroupInput'), nodes.new('NodeGroupOutput')
    flag = nodes.new('GeometryNodeInputNamedAttribute')
    flag.data_type = 'BOOLEAN'
    flag.inputs["Name"].default_value = ROOM_SIDE_ATTRIBUTE
    delete = nodes.new('GeometryNodeDeleteGeometry')
    delete.domain = 'FACE'
    drop = nodes.new('GeometryNodeRemoveAttribute')
    drop.inputs["Name"].default_value = ROOM_SIDE_ATTRIBUTE
    links.new(given.outputs[0], delete.inputs["Geometry"])
    links.new(next(o for o in flag.outputs if o.enabled), delete.inputs["Selection"])
    links.new(delete.outputs[0], drop.inputs[0])
    links.new(drop.outputs[0], out.inputs[0])
    for i, node in enumerate((given, flag, delete, drop, out)):
        node.location = (200 * i, 0)
    return group


def _cutter_mesh(name, cutter):
    """The cutter's solid in coordinates about the centre of the opening's outline, split at the
    wall's surface: the faces on the room side carry ROOM_SIDE_ATTRIBUTE. Returns (mesh, centre)."""
    verts = cutter.vertices()
    centre = cutter.outline().mean(axis=0)
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in verts - centre], [], cutter.faces)
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    bm.to_mesh(mesh)
    bm.free()
    flags = [i < cutter.room_side_faces for i in range(len(cutter.faces))]
    mesh.attributes.new(ROOM_SIDE_ATTRIBUTE, 'BOOLEAN', 'FACE').data.foreach_set("value", flags)
    mesh.update()
    return mesh, centre


def _toward_sensors(opening, study, centre):
    """The direction from the opening into the room: against its outward normal when the result
    gives one, else toward the sensors' centroid."""
    normal = opening.get("normal")
    if normal is not None and np.linalg.norm(normal) > 0:
        return -np.asarray(normal, np.float64)
    return study.sensor_centroid - centre


def _cutter(opening, study, depth, margin):
    """A curved opening's cutter follows its surface grid; a flat one's is the box of its corners."""
    grid = opening.get("surface_grid")
    if grid:
        return Cutter.from_grid(grid, depth, margin)
    centre = np.asarray(opening["corners"], np.float64).mean(axis=0)
    return Cutter.flat(opening["corners"], _toward_sensors(opening, study, centre), depth, margin)


def _objects_reached(context, cutters, exclude):
    """The visible mesh objects with faces inside or across a cutter (its outline shrunk by
    TOUCH_TOLERANCE, so that a floor or wall meeting the opening's edge does not count): the
    domain's own objects, and the wall's outer faces and reveals wherever they are modelled."""
    from mathutils.bvhtree import BVHTree
    depsgraph = context.evaluated_depsgraph_get()
    cutter_trees = []
    for cutter in cutters:
        verts = cutter.vertices(TOUCH_TOLERANCE)
        cutter_trees.append((verts.min(axis=0), verts.max(axis=0),
                             BVHTree.FromPolygons([tuple(v) for v in verts], cutter.faces)))
    reached = []
    for obj in context.scene.objects:
        if (obj.type != 'MESH' or obj.name in exclude or obj.fenestra.is_sensor or obj.fenestra.is_opening
                or not obj.visible_get()):
            continue
        obj_eval = obj.evaluated_get(depsgraph)
        mesh = obj_eval.to_mesh()
        try:
            if mesh is None or len(mesh.polygons) == 0:
                continue
            co = np.empty(len(mesh.vertices) * 3, np.float64)
            mesh.vertices.foreach_get("co", co)
            m = np.array(obj_eval.matrix_world, np.float64)
            co = co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]
            lo, hi = co.min(axis=0), co.max(axis=0)
            near = [(cutter, tree) for cutter, (clo, chi, tree) in zip(cutters, cutter_trees)
                    if np.all(lo <= chi) and np.all(clo <= hi)]
            if not near:
                continue
            if any(cutter.contains(co, TOUCH_TOLERANCE).any() for cutter, _ in near):
                reached.append(obj)
                continue
            polygons = [tuple(p.vertices) for p in mesh.polygons]
            tree = BVHTree.FromPolygons([tuple(v) for v in co], polygons)
            if any(tree.overlap(cutter) for _, cutter in near):
                reached.append(obj)
        finally:
            obj_eval.to_mesh_clear()
    return reached


def write_achieved(study, achieved):
    """Each sensor mesh's vertex attribute ACHIEVED_ATTRIBUTE (lux), from the values of all sensors
    in study order."""
    start = 0
    for name, count in study.sensor_objects:
        obj = bpy.data.objects.get(name)
        values = np.asarray(achieved[start:start + count], np.float64)
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


def tradeoff_result(result, index):
    """The result as it would be with trade-off `index` (of result["tradeoffs"]) as the answer: its
    openings, predicted values and error; the rest (the list itself included) as solved."""
    entry = result["tradeoffs"][index]
    sensors = [dict(s, predicted=p, predicted_stderr=e)
               for s, p, e in zip(result["sensors"], entry["predicted"], entry["predicted_stderr"])]
    error = dict(result["error"], **entry["error"], verified=None)  # the check was of the answer
    # The answer's climate figures as they are; a trade-off's are its own goals' figures only.
    climate = result.get("climate")
    if climate and index != 0:
        climate = climate_results.tradeoff_climate(climate, entry)
    return dict(result, openings=entry["openings"], sensors=sensors, error=error, climate=climate,
                open_elements=None if index != 0 else result.get("open_elements", []),
                warnings=[w for w in result.get("warnings", []) if not w.startswith("checked")
                          and not (index != 0 and w.startswith("climate goals: "))])


def apply(context, study, result):
    """Replaces the previous result with this one (a dict as fenestra.solve returns)."""
    scene = context.scene
    settings = scene.fenestra
    clear(scene)
    coll = _collection(scene)
    solve = settings.solve
    margin = max(solve.cutter_margin, MIN_MARGIN)
    cutters = []
    for i, opening in enumerate(result["openings"]):
        name = CUTTER_NAME % (i + 1)
        cutter = _cutter(opening, study, opening.get("depth", solve.wall_thickness), margin)
        cutters.append(cutter)
        mesh, centre = _cutter_mesh(name, cutter)
        obj = bpy.data.objects.new(name, mesh)
        obj.location = centre
        obj.display_type = 'WIRE'
        obj.hide_render = True
        obj.fenestra.is_opening = True
        remember(obj, opening)  # for Evaluate, once the user has moved it
        coll.objects.link(obj)
    if solve.use_booleans and cutters:
        # The domain objects, and every other object the cutters reach (a solid wall's outer
        # faces and edges, modelled in the same object or in another one).
        domain = [bpy.data.objects.get(name) for name in study.domain_objects]
        domain = [o for o in domain if o is not None and o.type == 'MESH']
        group = _open_through_group()
        for obj in domain + _objects_reached(context, cutters, {o.name for o in domain}):
            m = obj.modifiers.new(BOOLEAN_NAME, 'BOOLEAN')
            m.operation = 'DIFFERENCE'
            m.operand_type = 'COLLECTION'
            m.collection = coll
            m.solver = compat.BOOLEAN_SOLVER
            m.use_hole_tolerant = True
            # A closed mesh is a solid to the Boolean: a room with zero-thickness walls keeps a
            # face across the hole at the cutter's room side; this modifier removes it.
            m = obj.modifiers.new(OPEN_THROUGH_NAME, 'NODES')
            m.node_group = group

    # Per sensor: goal and achieved lux, on the results and as a vertex attribute for false colour.
    achieved = np.array([s["predicted"] for s in result["sensors"]], np.float64)
    write_achieved(study, achieved)

    r = settings.results
    r.sensors.clear()
    owners = [(name, vertex) for name, count in study.sensor_objects for vertex in range(count)]
    for s, (name, vertex) in zip(result["sensors"], owners):
        item = r.sensors.add()
        item.goal = s["goal"] if s["goal"] is not None else -1.0
        item.achieved = s["predicted"]
        item.object_name, item.vertex = name, vertex
    climate_results.apply(r, result.get("climate"))
    timings = result.get("timings_s", {})
    r.relative_rms = result["error"]["relative_rms"]
    r.max_relative = result["error"].get("max_relative", 0.0)
    verified = result["error"].get("verified")
    r.verified_rms = verified["relative_rms"] if verified else -1.0
    r.verified_noise = verified.get("noise_rms", 0.0) if verified else 0.0
    r.warnings = "\n".join(result.get("warnings", []))
    r.openings = len(result["openings"])
    r.tradeoffs.clear()
    for entry in result.get("tradeoffs", []):
        item = r.tradeoffs.add()
        item.openings = entry["openings_count"]
        item.relative_rms = entry["error"]["relative_rms"]
        item.glazing_area = entry["glazing_area_m2"]
        climate = entry.get("climate")
        item.climate_met = -1 if not climate else int(bool(climate.get("all_met")))
        item.climate_by_cutters = bool(climate) and climate.get("figures_by") == "cutters"
        item.climate_line = climate_results.tradeoff_line(result.get("climate"), entry)
    r.tradeoff_shown = 0
    r.open_elements = -1 if result.get("open_elements") is None else len(result["open_elements"])
    r.elements = result.get("element_count", 0)
    r.seconds_total = timings.get("total", 0.0)
    r.seconds_contributions = timings.get("contributions", 0.0)
    r.seconds_solver = r.seconds_total - r.seconds_contributions
    r.study_path = study.scene_path
    r.valid = True
    climate = result.get("climate") or {}
    if climate.get("space") and climate.get("per_sensor") and climate.get("year"):
        # The solved openings' year fills the Annual Daylight figures: its space metrics and maps.
        summary = dict(climate["year"], space=climate["space"], per_sensor=climate["per_sensor"])
        if climate.get("headline") == "real cutters":  # the core's words: the records disagreed beyond the noise
            summary["note"] = next((w for w in result.get("warnings", []) if "disagree beyond the noise" in w),
                                   "figures of the year with real cutters")
        annual_results.apply(scene, study, summary, r.openings, r.seconds_total, False, study.scene_path)
    display = settings.display
    if r.climate.valid and display.false_colour != 'NONE' and display.false_colour not in climate_results.QUANTITIES:
        display.false_colour = 'CLIMATE_DA'  # the year of the openings: what climate goals are about
    elif not r.climate.valid and display.false_colour in climate_results.QUANTITIES:
        display.false_colour = 'ACHIEVED'
    if settings.display.false_colour == 'DAYLIGHT_FACTOR':
        sky_reference.ensure_horizontal_illuminance(scene)
    settings.domain_faces = study.domain_faces
    settings.domain_area = study.domain_area
