"""Add Sensor Grid in a real Blender window (under Xvfb), driven by real clicks and key presses
(xdotool): a room modelled as one solid (walls 0.3 m and slabs 0.2 m thick around a 4 x 5 x 3 m
cavity, the cavity's south face the opening domain), its Height and Spacing typed into the Sensors
panel, Add Sensor Grid and Check Setup clicked; and a refusal too long for the status bar, shown
whole, wrapped, in Blender's report popup (one popup: one Esc closes it). Blender runs python_tests/blender/gui_driver.py on an empty scene (the Gui of
test_blender_gui.py); the screenshots (sensor_grid.png: the grid from above, outlined, inside the
cavity; refusal.png: the popup) are left in the driver's channel folder.

Skipped without Blender, Xvfb or xdotool (`make deps` installs them)."""

import time

import pytest

from test_blender_gui import BLENDER, XDOTOOL, XVFB, calls, click, find_button, gui_fixture, open_fenestra_sidebar

pytestmark = pytest.mark.skipif(None in (BLENDER, XVFB, XDOTOOL), reason="needs Blender, Xvfb and xdotool")

CAVITY = (4.0, 5.0, 3.0)  # m, its floor's upper face at z = 0
TOL = 1e-4  # m


gui = gui_fixture("gui_grid", scene="empty")


@pytest.fixture(scope="module")
def sidebar(gui):
    """The solid room selected and the Fenestra tab open with its Sensors panel (Opening Domain and
    Sky closed); the sidebar's rectangle."""
    gui.command("solid_room")
    return open_fenestra_sidebar(gui, closed=["FENESTRA_PT_domain", "FENESTRA_PT_sky"])


def type_into(gui, rect, prop, text):
    """A click on the number field of `prop` in the sidebar (which starts editing it), its text
    replaced by `text`, Return."""
    x, y = find_button(gui, rect, prop=prop)
    gui.xdotool("mousemove", str(x), str(y))
    time.sleep(0.2)
    gui.xdotool("click", "1")
    time.sleep(0.5)
    gui.key("ctrl+a")
    gui.xdotool("type", "--delay", "60", text)
    gui.key("Return")
    time.sleep(0.5)


def wall_distance(points):
    w, d, _ = CAVITY
    return min(min(x, w - x, y, d - y) for x, y, _ in points)


def test_a_grid_over_the_floor_of_a_solid_room(gui, sidebar):
    """Height 0.8 and Spacing 0.5 typed in, Add Sensor Grid clicked: one sensor object, its sensors
    0.8 m above the floor's upper face (not the slab's underside), at least 0.25 m off the inner
    walls, and the report says so; Check Setup, clicked, finds nothing wrong."""
    gui.command("set", values={"sensor_height": 1.5, "sensor_spacing": 1.0})
    type_into(gui, sidebar, "sensor_height", "0.8")
    type_into(gui, sidebar, "sensor_spacing", "0.5")
    s = gui.command("sensor_grids")
    assert abs(s["height"] - 0.8) < 1e-6 and abs(s["spacing"] - 0.5) < 1e-6, s
    assert s["grids"] == []

    x, y = find_button(gui, sidebar, operator="FENESTRA_OT_add_sensor_grid")
    click(gui, x, y, "fenestra.add_sensor_grid")
    s = gui.command("sensor_grids")
    assert [g["name"] for g in s["grids"]] == ["Fenestra Sensors"], s["grids"]
    points = s["grids"][0]["points"]
    assert len(points) == 80, len(points)  # 8 x 10 at 0.5 m over 4 x 5 m
    assert all(abs(p[2] - 0.8) < TOL for p in points), sorted({round(p[2], 4) for p in points})
    assert wall_distance(points) >= 0.25 - TOL, wall_distance(points)
    assert all(0.0 < p[0] < CAVITY[0] and 0.0 < p[1] < CAVITY[1] for p in points)
    reports = gui.command("reports")["reports"]
    assert any("80 sensors in 1 room, 0.80 m above the floor's upper face (z = 0.00 m)" in line
               for line in reports), reports

    x, y = find_button(gui, sidebar, operator="FENESTRA_OT_check_setup", start=y)
    click(gui, x, y, "fenestra.check_setup")
    s = gui.command("sensor_grids")
    assert s["setup_checked"] and s["setup_warnings"] == "", s["setup_warnings"]

    gui.command("select", name="Fenestra Sensors")  # outlined, to tell them from the room's faces
    gui.command("from_above", location=[CAVITY[0] / 2, CAVITY[1] / 2, 1.0], distance=9.0)
    time.sleep(1.0)
    gui.command("screenshot", name="sensor_grid")
    gui.command("select", name="Room")


def refuse(gui, sidebar, name):
    """Height 3.5 m in a room 3 m high, Add Sensor Grid clicked: refused, nothing added. Screenshots
    NAME_before (the pointer on the button) and NAME (a second after the click); returns the
    button's (x, y) and the refusal as the report has it."""
    before = gui.command("sensor_grids")["grids"]
    type_into(gui, sidebar, "sensor_height", "3.5")
    x, y = find_button(gui, sidebar, operator="FENESTRA_OT_add_sensor_grid")
    gui.xdotool("mousemove", str(x), str(y))
    time.sleep(1.0)
    gui.command("screenshot", name=name + "_before")
    click(gui, x, y, "fenestra.add_sensor_grid")
    time.sleep(1.0)
    gui.command("screenshot", name=name)
    assert gui.command("sensor_grids")["grids"] == before  # nothing added
    reports = " ".join(gui.command("reports")["reports"]).replace("\n", " ")  # wrapped in the window
    start = reports.rfind("No floor of 'Room' has room for sensors 3.50 m above it")
    assert start >= 0, reports
    end = "(a face within 45\u00b0 of horizontal, its ceiling higher than that)"
    message = " ".join(reports[start:reports.index(end, start) + len(end)].split())
    return x, y, message


def popup_height(popup):
    left, top, right, bottom = popup["extent"]
    return bottom - top + 1 if popup["changed"] else 0


def test_a_long_refusal_shows_whole_in_a_popup(gui, sidebar):
    """The refusal, too long for the status bar, is shown in Blender's report popup by the pointer,
    wrapped: as wide as its widest line and as tall as its title and lines."""
    x, y, message = refuse(gui, sidebar, "refusal")
    popup = gui.command("popup", before="refusal_before", after="refusal", x=x, y=y, message=message)
    left, top, right, bottom = popup["extent"]
    lines = popup["lines"]
    print("popup %s: %d lines, the widest %.0f px" % (popup["extent"], len(lines), popup["widest"]))
    assert len(lines) >= 2, lines  # a message too long for the status bar
    assert popup["changed"] and right - left + 1 >= popup["widest"], popup
    assert popup_height(popup) >= (len(lines) + 1) * popup["line_height"], popup  # the title and every line
    gui.key("Escape")
    time.sleep(0.5)
    gui.key("Escape")
    time.sleep(0.5)


def test_one_esc_closes_the_refusal(gui, sidebar):
    """One popup, Blender's own: one Esc closes it."""
    x, y, message = refuse(gui, sidebar, "refusal_esc")
    gui.key("Escape")
    time.sleep(1.0)
    gui.command("screenshot", name="refusal_esc_closed")
    closed = gui.command("popup", before="refusal_esc_before", after="refusal_esc_closed", x=x, y=y, message=message)
    try:
        assert popup_height(closed) < 2 * closed["line_height"], closed
    finally:
        gui.key("Escape")  # whatever is left
        time.sleep(0.5)
