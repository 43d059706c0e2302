"""Renders, with Cycles, Blender's Preetham Sky Texture as a latitude-longitude panorama.

blender -b --factory-startup --python-exit-code 1 --python render_preetham.py -- \
    TURBIDITY SUN_X SUN_Y SUN_Z OUT.exr WIDTH [HEIGHT]

The World is a Sky Texture node (sky_type 'PREETHAM', the given turbidity, sun_direction in
Blender world coordinates, +Z up) feeding the Background; there is no geometry, so every camera
ray sees the sky. An equirectangular panoramic camera sits at the origin, upright, rotated so
that the image centre looks toward +Y: pixel (row i, column j) of a W x H image, row 0 at the
top, looks toward elevation 90 - 180 (i + 0.5) / H degrees and azimuth (clockwise from +Y
toward +X) -180 + 360 (j + 0.5) / W degrees, i.e. the image reads west - north - east - south
from left to right like a panorama seen from inside. A Gaussian pixel filter 0.01 pixel wide
puts the samples at the pixel centre (Cycles' box filter ignores the width and spreads them
over the pixel), so the render has no Monte Carlo noise to speak of.

Writes OUT.exr (float RGBA OpenEXR, linear, view transform 'Standard', exposure 0) and
OUT.npz with, decoded by Blender from the renders, "radiance" (H, W, 3) and "direction"
(H, W, 3): the world direction of each pixel's camera ray, rendered by Cycles through the same
camera from a World that emits (direction + 1) / 2, so callers can check the mapping above.
"""

import math
import os
import sys

import bpy
import numpy as np

argv = sys.argv[sys.argv.index("--") + 1:]
turbidity = float(argv[0])
sun = tuple(float(c) for c in argv[1:4])
out_path = argv[4]
width = int(argv[5])
height = int(argv[6]) if len(argv) > 6 else width // 2

scene = bpy.context.scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 4
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0
scene.render.resolution_x = width
scene.render.resolution_y = height
scene.render.resolution_percentage = 100
scene.cycles.pixel_filter_type = "GAUSSIAN"
scene.cycles.filter_width = 0.01  # samples at the pixel centre
scene.render.film_transparent = False
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_mode = "RGBA"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "ZIP"

cam_data = bpy.data.cameras.new("panorama")
cam_data.type = "PANO"
cam_data.cycles.panorama_type = "EQUIRECTANGULAR"
cam_data.cycles.latitude_min, cam_data.cycles.latitude_max = -math.pi / 2, math.pi / 2
cam_data.cycles.longitude_min, cam_data.cycles.longitude_max = -math.pi, math.pi
cam = bpy.data.objects.new("panorama", cam_data)
scene.collection.objects.link(cam)
cam.location = (0.0, 0.0, 0.0)
# A Blender camera looks along its local -Z with local +Y up; (90, 0, 0) degrees turns it to look
# along +Y with +Z up, and Cycles' equirectangular lens centres the image on the view direction.
cam.rotation_euler = (math.pi / 2, 0.0, 0.0)
scene.camera = cam


def world_with(build):
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    background.inputs["Strength"].default_value = 1.0
    links.new(build(nodes, links), background.inputs["Color"])
    return world


def sky(nodes, links):
    tex = nodes.new("ShaderNodeTexSky")
    tex.sky_type = "PREETHAM"
    tex.turbidity = turbidity
    tex.sun_direction = sun
    return tex.outputs["Color"]


def direction(nodes, links):
    coords = nodes.new("ShaderNodeTexCoord")  # for the World, Generated is the ray direction
    half = nodes.new("ShaderNodeVectorMath")
    half.operation = "MULTIPLY_ADD"
    links.new(coords.outputs["Generated"], half.inputs[0])
    half.inputs[1].default_value = (0.5, 0.5, 0.5)
    half.inputs[2].default_value = (0.5, 0.5, 0.5)
    return half.outputs["Vector"]


def render(world, path):
    scene.world = world
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(height, width, 4)
    bpy.data.images.remove(image)
    return pixels[::-1, :, :3]  # Blender's rows run bottom to top


radiance = render(world_with(sky), out_path)
root = os.path.splitext(out_path)[0]
encoded = render(world_with(direction), root + "-direction.exr")
os.remove(root + "-direction.exr")
np.savez(root + ".npz", radiance=radiance, direction=2.0 * encoded - 1.0)
