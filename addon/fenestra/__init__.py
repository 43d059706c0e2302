"""Fenestra: design windows and skylights from daylight goals.

This package is the Python API (importable in any Python 3.11 with NumPy, no Blender needed)
and the Blender add-on (bl_info, register/unregister): its Blender modules, in fenestra.blender,
alone import bpy (docs/blender.md).

    import fenestra
    scene = fenestra.load_scene("examples/reference_room/scene.json")
    c = fenestra.contributions(scene)          # E, A, T, closed / all-open values
    values, stderr = fenestra.evaluate(scene, fenestra.read_openings("openings.json"))

Sensor values are luminance-weighted irradiance: lux when the sky is given in cd/m^2.
"""

bl_info = {
    "name": "Fenestra",
    "author": "Fenestra developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > Fenestra",
    "description": "Design openings (windows, skylights) from daylight goals",
    "category": "Lighting",
}

import sys  # noqa: E402

from . import native_status  # noqa: E402

try:
    from .daylight import (
        preetham_radiance,
        preetham_sun,
        solar_position,
        sun_direction,
        sunrise_sunset,
        utc_seconds,
    )
    from .api import (
        Cancelled,
        annual,
        automatic_constraints,
        catalogues,
        goal_error,
        Contributions,
        Progress,
        Scene,
        available_memory,
        check_cost,
        check_setup,
        climate_reach,
        constraint_violations,
        contributions,
        estimate_cost,
        evaluate,
        load_scene,
        openings_array,
        read_openings,
        scene_from_dict,
        sky,
        solve,
        write_image,
        write_sky,
    )
    from .sensor_grids import sensor_grid
    from . import native_signatures
    native_signatures.install()  # wrong argument types named in Fenestra's words
except ImportError as exc:
    # Inside Blender the add-on still registers and its panel says why the native module is missing.
    if "bpy" not in sys.modules:
        raise
    native_status.import_error = exc


__all__ = [
    "annual",
    "automatic_constraints",
    "Cancelled",
    "catalogues",
    "Contributions",
    "Progress",
    "Scene",
    "available_memory",
    "check_cost",
    "check_setup",
    "climate_reach",
    "constraint_violations",
    "contributions",
    "estimate_cost",
    "evaluate",
    "goal_error",
    "load_scene",
    "openings_array",
    "preetham_radiance",
    "preetham_sun",
    "solar_position",
    "sun_direction",
    "sunrise_sunset",
    "utc_seconds",
    "read_openings",
    "scene_from_dict",
    "sensor_grid",
    "sky",
    "solve",
    "write_image",
    "write_sky",
]


def register():
    from . import blender
    blender.register()


def unregister():
    from . import blender
    blender.unregister()
