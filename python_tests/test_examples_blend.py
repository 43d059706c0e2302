"""The Blender examples (examples/build_blend_examples.py): built headless, reopened, their settings
and study folders checked."""

import json
import os
import shutil
import subprocess

import pytest

BLENDER = shutil.which("blender")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ADDON = os.path.join(ROOT, "addon", "fenestra")
BUILD = os.path.join(ROOT, "examples", "build_blend_examples.py")

CHECK = """
import sys, addon_utils, bpy, numpy as np
addon_utils.enable("fenestra", default_set=True, handle_error=None)
bpy.ops.wm.open_mainfile(filepath=sys.argv[sys.argv.index("--") + 1])
f = bpy.context.scene.fenestra
sensors = [o for o in bpy.data.objects if o.fenestra.is_sensor]
assert len(sensors) == 1 and len(sensors[0].data.vertices) == 80, sensors
domain = {}
for o in bpy.data.objects:
    if o.type == 'MESH' and "fenestra_domain" in o.data.attributes:
        flags = np.zeros(len(o.data.polygons), bool)
        o.data.attributes["fenestra_domain"].data.foreach_get("value", flags)
        domain[o.name] = int(flags.sum())
print("CHECK", dict(sky=f.sky.type, goals=f.goals.source, units=f.goals.units, level=round(f.goals.level, 3),
                    thickness=round(f.solve.wall_thickness, 3), element=round(f.solve.element_size, 3),
                    quality=f.solve.quality, domain=domain))
"""


def blender(tmp_path, *args):
    scripts = tmp_path / "scripts"
    if not scripts.exists():
        (scripts / "addons").mkdir(parents=True)
        os.symlink(ADDON, scripts / "addons" / "fenestra")
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(scripts))
    cmd = [BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)


@pytest.mark.skipif(BLENDER is None, reason="Blender is not installed")
def test_room_and_thick_walls_examples(tmp_path):
    out = tmp_path / "out"
    r = blender(tmp_path, "--python", BUILD, "--", str(out), "room", "thick_walls")
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    check = tmp_path / "check.py"
    check.write_text(CHECK)
    expected = {
        "room": dict(sky="PREETHAM", goals="UNIFORM", units="NORMALIZED", level=0.5, thickness=0.0,
                     element=0.25, quality="PREVIEW", domain={"Room": 1}),
        "thick_walls": dict(sky="CIE_OVERCAST", goals="UNIFORM", units="DAYLIGHT_FACTOR", level=3.0,
                            thickness=0.3, element=0.25, quality="PREVIEW", domain={"South wall": 1}),
    }
    for name, settings in expected.items():
        r = blender(tmp_path, "--python", str(check), "--", str(out / (name + ".blend")))
        assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
        line = next(l for l in r.stdout.splitlines() if l.startswith("CHECK "))
        assert eval(line[6:]) == settings, line
        # The study folder, as the add-on exports it for a solve.
        scene = json.load(open(out / (name + "_study") / "scene.json"))
        assert len(scene["sensors"]["points"]) == 80
        # Wall Thickness 0 leaves the thickness to be measured from the model.
        assert scene["opening_domain"].get("thickness", 0.0) == pytest.approx(settings["thickness"])
        assert ("thickness" in scene["opening_domain"]) == (settings["thickness"] > 0)
        assert len(scene["opening_domain"]["groups"]) == 1
        assert (out / (name + "_study") / "scene.obj").stat().st_size > 0
