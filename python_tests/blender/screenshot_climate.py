"""Climate goals on a floor of rooms, in a window (needs a display and xdotool; run by
test_blender_climate.py under Xvfb, and used for docs/blender-climate-goals.png):

    blender --window-geometry 0 0 1400 2100 --python screenshot_climate.py -- OUT.png

with user preferences whose splash screen is off (BLENDER_USER_CONFIG) and the add-on on Blender's
add-on path (BLENDER_USER_SCRIPTS/addons/fenestra). Two rooms side by side (addon_climate.py's
floor: each lit by its south wall, each with its own sensor grid) under a year of Chicago weather,
Climate Goals Only. F6 is mapped to Add Climate Goal and F5 to Solve Openings (as a user's
shortcuts would be); real key presses (xdotool, the pointer over the 3D View) add an sDA and an
ASE goal per room and start the solve, which runs modal on its worker thread. Once it is done: a
screenshot of the whole window (the Climate Goals list under Sensors, the goals reached and each
room's figures under Results, the sensors in their DA colours seen from above, the legend) and
OUT.png, the 3D View's area (viewport and sidebar) cropped from it. Prints "CHECK name ok|FAILED
numbers" per check and exits 1 when a check fails or a step raises."""

import math
import os
import subprocess
import sys
import time

import bpy
import numpy as np
from bpy_extras.view3d_utils import location_3d_to_region_2d
from mathutils import Euler

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_climate  # noqa: E402
import addon_study  # noqa: E402
import window_script  # noqa: E402

OUT = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
addon_study.OUT = addon_climate.OUT = os.path.join(os.path.dirname(OUT), "climate_study")
ROOMS = ("West office", "East office")
RUN_TIMEOUT_S = 300
KEY_TIMEOUT_S = 20
state = {"failed": []}


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == 'VIEW_3D'), key=lambda a: a.width * a.height)
    return window, area, next(r for r in area.regions if r.type == 'WINDOW')


def check(name, passed, numbers):
    print("CHECK %s %s %s" % (name, "ok" if passed else "FAILED", numbers))
    sys.stdout.flush()
    if not passed:
        state["failed"].append(name)


def xdotool(*args):
    subprocess.run(["xdotool", *args], check=True, timeout=10)


def press(key):
    """A real key press with the pointer over the 3D View (X coordinates: origin top left)."""
    window, area, region = view3d()
    x = window.x + region.x + region.width // 2
    y = window.height - (region.y + region.height // 2)
    xdotool("mousemove", str(x), str(y))
    xdotool("key", key)


def setup():
    addon_study.enable()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    state["grids"] = [g.name for g in addon_climate.floor(ROOMS)]
    f = bpy.context.scene.fenestra
    f.goals.source = 'NONE'
    f.goals.least_glazing = True
    keymap = bpy.context.window_manager.keyconfigs.addon.keymaps.new(name="Window", space_type='EMPTY')
    keymap.keymap_items.new("fenestra.climate_goal_add", 'F6', 'PRESS')
    keymap.keymap_items.new("fenestra.solve_openings", 'F5', 'PRESS')
    window_script.only_the_fenestra_tab((
        "FENESTRA_PT_domain", "FENESTRA_PT_sky", "FENESTRA_PT_solve", "FENESTRA_PT_result_display",
        "FENESTRA_PT_selected_sensor", "FENESTRA_PT_annual"))
    window, area, region = view3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.show_region_toolbar = False
    space.show_gizmo = False
    space.overlay.show_floor = space.overlay.show_axis_x = space.overlay.show_axis_y = False
    space.shading.type = 'SOLID'
    space.shading.show_xray = True  # the sensors through the ceiling
    r3d = space.region_3d
    r3d.view_perspective = 'PERSP'
    r3d.view_location = (5.3, 1.8, 1.0)
    r3d.view_rotation = Euler((math.radians(30), 0, 0)).to_quaternion()
    r3d.view_distance = 15.0
    bpy.context.view_layer.objects.active = None
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    state["started"] = time.time()


def add_the_goals():
    for _ in range(2 * len(ROOMS)):
        press("F6")
    state["started"] = time.time()
    bpy.app.timers.register(window_script.guarded(wait_for_the_goals), first_interval=0.5)
    return None


def wait_for_the_goals():
    goals = bpy.context.scene.fenestra.goals
    if len(goals.climate) < 2 * len(ROOMS):
        if time.time() - state["started"] > KEY_TIMEOUT_S:
            check("goals_added_by_keys", False, "%d goals after %d s" % (len(goals.climate), KEY_TIMEOUT_S))
            return finish()
        return 0.2
    check("goals_added_by_keys", len(goals.climate) == 2 * len(ROOMS), [g.metric for g in goals.climate])
    # Each room: an sDA goal and an ASE goal on its sensor grid.
    for i, grid in enumerate(state["grids"]):
        sda, ase = goals.climate[2 * i], goals.climate[2 * i + 1]
        sda.metric, sda.sda_area, sda.sensor_group = 'SDA', 50.0, grid
        ase.metric, ase.sensor_group = 'ASE', grid
    goals.climate_index = 0
    press("F5")
    state["started"] = time.time()
    bpy.app.timers.register(window_script.guarded(wait_for_the_solve), first_interval=0.5)
    return None


def wait_for_the_solve():
    from fenestra.blender.com import solve_job
    r = bpy.context.scene.fenestra.results
    if solve_job.running() is not None or not r.valid:
        if time.time() - state["started"] > RUN_TIMEOUT_S:
            check("solve_modal", False, "no result after %d s: %s" % (RUN_TIMEOUT_S, getattr(solve_job.last(), "outcome", None)))
            return finish()
        if solve_job.last() is None and time.time() - state["started"] > KEY_TIMEOUT_S:
            check("solve_modal", False, "F5 started no solve")
            return finish()
        if solve_job.running() is None and solve_job.last() is not None and not r.valid:
            check("solve_modal", False, "ended without a result: %s" % solve_job.last().outcome)
            return finish()
        return 0.5
    check("solve_modal", solve_job.last() is not None and r.climate.valid,
          "%.1f s: %s" % (time.time() - state["started"], solve_job.last().outcome))
    bpy.app.timers.register(window_script.guarded(shoot), first_interval=1.0)
    return None


def window_pixels(path):
    """The window's screenshot as (h, w, 3) display values, bottom row first."""
    image = bpy.data.images.load(path)
    w, h = image.size
    pixels = np.zeros(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(h, w, 4)[:, :, :3]


def shoot():
    from fenestra.blender.result import result_display
    from fenestra.blender.ui.climate_panel import FENESTRA_PT_climate_results
    window, area, region = view3d()
    whole = os.path.join(os.path.dirname(OUT), "climate_window.png")
    with bpy.context.temp_override(window=window):
        bpy.ops.screen.screenshot(filepath=whole)
    pixels = window_pixels(whole)
    f = bpy.context.scene.fenestra
    c = f.results.climate
    check("results_list_the_goals", FENESTRA_PT_climate_results.poll(bpy.context) and
          [g.description for g in c.goals] == [d % grid for grid in state["grids"]
                                               for d in ("sDA300/50%% >= 50 %% (%s)", "ASE1000,250 <= 10 %% (%s)")],
          [(g.description, round(g.achieved, 3), g.met) for g in c.goals])
    check("rooms_listed", [room.name for room in c.rooms] == state["grids"] and
          [room.sensors for room in c.rooms] == [len(bpy.data.objects[g].data.vertices) for g in state["grids"]],
          [(room.name, room.sensors, round(room.spatial_daylight_autonomy, 3)) for room in c.rooms])
    scale, shown = result_display.current(bpy.context)
    check("da_scale", scale.quantity == 'CLIMATE_DA' and scale.top == 100.0, "%s 0..%g" % (scale.title, scale.top))
    ox, oy = region.x, region.y
    errors, low, high = [], 100.0, 0.0
    for grid in state["grids"]:
        sensors = bpy.data.objects[grid]
        values = shown[sensors.name]
        low, high = min(low, values.min()), max(high, values.max())
        colours = scale.colours(values)[:, :3]
        for vertex, colour in zip(sensors.data.vertices, colours):
            where = location_3d_to_region_2d(region, area.spaces.active.region_3d, sensors.matrix_world @ vertex.co)
            x, y = ox + int(round(where.x)), oy + int(round(where.y))
            patch = pixels[y - 1:y + 2, x - 1:x + 2].reshape(-1, 3)
            errors.append(float(np.abs(patch - colour).max(axis=1).min()))
    check("sensors_in_da_colours", max(errors) < 0.08,
          "worst sensor off its colour by %.3f (DA %.0f..%.0f %%)" % (max(errors), low, high))
    # OUT: the 3D View's area (the viewport and the sidebar), cropped from the window.
    window_script.save_area(pixels, area, OUT)
    print("CLIMATE %s; glazing %.2f of %.2f m²; screenshot %s" % (
        "; ".join("%s: %.3f %s" % (g.description, g.achieved, "met" if g.met else "not met") for g in c.goals),
        c.glazing_area, c.domain_area, OUT))
    return finish()


def finish():
    window_script.exit_with_verdict(state["failed"])


def start():
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    setup()
    bpy.app.timers.register(window_script.guarded(add_the_goals), first_interval=0.5)
    return None


bpy.app.timers.register(window_script.guarded(start), first_interval=1.0)
