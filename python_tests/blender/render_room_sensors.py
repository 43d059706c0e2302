"""Renders, with Cycles, the irradiance at sensor points inside a scene of grey Lambertian quads.

blender -b --factory-startup --python-exit-code 1 --python render_room_sensors.py -- SPEC.json OUT.json

SPEC.json:
  {"quads": [[[x, y, z] x 4, "material"], ...],      the geometry, holes and all, as it is
   "materials": {"name": reflectance, ...},           Lambertian albedo, grey
   "variants": [{"materials": {"name": reflectance}, "samples": n}, ...],
                                                      one render per variant: material overrides,
                                                      samples per pixel (default: as below)
   "sky": L,                                          uniform radiance, every direction
   "sensors": {"points": [...], "normals": [...]},
   "samples": 1024, "resolution": 10, "patch": 0.02, "max_bounces": 16, "seed": 1}

Each sensor is a white Lambertian square of side `patch` centred on the point and facing its
normal, visible to camera rays only (it casts no shadow and nothing sees it); an orthographic
camera 1 cm in front looks at it head-on and covers only it. A white Lambertian surface leaves
radiance E / pi, so each pixel times pi is the irradiance of the upper hemisphere of the sensor.
Writes {"value": [[per sensor] per variant], "stderr": [...], "pixels": n, "samples": [...],
"seconds": [...]},
the standard error from the spread of the pixel means (pixels are independent estimates).
"""

import json
import math
import os
import sys
import tempfile
import time

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index("--") + 1:]
spec_path, out_path = argv[0], argv[1]
with open(spec_path) as f:
    spec = json.load(f)

scene = bpy.context.scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene.render.engine = "CYCLES"
cycles = scene.cycles
cycles.device = "CPU"
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.seed = int(spec.get("seed", 1))
cycles.use_animated_seed = False
bounces = int(spec.get("max_bounces", 16))
cycles.max_bounces = cycles.diffuse_bounces = bounces
cycles.glossy_bounces = cycles.transmission_bounces = cycles.volume_bounces = 0
cycles.transparent_max_bounces = 8
cycles.sample_clamp_direct = 0.0  # no clamping: an unbiased estimate
cycles.sample_clamp_indirect = 0.0
cycles.light_sampling_threshold = 0.0
cycles.caustics_reflective = cycles.caustics_refractive = False
scene.render.use_persistent_data = True
resolution = int(spec.get("resolution", 10))
scene.render.resolution_x = scene.render.resolution_y = resolution
scene.render.resolution_percentage = 100
scene.render.filter_size = 0.01
scene.render.film_transparent = False
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"

world = bpy.data.worlds.new("sky")
world.use_nodes = True
background = world.node_tree.nodes["Background"]
sky = float(spec["sky"])
background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
background.inputs["Strength"].default_value = 1.0  # pixels are scaled by the radiance afterwards
scene.world = world


def diffuse_material(name, reflectance):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Roughness"].default_value = 0.0  # Lambertian
    bsdf.inputs["Color"].default_value = (reflectance, reflectance, reflectance, 1.0)
    material.node_tree.links.new(bsdf.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    return material, bsdf


materials, colour_inputs = {}, {}
for name, reflectance in spec["materials"].items():
    materials[name], bsdf = diffuse_material(name, float(reflectance))
    colour_inputs[name] = bsdf.inputs["Color"]

# The geometry: one mesh, one material slot per material, the quads as given (no Boolean).
names = sorted(materials)
verts, faces, face_material = [], [], []
for quad, name in spec["quads"]:
    faces.append([len(verts) + i for i in range(4)])
    verts += [tuple(p) for p in quad]
    face_material.append(names.index(name))
mesh = bpy.data.meshes.new("room")
mesh.from_pydata(verts, [], faces)
for name in names:
    mesh.materials.append(materials[name])
for polygon, index in zip(mesh.polygons, face_material):
    polygon.material_index = index
    polygon.use_smooth = False
mesh.validate()
room = bpy.data.objects.new("room", mesh)
scene.collection.objects.link(room)

# The sensors: white squares seen by the camera only, and one camera each.
white, _ = diffuse_material("sensor", 1.0)
patch = float(spec.get("patch", 0.02))
points = [Vector(p) for p in spec["sensors"]["points"]]
normals = spec["sensors"]["normals"]
if len(normals) == 3 and not isinstance(normals[0], list):
    normals = [normals] * len(points)
normals = [Vector(n).normalized() for n in normals]
cameras = []
for index, (point, normal) in enumerate(zip(points, normals)):
    h = patch / 2
    square = bpy.data.meshes.new("sensor%d" % index)
    square.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [[0, 1, 2, 3]])
    square.materials.append(white)
    obj = bpy.data.objects.new("sensor%d" % index, square)
    obj.location = point
    obj.rotation_euler = Vector((0, 0, 1)).rotation_difference(normal).to_euler()
    obj.visible_diffuse = obj.visible_glossy = obj.visible_transmission = False
    obj.visible_volume_scatter = obj.visible_shadow = False
    scene.collection.objects.link(obj)
    cam_data = bpy.data.cameras.new("cam%d" % index)
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 0.8 * patch  # every pixel on the square
    cam_data.clip_start = 0.001
    cam_data.clip_end = 0.02
    cam = bpy.data.objects.new("cam%d" % index, cam_data)
    scene.collection.objects.link(cam)
    cam.location = point + 0.01 * normal
    cam.rotation_euler = (-normal).to_track_quat("-Z", "Y").to_euler()
    cameras.append(cam)

result = {"value": [], "stderr": [], "pixels": resolution * resolution, "samples": [], "seconds": []}
tmp = tempfile.mkdtemp()
for variant in spec.get("variants", [{}]):
    for name, reflectance in spec["materials"].items():
        r = float(variant.get("materials", {}).get(name, reflectance))
        colour_inputs[name].default_value = (r, r, r, 1.0)
    cycles.samples = int(variant.get("samples", spec.get("samples", 1024)))
    start = time.monotonic()
    values, errors = [], []
    for index, cam in enumerate(cameras):
        scene.camera = cam
        scene.render.filepath = os.path.join(tmp, "s%d.exr" % index)
        bpy.ops.render.render(write_still=True)
        image = bpy.data.images.load(scene.render.filepath)
        px = list(image.pixels)
        bpy.data.images.remove(image)
        grey = [sum(px[i:i + 3]) / 3.0 for i in range(0, len(px), 4)]  # every surface is grey
        count = len(grey)
        mean = sum(grey) / count
        var = sum((g - mean) ** 2 for g in grey) / (count - 1)
        values.append(math.pi * sky * mean)
        errors.append(math.pi * sky * math.sqrt(var / count))
    result["value"].append(values)
    result["stderr"].append(errors)
    result["samples"].append(cycles.samples)
    result["seconds"].append(time.monotonic() - start)

with open(out_path, "w") as f:
    json.dump(result, f)
