"""An environment map lights Fenestra and Blender's Cycles identically (Blender's world convention)."""

import json
import os
import shutil
import subprocess

import numpy as np
import pytest

import fenestra

BLENDER = shutil.which("blender")
HERE = os.path.dirname(os.path.abspath(__file__))
NORMALS = [(1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0), (0, 0, 1)]
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def lopsided_map(width=64, height=32):
    """Upper hemisphere: a warm lobe toward azimuth 30 degrees (between +X and +Y), a blue tint
    toward -Y; lower hemisphere: dim grey. Any mirrored or rotated reading shows."""
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    theta = v[:, None] * np.pi
    phi = (0.5 - u[None, :]) * 2 * np.pi
    lobe = np.maximum(0.0, np.cos(phi - np.radians(30))) ** 3
    blue = np.maximum(0.0, np.cos(phi + np.pi / 2)) ** 2
    img = np.zeros((height, width, 3), np.float32)
    upper = theta < np.pi / 2
    img[..., 0] = np.where(upper, 200 + 2000 * lobe, 30)
    img[..., 1] = np.where(upper, 200 + 1200 * lobe + 100 * blue, 30)
    img[..., 2] = np.where(upper, 200 + 300 * lobe + 900 * blue, 30)
    return img


@pytest.mark.skipif(BLENDER is None, reason="Blender is not installed")
def test_environment_map_matches_cycles(tmp_path):
    env = tmp_path / "sky.exr"
    fenestra.write_image(str(env), lopsided_map())
    out = tmp_path / "cycles.json"
    cmd = [BLENDER, "-b", "--factory-startup", "--python-exit-code", "1",
           "--python", os.path.join(HERE, "blender", "render_irradiance.py"), "--", str(env), str(out)]
    cmd += [",".join(str(c) for c in n) for n in NORMALS]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    cycles = json.loads(out.read_text())

    (tmp_path / "far.obj").write_text("o slab\nusemtl slab\nv -0.1 -0.1 -500\nv 0.1 -0.1 -500\n"
                                      "v 0.1 0.1 -500\nv -0.1 0.1 -500\nf 1 2 3 4\n")
    scene = fenestra.scene_from_dict({
        "fenestra": 1, "geometry": "far.obj",
        "materials": {"slab": {"reflectance": 0.0}},
        "opening_domain": {"materials": ["slab"], "element_size": 0.05},
        "sensors": {"points": [[0, 0, 0]] * len(NORMALS), "normals": [list(n) for n in NORMALS]},
        "sky": {"type": "envmap", "file": "sky.exr"},
        "render": {"paths_per_sensor": 1 << 16, "seed": 5},
    }, base_dir=tmp_path)
    ours, ours_err = fenestra.evaluate(scene, [])

    theirs = np.array(cycles["mean"]) @ LUMINANCE
    theirs_err = np.sqrt((np.array(cycles["stderr"]) ** 2) @ LUMINANCE ** 2)
    assert np.ptp(ours) > 0.3 * ours.mean()  # the map really is lopsided
    sigma = np.hypot(ours_err, theirs_err)
    assert np.all(np.abs(ours - theirs) <= 4 * sigma + 1e-3 * theirs), np.c_[ours, theirs, sigma]
