"""Preview Sky in a real Blender window (under Xvfb), by real keys and clicks: Z's shading pie to
Material Preview, where the viewport's background is Blender's own; a click on Preview Sky (Sky
panel) lights the World with the study's sky and turns Scene World on, and the background then shows
that sky instead of Blender's neutral grey. Blender runs python_tests/blender/gui_driver.py
on the room example; screenshots are left in its channel folder.

Skipped without Blender, Xvfb or xdotool (`make deps` installs them)."""

import time

import numpy as np
import pytest

from test_blender_gui import BLENDER, XDOTOOL, XVFB, click, find_button, gui_fixture, open_fenestra_sidebar

pytestmark = pytest.mark.skipif(None in (BLENDER, XVFB, XDOTOOL), reason="needs Blender, Xvfb and xdotool")

gui = gui_fixture("gui_sky")

CLEAR_SKY = {"sky.type": 'PREETHAM', "sky.month": 6, "sky.day": 21, "sky.use_date_end": False, "sky.start_time": 12.0}
RENDER_WAIT_S = 60.0  # EEVEE on software OpenGL compiles its shaders first


def background(gui, name):
    """The colours of a band of the 3D View's background in screenshot NAME: near its top, above
    the room example's ground (n, 3)."""
    gui.command("screenshot", name=name)
    import matplotlib.image
    pixels = matplotlib.image.imread("%s/%s.png" % (gui.channel, name))[:, :, :3]
    x, y = gui.state["view3d"]
    return pixels[90:140, x - 300:x + 100].reshape(-1, 3)


def settled(gui, name, timeout=RENDER_WAIT_S):
    """The background once two screenshots two seconds apart agree (EEVEE has rendered)."""
    deadline, last = time.monotonic() + timeout, None
    while time.monotonic() < deadline:
        time.sleep(2.0)
        now = background(gui, name)
        if last is not None and np.abs(now.mean(axis=0) - last.mean(axis=0)).max() < 0.01:
            return now
        last = now
    raise AssertionError("the 3D View kept changing for %.0f s" % timeout)


def test_preview_sky_shows_in_material_preview(gui):
    gui.command("set", values=CLEAR_SKY)
    gui.point_at_view()
    time.sleep(0.3)
    gui.key("z")  # the shading pie
    time.sleep(0.5)
    gui.key("m")  # Material Preview
    deadline = time.monotonic() + 30
    while gui.command("shading")["type"] != 'MATERIAL' and time.monotonic() < deadline:
        time.sleep(0.3)
    shading = gui.command("shading")
    assert shading["type"] == 'MATERIAL' and not shading["use_scene_world"], shading
    before = settled(gui, "material_preview_before")

    rect = open_fenestra_sidebar(gui, closed=["FENESTRA_PT_domain", "FENESTRA_PT_sensors", "FENESTRA_PT_solve"])
    x, y = find_button(gui, rect, "FENESTRA_OT_preview_sky")
    click(gui, x, y, "fenestra.preview_sky")
    shading = gui.command("shading")
    assert shading["use_scene_world"] and shading["use_scene_world_render"] and shading["world"], shading
    gui.point_at_view()
    after = settled(gui, "material_preview_sky")
    print("background before %s, with the sky %s" % (before.mean(axis=0).round(3), after.mean(axis=0).round(3)))
    assert np.ptp(before, axis=1).max() < 0.01, before  # Blender's own background: neutral grey
    assert np.abs(after.mean(axis=0) - before.mean(axis=0)).max() > 0.1, (before, after)  # the sky's
