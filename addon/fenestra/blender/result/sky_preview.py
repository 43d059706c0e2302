"""Preview Sky: the study's sky map in the World, exposed so that it can be seen.

The map is in cd/m² (thousands at the zenith); the World shows it at *Preview Strength*, and the
scene's exposure is set so that the zenith comes out mid grey: at the default strength the World is
not a white glare. A later strength change only rescales the World (the map is kept).

Blender's Material Preview and Rendered shading light the viewport with a studio light unless
*Scene World* is on (View3DShading.use_scene_world, use_scene_world_render), which it is not by
default: Preview Sky turns it on in the 3D Views it is given, so that the World shows."""

import math
import os
import tempfile

import numpy as np

from .. import compat
from ..com import names, native
from ..study import export, sky

MID_GREY = 0.18     # scene-linear value that the view transforms show as mid grey
LUMINANCE = (0.2126, 0.7152, 0.0722)  # linear sRGB (Rec. 709) weights
EXPOSURE_LIMIT = 32.0  # Blender's range for view_settings.exposure


def zenith_luminance(sky_map):
    """cd/m² at the zenith: the map's top row (equirectangular, zenith on top)."""
    return float(np.mean(np.asarray(sky_map[0], np.float64) @ LUMINANCE))


def exposure_for(zenith, strength):
    """Stops that bring the zenith, shown at this World strength, to mid grey; None when dark."""
    shown = zenith * strength
    if not shown > 0.0:
        return None
    return max(-EXPOSURE_LIMIT, min(EXPOSURE_LIMIT, math.log2(MID_GREY / shown)))


def preview(scene):
    """Computes the sky map into `sky.exr` in the study folder, lights the World with it and sets
    the exposure. Returns (the sky's summary dict, the exposure set or None). Raises ValueError or
    OSError with the native message."""
    from ... import api as fenestra
    path = os.path.join(export.study_directory(scene), "sky.exr")
    with tempfile.TemporaryDirectory() as probe:
        native_scene = native.probe_scene(probe, sky=sky.sky_dict(scene))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        fenestra.write_sky(native_scene, path)
        summary = fenestra.sky(native_scene)
    strength = scene.fenestra.sky.preview_strength
    sky.show_in_world(scene, path, strength)
    exposure = exposure_for(zenith_luminance(summary["map"]), strength)
    if exposure is not None:
        scene.view_settings.exposure = exposure
    return summary, exposure


def show_world_in_viewports(screens):
    """Turns on Scene World in Material Preview and Rendered shading in every 3D View of `screens`;
    returns how many of them had it off (in either)."""
    changed = 0
    for screen in screens:
        for area in screen.areas:
            if area.type != 'VIEW_3D':
                continue
            for space in area.spaces:
                if space.type != 'VIEW_3D':
                    continue
                shading = space.shading
                if not (shading.use_scene_world and shading.use_scene_world_render):
                    shading.use_scene_world = shading.use_scene_world_render = True
                    changed += 1
    return changed


def strength_changed(sky_settings, context):
    """Update of *Preview Strength*: the previewed World at the new strength, nothing recomputed."""
    world = context.scene.world
    if world is None or not compat.uses_nodes(world) or names.WORLD_NODE not in world.node_tree.nodes:
        return  # no preview yet: the next Preview Sky uses the strength
    for link in world.node_tree.nodes[names.WORLD_NODE].outputs["Color"].links:
        if link.to_node.bl_idname == "ShaderNodeBackground":
            link.to_node.inputs["Strength"].default_value = sky_settings.preview_strength
