"""Blender's side of the GUI tests (python_tests/test_blender_gui.py), in a Blender with a window:

    blender --window-geometry 0 0 W H EMPTY.blend --python gui_driver.py -- CHANNEL [SCENE]

Builds the room example (examples/build_blend_examples.py; SCENE "room", the default), a floor of
two rooms with climate goals (SCENE "climate") or nothing (SCENE "empty") with the add-on, study folder CHANNEL/study, maps F5 to Solve Openings in the Window keymap (as a user's shortcut would), and
then, while the test drives Blender with real key events, reports its state to CHANNEL/state.json
every few milliseconds (the running solve's also to CHANNEL/job.json, from a thread) and follows the test's commands (CHANNEL/command-N.json, answered in
CHANNEL/reply-N.json): "set" scene.fenestra settings (optionally as an undo step), "snapshot" of
the model and the study folder, "solve_from_script" (an operator call, to read a refusal),
"sidebar" (opens the 3D View's sidebar with the Fenestra tab and Item alone, returns its
rectangle; "restore_panels" brings the other tabs back), "keymap" (the
user key configuration's items for Fenestra's commands), "look_at_sensors" (alone, from above,
with a goal colour attribute), "sensors_seen" (what the 3D View shows of them), "show_all",
"solid_room" (a room modelled as one solid: addon_sensor_grid.solid), "sensor_grids" (the sensor
objects and their points), "reports" (the window's reports, as the Info editor lists them),
"from_above" (the 3D View in X-ray from above), "results" (what the Results panels read), "shading" (the 3D View's), "windows" (each window's areas) and
"close_other_windows", "popup" (where a screenshot differs from another
one: a popup's extent), "screenshot", "quit". It also counts the calls of Fenestra's commands (state "calls") and records
which operator or property the last right-click menu on a button was for (state "context_menu"). The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import contextlib
import hashlib
import json
import os
import sys
import threading
import time
import traceback

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "examples"))
sys.path.insert(0, HERE)
import build_blend_examples as examples  # noqa: E402
import window_script  # noqa: E402

ARGS = sys.argv[sys.argv.index("--") + 1:]
CHANNEL = ARGS[0]
SCENE = ARGS[1] if len(ARGS) > 1 else "room"
STUDY = os.path.join(CHANNEL, "study")
TICK_S = 0.01
JOBS_LOCK = threading.Lock()
# Blender (3.4 to 4.5, with Python 3.11) can crash when an operator runs from Python under a context
# override while another Python thread holds the GIL (docs/blender.md, "Scripts and threads"): the
# monitor thread waits, holding no GIL, while this driver runs one (overridden()).
QUIET = threading.RLock()
state = {"next_command": 0, "jobs": 0, "last_job": None, "calls": {},
         "context_menu": {"count": 0, "operator": None, "property": None}}
COMMANDS = ("fenestra.solve_openings", "fenestra.evaluate_openings", "fenestra.annual_daylight", "fenestra.check_setup",
            "fenestra.show_goal_plot", "fenestra.apply_tradeoff", "fenestra.preview_sky",
            "fenestra.add_sensor_grid")


def write_json(path, value):
    part = "%s.%d.part" % (path, threading.get_ident())
    with open(part, "w") as f:
        json.dump(value, f)
    os.replace(part, path)


def setup():
    examples.enable_addon()
    if SCENE == "room":
        with in_view3d():  # the operators that build it need a window's context
            examples.build_room()
    elif SCENE == "climate":
        with in_view3d():
            climate_floor()
    f = bpy.context.scene.fenestra
    f.solve.study_directory = STUDY
    km = bpy.context.window_manager.keyconfigs.addon.keymaps.new(name="Window", space_type='EMPTY')
    km.keymap_items.new("fenestra.solve_openings", 'F5', 'PRESS')
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    count_calls()
    bpy.types.UI_MT_button_context_menu.append(record_context_menu)
    undo_push("Fenestra GUI test set up")


def climate_floor():
    """addon_climate.py's floor of two rooms (a sensor grid each, a year of Chicago weather), an sDA
    and an ASE goal per room, Least Glazing: a climate solve with trade-offs to click."""
    import addon_climate
    import addon_study
    addon_climate.OUT = addon_study.OUT = os.path.join(CHANNEL, "climate")
    grids = addon_climate.floor(("West office", "East office"))
    f = bpy.context.scene.fenestra
    f.goals.source = 'NONE'
    for grid in grids:
        addon_climate.add_goal('SDA', sda_area=50.0, sensor_group=grid.name)
        addon_climate.add_goal('ASE', sensor_group=grid.name)
    f.goals.least_glazing = True


def results():
    """What the Results and Climate Goals panels read: the trade-offs, which one is shown, the
    openings, each climate goal's figure; and the false colour legend's title."""
    import numpy as np
    from fenestra.blender.result import result_display
    r = bpy.context.scene.fenestra.results
    c = r.climate
    window, area = view3d()
    with overridden(window=window, area=area):
        shown = result_display.current(bpy.context)
    legend = shown[0].title_for(np.concatenate(list(shown[1].values()))) if shown else None
    return {"valid": r.valid, "legend": legend, "tradeoff_shown": r.tradeoff_shown, "openings": r.openings,
            "open_elements": r.open_elements, "cutters": sorted(o.name for o in bpy.data.objects if o.fenestra.is_opening),
            "tradeoffs": [{"openings": t.openings, "glazing_area": t.glazing_area, "climate_met": t.climate_met,
                           "climate_line": t.climate_line} for t in r.tradeoffs],
            "climate": {"valid": c.valid, "tradeoff": c.tradeoff, "glazing_area": c.glazing_area,
                        "goals": [[g.description, *g.lead()] for g in c.goals], "rooms": len(c.rooms)},
            "study_path": r.study_path}


def count_calls():
    """Wraps Fenestra's commands' invoke and execute (looked up at each call) to count their calls."""
    for idname in COMMANDS:
        group, name = idname.split(".")
        cls = bpy.types.Operator.bl_rna_get_subclass_py("%s_OT_%s" % (group.upper(), name))
        for method in ("invoke", "execute"):
            if hasattr(cls, method):
                setattr(cls, method, counted(idname, getattr(cls, method)))


def counted(idname, method):
    """The method, counting its calls. Blender passes as many arguments as the function names."""
    def invoke(self, context, event):
        state["calls"][idname] = state["calls"].get(idname, 0) + 1
        return method(self, context, event)

    def execute(self, context):
        state["calls"][idname] = state["calls"].get(idname, 0) + 1
        return method(self, context)
    return invoke if method.__name__ == "invoke" else execute


def record_context_menu(menu, context):
    """The right-click menu of a button: for which operator or property (None for other buttons)."""
    op = getattr(context, "button_operator", None)
    prop = getattr(context, "button_prop", None)
    menu_state = state["context_menu"]
    menu_state["count"] += 1
    menu_state["operator"] = op.bl_rna.identifier if op is not None else None
    menu_state["property"] = prop.identifier if prop is not None else None


@contextlib.contextmanager
def overridden(**members):
    """Context.temp_override(**members), the monitor thread paused meanwhile (QUIET)."""
    with QUIET, bpy.context.temp_override(**members):
        yield


def in_view3d():
    """A context with the window and its 3D View, as an operator run from the viewport sees."""
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == 'VIEW_3D')
    return overridden(window=window, area=area)


def undo_push(message):
    with in_view3d():
        bpy.ops.ed.undo_push(message=message)


def view3d_centre():
    """The 3D View's centre in X screen coordinates (origin top left)."""
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == 'VIEW_3D'), key=lambda a: a.width * a.height)
    region = next(r for r in area.regions if r.type == 'WINDOW')
    return [window.x + region.x + region.width // 2, window.height - (region.y + region.height // 2)]


def job_state():
    """The last job, numbered in the order jobs started (no bpy: the monitor thread calls it too)."""
    from fenestra.blender.com import solve_job
    with JOBS_LOCK:
        job = solve_job.last()
        if job is None:
            return None
        if job is not state["last_job"]:
            state["last_job"] = job
            state["jobs"] += 1
        number = state["jobs"]
    return {"number": number, "status": job.status, "fraction": job.fraction, "started": job.started,
            "ended": job.ended, "cancel_requested": job.cancel_requested, "cancel_reason": job.cancel_reason,
            "outcome": job.outcome, "cancelled": job.done.is_set() and job.cancelled,
            "error": None if job.error is None else str(job.error), "reused": job.reused}


def monitor_jobs():
    """CHANNEL/job.json every few milliseconds from a thread of its own: Blender's main thread, which
    writes state.json, can be held up by redraws for a good part of a second."""
    while True:
        try:
            with QUIET:
                write_json(os.path.join(CHANNEL, "job.json"), {"now": time.monotonic(), "job": job_state()})
        except Exception:
            traceback.print_exc()
        time.sleep(0.003)


def report_state():
    from fenestra.blender.com import solve_job
    f = bpy.context.scene.fenestra
    write_json(os.path.join(CHANNEL, "state.json"), {
        "now": time.monotonic(), "running": solve_job.running() is not None, "job": job_state(),
        "mode": bpy.context.mode, "goal_level": f.goals.level, "results_valid": f.results.valid,
        "relative_rms": f.results.relative_rms, "seconds_total": f.results.seconds_total,
        "solve_polls": bpy.ops.fenestra.solve_openings.poll(), "view3d": view3d_centre(),
        "calls": state["calls"], "context_menu": state["context_menu"]})


def digest_of_file(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def snapshot():
    """What a cancelled or discarded solve must leave alone: the result in the model and the study folder."""
    f = bpy.context.scene.fenestra
    model = {
        "objects": sorted(o.name for o in bpy.data.objects),
        "modifiers": sorted([o.name, m.name] for o in bpy.data.objects for m in o.modifiers),
        "cutters": sorted([o.name, [list(map(lambda x: round(x, 6), o.location))]] for o in bpy.data.objects
                          if o.fenestra.is_opening),
        "results": [f.results.valid, f.results.openings, f.results.relative_rms, f.results.study_path,
                    [[s.goal, s.achieved] for s in f.results.sensors]],
    }
    folder = {}
    if os.path.isdir(STUDY):
        folder = {name: digest_of_file(os.path.join(STUDY, name)) for name in sorted(os.listdir(STUDY))}
    siblings = sorted(n for n in os.listdir(CHANNEL) if n.startswith(".study"))  # staging folders left behind
    return {"model": model, "folder": folder, "staging": siblings}


def set_settings(values, undo_step=None):
    f = bpy.context.scene.fenestra
    for path, value in values.items():
        owner, _, name = path.rpartition(".")
        target = f
        for part in filter(None, owner.split(".")):
            target = getattr(target, part)
        setattr(target, name, value)
    if undo_step:
        undo_push(undo_step)
    return {"goal_level": f.goals.level}


def solve_from_script():
    with in_view3d():
        try:
            return {"result": sorted(bpy.ops.fenestra.solve_openings('INVOKE_DEFAULT'))}
        except RuntimeError as exc:
            return {"error": str(exc)}


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == 'VIEW_3D'), key=lambda a: a.width * a.height)
    return window, area


def to_x(window, region, x, y):
    """Region coordinates (origin bottom left) in X screen coordinates (origin top left)."""
    return [window.x + region.x + int(x), window.height - (region.y + int(y))]


def sidebar(closed=("FENESTRA_PT_domain", "FENESTRA_PT_sensors", "FENESTRA_PT_sky")):
    """Opens the sidebar on the Fenestra tab, the first time with the panels named in `closed`
    closed; returns its rectangle [left, top, right, bottom] in X screen coordinates."""
    window, area = view3d()
    area.spaces.active.show_region_ui = True
    if "hidden_panels" not in state:  # the other tabs' panels out, and some of Fenestra's closed
        state["hidden_panels"] = window_script.hide_other_tabs()
        window_script.set_panel_options({name: {'DEFAULT_CLOSED'} for name in closed})
    region = next(r for r in area.regions if r.type == 'UI')
    return to_x(window, region, 0, region.height) + to_x(window, region, region.width, 0)


def keymap_items():
    keyconfig = bpy.context.window_manager.keyconfigs.user
    return [[km.name, kmi.idname, kmi.type, kmi.shift, kmi.ctrl, kmi.alt, kmi.active]
            for km in keyconfig.keymaps for kmi in km.keymap_items if kmi.idname in COMMANDS]


def sensors_seen(name):
    """The sensors as the 3D View shows them: a screenshot (CHANNEL/NAME.png), the colour at each
    sensor's screen position, what the false colour draws, the active colour attribute and mode."""
    from bpy_extras.view3d_utils import location_3d_to_region_2d
    from fenestra.blender.result import result_display
    import numpy as np
    window, area = view3d()
    region = next(r for r in area.regions if r.type == 'WINDOW')
    path = os.path.join(CHANNEL, name + ".png")
    with overridden(window=window, area=area, region=region):
        bpy.ops.screen.screenshot_area(filepath=path)
        shown = result_display.current(bpy.context)
    image = bpy.data.images.load(path)
    w, h = image.size
    pixels = np.zeros(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    pixels = pixels.reshape(h, w, 4)[:, :, :3]
    sensors = bpy.data.objects["Sensors"]
    colours = []
    for v in sensors.data.vertices:
        p = location_3d_to_region_2d(region, area.spaces.active.region_3d, sensors.matrix_world @ v.co)
        x, y = int(p.x) + region.x - area.x, int(p.y) + region.y - area.y
        if 0 <= x < w and 0 <= y < h:
            colours.append(pixels[y, x].tolist())
    return {"colours": colours, "false_colour": sorted(shown[1]) if shown else [], "mode": sensors.mode,
            "active_colour": sensors.data.color_attributes.active_color_name}


def look_at_sensors():
    """The sensors alone (the other objects hidden), from above, in Solid shading; with a goal
    colour attribute (mid grey) beside another colour attribute that is active."""
    from fenestra.blender.com import names
    from mathutils import Vector
    sensors = bpy.data.objects["Sensors"]
    colours = sensors.data.color_attributes
    if names.GOAL_ATTRIBUTE not in colours:
        goal = colours.new(names.GOAL_ATTRIBUTE, 'FLOAT_COLOR', 'POINT')
        goal.data.foreach_set("color_srgb", [0.5, 0.5, 0.5, 1.0] * len(sensors.data.vertices))
        other = colours.new("Other", 'FLOAT_COLOR', 'POINT')
        other.data.foreach_set("color_srgb", [0.0, 0.0, 0.0, 1.0] * len(sensors.data.vertices))
    colours.active_color_name = "Other"
    for o in bpy.context.view_layer.objects:
        o.hide_set(o is not sensors)
    window, area = view3d()
    space = area.spaces.active
    space.shading.type = 'SOLID'
    r3d = space.region_3d
    r3d.view_perspective = 'ORTHO'
    r3d.view_rotation = (1.0, 0.0, 0.0, 0.0)  # from above
    r3d.view_location = sensors.matrix_world @ (sum((Vector(c) for c in sensors.bound_box), Vector()) / 8)
    r3d.view_distance = 14.0
    for o in bpy.context.view_layer.objects:
        o.select_set(o is sensors)
    bpy.context.view_layer.objects.active = sensors
    return {}


def solid_room():
    """A room modelled as one solid (python_tests/blender/addon_sensor_grid.py: a 4 x 5 x 3 m cavity,
    walls 0.3 m, slabs 0.2 m, the cavity's south face the opening domain) named 'Room', selected and
    active; uniform goals and sky, so that Check Setup has a whole study to check."""
    import addon_sensor_grid
    room = addon_sensor_grid.solid("Room", [(0.0, 4.0)])
    for o in bpy.context.view_layer.objects:
        o.select_set(o is room)
    bpy.context.view_layer.objects.active = room
    f = bpy.context.scene.fenestra
    f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'NORMALIZED', 0.5
    f.sky.type = 'UNIFORM'
    undo_push("Solid room")
    return {"cavity": [[0.0, 0.0, 0.0], [4.0, 5.0, 3.0]]}


def sensor_grids():
    """The sensor objects (name, world coordinates of each point), the grid's settings and Check
    Setup's verdict."""
    grids = []
    for obj in sorted((o for o in bpy.data.objects if o.fenestra.is_sensor), key=lambda o: o.name):
        grids.append({"name": obj.name, "points": [list(obj.matrix_world @ v.co) for v in obj.data.vertices]})
    f = bpy.context.scene.fenestra
    return {"grids": grids, "height": f.sensor_height, "spacing": f.sensor_spacing,
            "setup_checked": f.setup_checked, "setup_warnings": f.setup_warnings}


def reports():
    """The window's reports as the Info editor lists them (the Timeline shows the Info editor for a
    moment: its Copy puts the selected reports on the clipboard)."""
    window = bpy.context.window_manager.windows[0]
    area = min((a for a in window.screen.areas if a.type != 'VIEW_3D'), key=lambda a: a.y)  # the Timeline
    kind, ui_type = area.type, area.ui_type
    area.type = 'INFO'
    try:
        region = next(r for r in area.regions if r.type == 'WINDOW')
        with overridden(window=window, area=area, region=region):
            bpy.ops.info.select_all(action='SELECT')
            bpy.ops.info.report_copy()
            bpy.ops.info.select_all(action='DESELECT')
    finally:
        area.type = kind
        area.ui_type = ui_type
    return bpy.context.window_manager.clipboard.splitlines()


def from_above(location, distance):
    """The 3D View from above, orthographic, in Solid shading with X-ray (through the ceiling)."""
    window, area = view3d()
    space = area.spaces.active
    space.shading.type = 'SOLID'
    space.shading.show_xray = True
    r3d = space.region_3d
    r3d.view_perspective = 'ORTHO'
    r3d.view_rotation = (1.0, 0.0, 0.0, 0.0)
    r3d.view_location = location
    r3d.view_distance = distance
    return {}


def window_pixels(name):
    """CHANNEL/NAME.png (a screenshot of the window) as (h, w, 3) values, top row first."""
    import numpy as np
    image = bpy.data.images.load(os.path.join(CHANNEL, name + ".png"))
    w, h = image.size
    pixels = np.zeros(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(h, w, 4)[::-1, :, :3]


def popup(before, after, x, y, message):
    """Where screenshot `after` differs from `before` around (x, y) (X coordinates): the extent
    [left, top, right, bottom] of the changed pixels connected to that point by changed rows and
    columns; and the lines long_message.py shows for `message`, with the widest one's width in
    pixels."""
    import blf
    import numpy as np
    from fenestra.blender.ui import long_message
    changed = np.abs(window_pixels(after) - window_pixels(before)).max(axis=2) > 0.02
    h, w = changed.shape
    rows = changed.any(axis=1)
    top = bottom = min(max(y, 0), h - 1)
    while top > 0 and rows[top - 1]:
        top -= 1
    while bottom < h - 1 and rows[bottom + 1]:
        bottom += 1
    columns = changed[top:bottom + 1].any(axis=0)
    left = right = min(max(x, 0), w - 1)
    while left > 0 and columns[left - 1]:
        left -= 1
    while right < w - 1 and columns[right + 1]:
        right += 1
    lines = long_message.popup_lines(message)
    scale = bpy.context.preferences.system.ui_scale
    blf.size(0, 11 * scale)
    widest = max((blf.dimensions(0, line)[0] for line in lines), default=0.0)
    return {"extent": [left, top, right, bottom], "changed": bool(changed[top:bottom + 1, left:right + 1].any()),
            "lines": lines, "widest": widest, "line_height": 20 * scale}


def follow_commands():
    path = os.path.join(CHANNEL, "command-%d.json" % state["next_command"])
    if not os.path.exists(path):
        return
    with open(path) as f:
        command = json.load(f)
    name, args = command["do"], command.get("args", {})
    try:
        if name == "set":
            reply = set_settings(**args)
        elif name == "snapshot":
            reply = snapshot()
        elif name == "solve_from_script":
            reply = solve_from_script()
        elif name == "restore_panels":  # the other tabs' panels back (Vertex Paint's header needs some)
            hidden = state.pop("hidden_panels", [])
            while hidden:  # parents before their sub-panels
                ready = [c for c in hidden if not getattr(c, "bl_parent_id", "")
                         or hasattr(bpy.types, c.bl_parent_id)]
                for cls in ready or hidden:
                    bpy.utils.register_class(cls)
                    hidden.remove(cls)
            reply = {}
        elif name == "sidebar":
            reply = {"rect": sidebar(**args)}
        elif name == "solid_room":
            reply = solid_room()
        elif name == "sensor_grids":
            reply = sensor_grids()
        elif name == "reports":
            reply = {"reports": reports()}
        elif name == "from_above":
            reply = from_above(**args)
        elif name == "popup":
            reply = popup(**args)
        elif name == "keymap":
            reply = {"items": keymap_items()}
        elif name == "look_at_sensors":
            reply = look_at_sensors()
        elif name == "results":
            reply = results()
        elif name == "shading":  # the 3D View's shading: type and whether it shows the scene's world
            shading = view3d()[1].spaces.active.shading
            reply = {"type": shading.type, "use_scene_world": shading.use_scene_world,
                     "use_scene_world_render": shading.use_scene_world_render,
                     "world": bpy.context.scene.world.name if bpy.context.scene.world else None}
        elif name == "windows":  # each window's areas: type and, for an Image Editor, its image
            reply = {"windows": [[[a.type, a.spaces.active.image.name if a.type == 'IMAGE_EDITOR'
                                   and a.spaces.active.image else None] for a in w.screen.areas]
                                 for w in bpy.context.window_manager.windows]}
        elif name == "close_other_windows":
            for w in list(bpy.context.window_manager.windows)[1:]:
                with overridden(window=w):
                    bpy.ops.wm.window_close()
            reply = {}
        elif name == "show_all":
            for o in bpy.context.view_layer.objects:
                o.hide_set(False)
            reply = {}
        elif name == "sensors_seen":
            reply = sensors_seen(args["name"])
        elif name == "screenshot":
            path = os.path.join(CHANNEL, args["name"] + ".png")
            window = bpy.context.window_manager.windows[0]
            with overridden(window=window):
                bpy.ops.screen.screenshot(filepath=path)
            reply = {"path": path}
        elif name == "select":
            for o in bpy.context.view_layer.objects:
                o.select_set(o.name == args["name"])
            bpy.context.view_layer.objects.active = bpy.data.objects[args["name"]]
            reply = {}
        elif name == "quit":
            write_json(os.path.join(CHANNEL, "reply-%d.json" % state["next_command"]), {})
            bpy.ops.wm.quit_blender()
            return
        else:
            reply = {"failed": "unknown command %r" % name}
    except Exception:
        reply = {"failed": traceback.format_exc()}
    write_json(os.path.join(CHANNEL, "reply-%d.json" % state["next_command"]), reply)
    state["next_command"] += 1


def tick():
    try:
        follow_commands()
        report_state()
    except Exception:
        traceback.print_exc()
        write_json(os.path.join(CHANNEL, "failed.json"), {"traceback": traceback.format_exc()})
        return None
    return TICK_S


def start():
    try:
        setup()
    except Exception:
        write_json(os.path.join(CHANNEL, "failed.json"), {"traceback": traceback.format_exc()})
        return None
    bpy.app.timers.register(tick, first_interval=TICK_S, persistent=True)
    threading.Thread(target=monitor_jobs, name="gui-test-monitor", daemon=True).start()
    return None


bpy.app.timers.register(start, first_interval=0.5)
