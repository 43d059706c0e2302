"""The viewport after Preview Sky and a solve, checked on screenshots (needs a display; run by
test_blender_results.py under Xvfb):

    blender --enable-event-simulate --window-geometry 0 0 1400 1000 --python screenshot_results.py -- OUT_DIR

with user preferences whose splash screen is off (BLENDER_USER_CONFIG) and the add-on on Blender's
add-on path (BLENDER_USER_SCRIPTS/addons/fenestra). Writes OUT_DIR/sky.png, sky_brighter.png,
results.png and hover.png (screenshots of the 3D View; the pointer is moved by simulated events) and prints one line per check: "CHECK name ok|FAILED
numbers". Exits 1 when a check fails or a step raises."""

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
addon_study.OUT = os.path.join(OUT, "study")
MATERIAL_PREVIEW_TIMEOUT = 240  # s: a software renderer compiles the World's shader slowly
state = {"failed": [], "started": time.time()}


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == 'VIEW_3D'), key=lambda a: a.width * a.height)
    return window, area, next(r for r in area.regions if r.type == 'WINDOW')


def screenshot(name):
    """The 3D View area as an (h, w, 3) array of display values 0..1, bottom row first, and the
    offset (x, y) of its WINDOW region in it."""
    window, area, region = view3d()
    path = os.path.join(OUT, name)
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screenshot_area(filepath=path)
    image = bpy.data.images.load(path)
    w, h = image.size
    pixels = np.zeros(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(h, w, 4)[:, :, :3], (region.x - area.x, region.y - area.y)


def check(name, passed, numbers):
    print("CHECK %s %s %s" % (name, "ok" if passed else "FAILED", numbers))
    if not passed:
        state["failed"].append(name)


def sky_region(pixels, offset):
    """The upper middle of the viewport: only sky when looking up."""
    _, area, region = view3d()
    x0, y0 = offset
    return pixels[y0 + int(0.6 * region.height):y0 + int(0.9 * region.height),
                  x0 + int(0.3 * region.width):x0 + int(0.6 * region.width)]


def setup():
    addon_study.enable()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    addon_study.study()
    f = bpy.context.scene.fenestra
    f.sky.type, f.sky.horizontal_illuminance, f.sky.map_width = 'CIE_OVERCAST', 10000.0, 256
    f.goals.units, f.goals.level = 'DAYLIGHT_FACTOR', 3.0
    assert bpy.ops.fenestra.solve_openings() == {'FINISHED'}
    assert bpy.ops.fenestra.preview_sky() == {'FINISHED'}
    window, area, region = view3d()
    space = area.spaces.active
    space.show_region_ui = False
    space.show_gizmo = False
    space.overlay.show_floor = space.overlay.show_axis_x = space.overlay.show_axis_y = False
    space.shading.type = 'MATERIAL'
    # Preview Sky turned on the World in Material Preview and Rendered (off by default: a studio light).
    check("preview_sky_shows_the_world", space.shading.use_scene_world and space.shading.use_scene_world_render,
          "use_scene_world %s, use_scene_world_render %s"
          % (space.shading.use_scene_world, space.shading.use_scene_world_render))
    r3d = space.region_3d
    r3d.view_perspective = 'PERSP'
    r3d.view_location = (2.0, -6.0, 1.5)
    r3d.view_rotation = Euler((math.radians(150), 0, 0)).to_quaternion()  # looking up, away from the room
    r3d.view_distance = 1.0
    bpy.context.scene.fenestra.display.show_legend = False  # the sky alone first
    return 2.0


def wait_for_the_world():
    """Material Preview shows a black or grey viewport until the World's shader is compiled: wait
    for the sky to show and settle."""
    pixels, offset = screenshot("sky.png")
    mean = float(sky_region(pixels, offset).mean())
    settled = mean > 0.05 and abs(mean - state.get("last", -1.0)) < 0.005
    state["last"] = mean
    if not settled and time.time() - state["started"] < MATERIAL_PREVIEW_TIMEOUT:
        return 3.0
    return check_sky()


def check_sky():
    pixels, offset = screenshot("sky.png")
    sky = sky_region(pixels, offset)
    mean, white = float(sky.mean()), float((sky.min(axis=2) > 0.97).mean())
    check("sky_not_white", mean < 0.85 and white < 0.02, "mean %.3f, white fraction %.3f" % (mean, white))
    check("sky_not_black", mean > 0.15, "mean %.3f" % mean)
    state["sky_mean"] = mean
    bpy.context.scene.fenestra.sky.preview_strength *= 4.0  # two stops, without Preview Sky
    bpy.app.timers.register(window_script.guarded(check_brighter), first_interval=4.0)
    return None


def check_brighter():
    pixels, offset = screenshot("sky_brighter.png")
    mean = float(sky_region(pixels, offset).mean())
    check("strength_applies_at_once", mean > state["sky_mean"] + 0.08,
          "mean %.3f after, %.3f before" % (mean, state["sky_mean"]))
    window, area, region = view3d()
    space = area.spaces.active
    space.shading.type = 'SOLID'
    space.shading.show_xray = True
    r3d = space.region_3d
    r3d.view_location = (2.0, 2.0, 1.0)
    r3d.view_rotation = Euler((0, 0, 0)).to_quaternion()  # from above, through the ceiling
    r3d.view_distance = 9.0
    bpy.context.scene.fenestra.display.show_legend = True
    bpy.app.timers.register(window_script.guarded(check_legend), first_interval=3.0)
    return None


def check_legend():
    from fenestra.blender.draw import legend
    from fenestra.blender.result import result_display
    pixels, offset = screenshot("results.png")
    window, area, region = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        _, (x0, y0, x1, y1) = legend.layout(bpy.context)
    ox, oy = offset
    row = pixels[oy + int((y0 + y1) / 2), ox + int(x0):ox + int(x1)]
    scale, _ = result_display.current(bpy.context)
    at = np.array([0.05, 0.5, 0.95])
    seen = row[(at * (len(row) - 1)).astype(int)]
    want = scale.colours(at * scale.top)[:, :3]
    check("legend_bar_drawn", np.abs(seen - want).max() < 0.06,
          "at %s of the bar: %s, colour map %s" % (at, np.round(seen, 2).tolist(), np.round(want, 2).tolist()))
    check("legend_bar_graded", len(np.unique(np.round(row, 2), axis=0)) > 10,
          "%d distinct colours along the bar" % len(np.unique(np.round(row, 2), axis=0)))
    # Text above the bar (the title): bright pixels on the dark background.
    title = pixels[oy + int(y1) + 2:oy + int(y1) + 20, ox + int(x0):ox + int(x1)]
    check("legend_title_drawn", (title.min(axis=2) > 0.8).sum() > 30,
          "%d white pixels" % (title.min(axis=2) > 0.8).sum())
    # Inspect Sensors: the pointer moved next to a sensor labels it.
    with bpy.context.temp_override(window=window, area=area, region=region):
        assert bpy.ops.fenestra.inspect_sensors('INVOKE_DEFAULT') == {'RUNNING_MODAL'}
    sensors = bpy.data.objects["Fenestra Sensors"]
    target = len(sensors.data.vertices) // 2
    where = location_3d_to_region_2d(region, region_data(), sensors.matrix_world @ sensors.data.vertices[target].co)
    x, y = int(region.x + where.x + 4), int(region.y + where.y + 3)
    window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x - 40, y=y)
    window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    state["target"], state["where"] = target, (where.x, where.y)
    bpy.app.timers.register(window_script.guarded(check_hover), first_interval=2.0)
    return None


def region_data():
    return view3d()[1].spaces.active.region_3d


def check_hover():
    from fenestra.blender.draw import sensor_hover
    pixels, (ox, oy) = screenshot("hover.png")
    hovered = dict(sensor_hover.hovered)
    check("hovered_sensor", hovered.get("object") == "Fenestra Sensors" and hovered.get("vertex") == state["target"],
          "hovered %s, pointed at vertex %d" % (hovered.get("vertex"), state["target"]))
    x, y = state["where"]
    label = pixels[oy + int(y) + 2:oy + int(y) + 20, ox + int(x) + 8:ox + int(x) + 160]
    check("hover_label_drawn", (label.min(axis=2) > 0.8).sum() > 30, "%d white pixels" % (label.min(axis=2) > 0.8).sum())
    window = view3d()[0]
    window.event_simulate(type='ESC', value='PRESS')
    bpy.app.timers.register(window_script.guarded(finish), first_interval=1.0)
    return None


def finish():
    from fenestra.blender.draw import sensor_hover
    check("inspect_ends_on_esc", not sensor_hover.hovered, str(sensor_hover.hovered))
    window_script.exit_with_verdict(state["failed"])


def start():
    os.makedirs(OUT, exist_ok=True)
    setup()
    bpy.app.timers.register(window_script.guarded(wait_for_the_world), first_interval=3.0)
    return None


bpy.app.timers.register(window_script.guarded(start), first_interval=1.0)
