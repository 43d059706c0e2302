"""Annual Daylight in a window (needs a display; run by test_blender_results.py under Xvfb, and used for
docs/blender-annual.png):

    blender --window-geometry 0 0 1400 2100 --python screenshot_annual.py -- OUT.png

with user preferences whose splash screen is off (BLENDER_USER_CONFIG) and the add-on on Blender's
add-on path (BLENDER_USER_SCRIPTS/addons/fenestra). The room of addon_study.py with one window and a
year of Chicago weather: a solve, then Annual Daylight started as from its button (modal, on a worker
thread), and a screenshot of the whole window once it is done (annual_window.png beside OUT.png):
the Fenestra tab with the Sky and Annual Daylight panels, the sensors in false colour (daylight
autonomy) seen from above, and the legend; OUT.png is the 3D View's area (viewport and sidebar)
cropped from it. Prints one line per check, "CHECK name ok|FAILED numbers", and exits 1 when a check fails
or a step raises."""

import math
import os
import sys
import time

import bpy
import numpy as np
from bpy_extras.view3d_utils import location_3d_to_region_2d
from mathutils import Euler

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_study  # noqa: E402
import window_script  # noqa: E402

OUT = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
addon_study.OUT = os.path.join(os.path.dirname(OUT), "annual_study")
RUN_TIMEOUT_S = 300
state = {"failed": []}


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == 'VIEW_3D'), key=lambda a: a.width * a.height)
    return window, area, next(r for r in area.regions if r.type == 'WINDOW')


def check(name, passed, numbers):
    print("CHECK %s %s %s" % (name, "ok" if passed else "FAILED", numbers))
    if not passed:
        state["failed"].append(name)


def setup():
    addon_study.enable()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    addon_study.study()
    addon_study.climate()
    f = bpy.context.scene.fenestra
    f.solve.constraints.max_openings, f.solve.constraints.max_width = 1, 1.5
    f.solve.wall_thickness = 0.0
    assert bpy.ops.fenestra.solve_openings() == {'FINISHED'}
    window_script.only_the_fenestra_tab((
        "FENESTRA_PT_domain", "FENESTRA_PT_sensors", "FENESTRA_PT_solve", "FENESTRA_PT_result_display",
        "FENESTRA_PT_selected_sensor"))
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
    r3d.view_location = (2.0, 1.6, 1.0)
    r3d.view_rotation = Euler((math.radians(30), 0, 0)).to_quaternion()  # from above, the window side near
    r3d.view_distance = 8.5
    bpy.context.view_layer.objects.active = None  # the Item tab has nothing to show: Fenestra's is shown
    with bpy.context.temp_override(window=window, area=area, region=region):
        assert bpy.ops.fenestra.annual_daylight('INVOKE_DEFAULT') == {'RUNNING_MODAL'}
    state["started"] = time.time()
    return None


def wait_for_the_run():
    from fenestra.blender.com import solve_job
    if solve_job.running() is not None or not bpy.context.scene.fenestra.annual.valid:
        if time.time() - state["started"] > RUN_TIMEOUT_S:
            print("the annual run did not finish: %s" % getattr(solve_job.last(), "outcome", None))
            os._exit(1)
        if solve_job.running() is None and not bpy.context.scene.fenestra.annual.valid:
            print("the annual run ended without a result: %s" % solve_job.last().outcome)
            os._exit(1)
        return 0.5
    check("annual_run_modal", True, "%.1f s" % (time.time() - state["started"]))
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
    from fenestra.blender.draw import legend
    from fenestra.blender.result import result_display
    window, area, region = view3d()
    whole = os.path.join(os.path.dirname(OUT), "annual_window.png")
    with bpy.context.temp_override(window=window):
        bpy.ops.screen.screenshot(filepath=whole)
    pixels = window_pixels(whole)
    scale, shown = result_display.current(bpy.context)
    check("annual_scale", scale.quantity == 'DA' and scale.top == 100.0, "%s 0..%g" % (scale.title, scale.top))
    # The legend's bar, in window pixels: the colour map where it belongs, and its title above.
    with bpy.context.temp_override(window=window, area=area, region=region):
        _, (x0, y0, x1, y1) = legend.layout(bpy.context)
    ox, oy = region.x, region.y
    row = pixels[oy + int((y0 + y1) / 2), ox + int(x0):ox + int(x1)]
    at = np.array([0.05, 0.5, 0.95])
    seen = row[(at * (len(row) - 1)).astype(int)]
    want = scale.colours(at * scale.top)[:, :3]
    check("legend_bar_drawn", np.abs(seen - want).max() < 0.06,
          "at %s of the bar: %s, colour map %s" % (at, np.round(seen, 2).tolist(), np.round(want, 2).tolist()))
    title = pixels[oy + int(y1) + 2:oy + int(y1) + 20, ox + int(x0):ox + int(x1)]
    check("legend_title_drawn", (title.min(axis=2) > 0.8).sum() > 30, "%d white pixels" % (title.min(axis=2) > 0.8).sum())
    # Each sensor's dot in the colour of its daylight autonomy.
    sensors = bpy.data.objects["Fenestra Sensors"]
    values = shown[sensors.name]
    colours = scale.colours(values)[:, :3]
    errors = []
    for vertex, colour in zip(sensors.data.vertices, colours):
        where = location_3d_to_region_2d(region, area.spaces.active.region_3d, sensors.matrix_world @ vertex.co)
        x, y = ox + int(round(where.x)), oy + int(round(where.y))
        patch = pixels[y - 1:y + 2, x - 1:x + 2].reshape(-1, 3)
        errors.append(float(np.abs(patch - colour).max(axis=1).min()))
    check("sensors_in_false_colour", max(errors) < 0.08,
          "worst sensor off its colour by %.3f (DA %.0f..%.0f %%)" % (max(errors), values.min(), values.max()))
    window_script.save_area(pixels, area, OUT)
    a = bpy.context.scene.fenestra.annual
    print("ANNUAL sDA %.3f ASE %.3f DA %.3f mean %.0f lx EN17037 %r; screenshot %s"
          % (a.spatial_daylight_autonomy, a.annual_sunlight_exposure, a.daylight_autonomy, a.mean_illuminance,
             a.en17037_level, OUT))
    window_script.exit_with_verdict(state["failed"])


def start():
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    setup()
    bpy.app.timers.register(window_script.guarded(wait_for_the_run), first_interval=0.5)
    return None


bpy.app.timers.register(window_script.guarded(start), first_interval=1.0)
