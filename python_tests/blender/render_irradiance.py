"""Renders, with Cycles, the irradiance an environment map gives white Lambertian squares.

blender -b --factory-startup --python-exit-code 1 --python render_irradiance.py -- MAP.exr OUT.json NX,NY,NZ ...

For each normal, a 1 m white diffuse square at the origin faces it; an orthographic camera looks at
it head-on. A white Lambertian surface leaves radiance E / pi, so each pixel times pi is the
irradiance (per RGB channel). Writes {"normals": [...], "mean": [[r,g,b]...], "stderr": [[...]]}.
"""

import json
import math
import os
import sys
import tempfile

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index("--") + 1:]
env_path, out_path = argv[0], argv[1]
normals = [tuple(float(c) for c in n.split(",")) for n in argv[2:]]

scene = bpy.context.scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 1024
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 1
scene.render.resolution_x = scene.render.resolution_y = 6
scene.render.resolution_percentage = 100
scene.render.filter_size = 0.01
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"

world = bpy.data.worlds.new("env")
world.use_nodes = True
nodes = world.node_tree.nodes
tex = nodes.new("ShaderNodeTexEnvironment")
tex.image = bpy.data.images.load(env_path)
tex.interpolation = "Closest"
world.node_tree.links.new(tex.outputs["Color"], nodes["Background"].inputs["Color"])
scene.world = world

material = bpy.data.materials.new("white")
material.use_nodes = True
mnodes = material.node_tree.nodes
mnodes.remove(mnodes["Principled BSDF"])
diffuse = mnodes.new("ShaderNodeBsdfDiffuse")
diffuse.inputs["Color"].default_value = (1, 1, 1, 1)
material.node_tree.links.new(diffuse.outputs["BSDF"], mnodes["Material Output"].inputs["Surface"])

result = {"normals": normals, "mean": [], "stderr": []}
tmp = tempfile.mkdtemp()
for index, n in enumerate(normals):
    normal = Vector(n).normalized()
    bpy.ops.mesh.primitive_plane_add(size=1.0)
    plane = bpy.context.active_object
    plane.rotation_euler = Vector((0, 0, 1)).rotation_difference(normal).to_euler()
    plane.data.materials.append(material)
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 0.5
    cam = bpy.data.objects.new("cam", cam_data)
    scene.collection.objects.link(cam)
    cam.location = normal * 0.5
    cam.rotation_euler = (-normal).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    scene.render.filepath = os.path.join(tmp, "n%d.exr" % index)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(scene.render.filepath)
    px = list(image.pixels)
    rgb = [px[i:i + 3] for i in range(0, len(px), 4)]
    count = len(rgb)
    mean = [sum(p[c] for p in rgb) / count for c in range(3)]
    var = [sum((p[c] - mean[c]) ** 2 for p in rgb) / (count - 1) for c in range(3)]
    result["mean"].append([math.pi * m for m in mean])
    result["stderr"].append([math.pi * math.sqrt(v / count) for v in var])
    bpy.data.objects.remove(plane)
    bpy.data.objects.remove(cam)

with open(out_path, "w") as f:
    json.dump(result, f)
