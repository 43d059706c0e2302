"""The Sun Position add-on's place, date and north reach the exported sky (run by
test_blender_addon.py in each Blender). Sun Position is bundled with Blender up to 4.1; from 4.2 it
is an extension from extensions.blender.org, absent from a fresh bpy 4.5: there the integration's
test is skipped, and the sky is tested to come from Fenestra's own fields."""

import os
import sys
import unittest

import addon_utils
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402


def enable_sun_position():
    """The Sun Position settings (scene.sun_pos_properties), enabled wherever Blender has it, else None."""
    names = [m.__name__ for m in addon_utils.modules() if m.__name__.split(".")[-1] == "sun_position"]
    if names:
        addon_utils.enable(names[0], default_set=True, handle_error=None)
    return getattr(bpy.context.scene, "sun_pos_properties", None)


def preetham():
    f = bpy.context.scene.fenestra
    f.sky.type, f.sky.latitude, f.sky.longitude, f.sky.utc_offset = 'PREETHAM', 10.0, 20.0, 3.0
    f.sky.year, f.sky.month, f.sky.day = 2024, 3, 4
    return f.sky


class SunPosition(unittest.TestCase):
    def setUp(self):
        bpy.ops.wm.read_homefile(use_empty=True)
        installed.enable()
        self.sky = installed.blender("study.sky")

    def test_place_date_and_north_from_sun_position(self):
        sp = enable_sun_position()
        if sp is None:
            self.skipTest("Sun Position is not installed in Blender %s (an extension from 4.2 on)"
                          % bpy.app.version_string)
        sp.latitude, sp.longitude, sp.UTC_zone, sp.use_daylight_savings = 59.33, 18.07, 1.0, True
        sp.north_offset, sp.year, sp.month, sp.day = 0.5, 2023, 6, 21
        s = preetham()
        s.use_sun_position = True
        written = self.sky.sky_dict(bpy.context.scene)
        self.assertAlmostEqual(written["latitude"], 59.33, places=5)  # (a float32 of Sun Position's)
        self.assertAlmostEqual(written["longitude"], 18.07, places=5)
        self.assertEqual((written["utc_offset"], written["date"]), (2.0, "2023-06-21"))
        self.assertAlmostEqual(written["north_offset_deg"], 28.647890, places=5)
        s.use_sun_position = False  # Fenestra's own fields again
        written = self.sky.sky_dict(bpy.context.scene)
        self.assertEqual((written["latitude"], written["longitude"], written["utc_offset"], written["date"]),
                         (10.0, 20.0, 3.0, "2024-03-04"))

    def test_without_sun_position_the_own_fields_are_used(self):
        if getattr(bpy.context.scene, "sun_pos_properties", None) is not None:
            names = [m.__name__ for m in addon_utils.modules() if m.__name__.split(".")[-1] == "sun_position"]
            addon_utils.disable(names[0], default_set=True, handle_error=None)
        self.assertIsNone(self.sky.sun_position(bpy.context.scene))
        s = preetham()
        s.use_sun_position = True  # asked for, but not there
        written = self.sky.sky_dict(bpy.context.scene)
        self.assertEqual((written["latitude"], written["longitude"], written["utc_offset"], written["date"]),
                         (10.0, 20.0, 3.0, "2024-03-04"))


if __name__ == "__main__":
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
