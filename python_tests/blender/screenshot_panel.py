"""Screenshot of the Fenestra tab after an interactive (modal) solve, for docs/ (needs a display):

    xvfb-run -a -s "-screen 0 1400x1950x24" blender --enable-event-simulate --window-geometry 0 0 1400 1950 \\
        --python python_tests/blender/screenshot_panel.py -- docs/blender-panel.png

with user preferences whose splash screen is off (BLENDER_USER_CONFIG).

The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra). Exits 1 if the
solve does not finish."""

import math
import os
import sys
import tempfile
import time
import traceback

import bpy
from mathutils import Euler

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_study  # noqa: E402
import window_script  # noqa: E402

OUT = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
addon_study.OUT = tempfile.mkdtemp()  # the study folder
state = {"started": None}


def view3d():
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == 'VIEW_3D':
            return window, area, next(r for r in area.regions if r.type == 'WINDOW')
    raise RuntimeError("no 3D View")


def setup():
    addon_study.enable()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    addon_study.study()
    f = bpy.context.scene.fenestra
    f.sky.type, f.sky.horizontal_illuminance = 'CIE_OVERCAST', 10000.0
    f.goals.units, f.goals.level = 'DAYLIGHT_FACTOR', 2.0
    space = view3d()[1].spaces.active
    space.shading.show_xray = True
    space.shading.xray_alpha = 0.6
    f.solve.element_size, f.solve.quality = 0.3, 'PREVIEW'
    # Only the Fenestra tab in the sidebar; the Constraints sub-panel open, so that its automatic
    # values show; Sky and Checks closed, so that the Results fit below.
    window_script.hide_other_tabs()
    window_script.set_panel_options({"FENESTRA_PT_constraints": set(), "FENESTRA_PT_sky": {'DEFAULT_CLOSED'},
                                     "FENESTRA_PT_checks": {'DEFAULT_CLOSED'}})
    window, area, region = view3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.show_region_toolbar = False
    space.overlay.show_floor = False
    r3d = space.region_3d
    r3d.view_perspective = 'PERSP'
    r3d.view_location = (2.0, 1.0, 1.0)
    r3d.view_rotation = Euler((math.radians(70), 0, math.radians(-35))).to_quaternion()
    r3d.view_distance = 9.0
    with bpy.context.temp_override(window=window, area=area, region=region):
        assert bpy.ops.fenestra.solve_openings('INVOKE_DEFAULT') == {'RUNNING_MODAL'}
    state["started"] = time.time()
    return 0.5


def wait_and_shoot():
    if not bpy.context.scene.fenestra.results.valid:
        if time.time() - state["started"] > 120:
            print("the solve did not finish")
            os._exit(1)
        return 0.5
    bpy.context.view_layer.objects.active = None  # the Item tab has nothing to show: Fenestra's is shown
    window, area, region = view3d()
    if state.get("widened") is None:
        # Drag the sidebar's edge to the left (events are simulated: --enable-event-simulate).
        ui = next(r for r in area.regions if r.type == 'UI')
        x, y = ui.x + 2, ui.y + ui.height // 2
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        window.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y)
        for step in range(1, 11):
            window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x - 16 * step, y=y)
        window.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x - 160, y=y)
        state["widened"] = True
        return 1.0
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screenshot_area(filepath=OUT)
    r = bpy.context.scene.fenestra.results
    print("SOLVED %d openings, %.3f relative RMS; screenshot %s" % (r.openings, r.relative_rms, OUT))
    print("WARNINGS %s" % r.warnings)
    bpy.ops.wm.quit_blender()
    return None


def guarded(step):
    """A timer callback that ends Blender with status 1 on an exception."""
    def run():
        try:
            return step()
        except Exception:
            traceback.print_exc()
            os._exit(1)
    return run


def start():
    setup()
    bpy.app.timers.register(guarded(wait_and_shoot), first_interval=1.0)
    return None


bpy.app.timers.register(guarded(start), first_interval=1.0)
