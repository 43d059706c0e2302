"""The study's sky (docs/sky.md) from scene.fenestra.sky, or from the Sun Position add-on."""

import math

import bpy

from .. import compat
from ..com.names import WORLD_NODE
from . import weather_file


def clock(hours):
    """Hours as the scene file's "HH:MM"."""
    minutes = int(round(hours * 60.0))
    return "%02d:%02d" % (minutes // 60, minutes % 60)


def occupied_problem(sky_settings):
    """None when the occupied hours are a period within one day, else what to change."""
    if not sky_settings.occupied_start < sky_settings.occupied_end:
        return ("Occupied hours: the start (%s) must be before the end (%s); the period cannot cross midnight"
                % (clock(sky_settings.occupied_start), clock(sky_settings.occupied_end)))
    return None


def climate_problem(sky_settings):
    """The first reason the climate sky cannot be used, or None (also None for another sky)."""
    if sky_settings.type != 'CLIMATE':
        return None
    return weather_file.problem(sky_settings) or occupied_problem(sky_settings)


def sun_position(scene):
    """The Sun Position add-on's settings when it is enabled, else None."""
    return getattr(scene, "sun_pos_properties", None)


def place_and_date(scene):
    """(latitude, longitude, utc_offset, north_offset_deg, (y, m, d)) from Sun Position or ours."""
    s = scene.fenestra.sky
    sp = sun_position(scene) if s.use_sun_position else None
    if sp is not None:
        utc = sp.UTC_zone + (1.0 if sp.use_daylight_savings else 0.0)
        return sp.latitude, sp.longitude, utc, math.degrees(sp.north_offset), (sp.year, sp.month, sp.day)
    return s.latitude, s.longitude, s.utc_offset, math.degrees(s.north_offset), (s.year, s.month, s.day)


def sky_dict(scene):
    """The scene file's "sky" section."""
    s = scene.fenestra.sky
    resolution = [s.map_width, max(2, s.map_width // 2 // 2 * 2)]
    if s.type == 'UNIFORM':
        return {"type": "uniform", "radiance": s.horizontal_illuminance / math.pi}
    if s.type == 'CLIMATE':
        return climate_dict(scene)
    if s.type == 'CIE_OVERCAST':
        return {"type": "cie_overcast", "horizontal_illuminance": s.horizontal_illuminance,
                "ground_reflectance": s.ground_reflectance, "resolution": resolution}
    latitude, longitude, utc, north, (y, m, d) = place_and_date(scene)
    sky = {"type": "preetham" if s.type == 'PREETHAM' else "cie_clear",
           "latitude": round(latitude, 6), "longitude": round(longitude, 6), "utc_offset": utc,
           "date": "%04d-%02d-%02d" % (y, m, d),
           "start": clock(s.start_time), "end": clock(s.end_time), "step_minutes": s.step_minutes,
           "turbidity": s.turbidity, "ground_reflectance": s.ground_reflectance,
           "north_offset_deg": round(north, 6), "resolution": resolution}
    if s.use_date_end:
        sky["date_end"] = "%04d-%02d-%02d" % (s.end_year, s.end_month, s.end_day)
    return sky


def climate_dict(scene):
    """The climate sky: the weather file (absolute, so that the study folder may move), its place,
    and this model's north. Raises ValueError with the panel's words for a bad weather file or
    occupied period (weather_file.py), before anything is written."""
    s = scene.fenestra.sky
    problem = climate_problem(s)
    if problem:
        raise ValueError(problem)
    north = place_and_date(scene)[3]
    return {"type": "climate", "weather": weather_file.path(s), "patches": int(s.patches),
            "occupied": [clock(s.occupied_start), clock(s.occupied_end)],
            "north_offset_deg": round(north, 6), "ground_reflectance": s.ground_reflectance}


def show_in_world(scene, image_path, strength):
    """Lights the World with an equirectangular map (Environment Texture, Closest, as Fenestra
    reads it) at the given strength."""
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    compat.use_nodes(world)
    nodes, links = world.node_tree.nodes, world.node_tree.links
    image = bpy.data.images.load(image_path, check_existing=True)
    image.reload()
    env = nodes.get(WORLD_NODE) or nodes.new("ShaderNodeTexEnvironment")
    env.name = env.label = WORLD_NODE
    env.image = image
    env.interpolation = 'Closest'
    env.location = (-400, 300)
    background = next((n for n in nodes if n.bl_idname == "ShaderNodeBackground"), None)
    background = background or nodes.new("ShaderNodeBackground")
    output = next((n for n in nodes if n.bl_idname == "ShaderNodeOutputWorld"), None)
    output = output or nodes.new("ShaderNodeOutputWorld")
    links.new(env.outputs["Color"], background.inputs["Color"])
    links.new(background.outputs["Background"], output.inputs["Surface"])
    background.inputs["Strength"].default_value = strength
