"""Every Blender API name the add-on uses exists in each tested Blender (python_tests/blender/
api_names.py reads the add-on's source and checks operators, types, module attributes, attributes of
Blender data and enum values in the running Blender; blenders.py gives the Blenders)."""

import os
import re

from test_blender_addon import HERE

SCRIPT = os.path.join(HERE, "blender", "api_names.py")

# Uses that some Blender lacks, each with the versions that lack it: the check must name them.
BROKEN = '''import bpy


def broken(context):
    group = bpy.data.node_groups.new("g", 'GeometryNodeTree')
    group.inputs.new('NodeSocketGeometry', "Geometry")  # removed in 4.0
    mesh = bpy.data.meshes.new("m")
    mesh.use_auto_smooth = True  # removed in 4.1
    m = bpy.data.objects.new("o", mesh).modifiers.new("b", 'BOOLEAN')
    m.solver = 'MANIFOLD'  # new in 4.5
    context.scene.render.engine = 'BLENDER_EEVEE_NEXT'  # 4.2 to 4.5 only
    bpy.ops.object.no_such_operator()
    return bpy.types.NoSuchType, 'GeometryNodeNoSuchNode'
'''
LACKED = {
    "blender-3.4": ["solver = 'MANIFOLD'", "engine = 'BLENDER_EEVEE_NEXT'"],
    "bpy-4.5": ["GeometryNodeTree.inputs", "Mesh.use_auto_smooth"],
}
ALWAYS = ["bpy.ops.object.no_such_operator", "bpy.types.NoSuchType", "type 'GeometryNodeNoSuchNode'"]


def missing(output):
    return [line for line in output.splitlines() if line.startswith("MISSING ")]


def test_every_api_name_the_addon_uses_exists(blender, tmp_path):
    r = blender.run(tmp_path, SCRIPT)
    assert r.returncode == 0 and not missing(r.stdout), "\n".join(missing(r.stdout)) + r.stderr[-3000:]
    checked = int(re.search(r"^CHECKED (\d+)$", r.stdout, re.M).group(1))
    assert checked > 500, checked  # the walk found the add-on's uses


def test_names_a_blender_lacks_are_reported(blender, tmp_path):
    broken = tmp_path / "broken.py"
    broken.write_text(BROKEN)
    r = blender.run(tmp_path, SCRIPT, str(broken))
    assert r.returncode == 1, r.stdout[-3000:] + r.stderr[-3000:]
    reported = "\n".join(line for line in missing(r.stdout) if "broken.py" in line)
    lacked = LACKED[blender.name] + ALWAYS
    for what in lacked:
        assert what in reported, (what, reported)
    assert len(reported.splitlines()) == len(lacked), reported
