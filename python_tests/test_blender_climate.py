"""Climate goals in Blender: headless (python_tests/blender/addon_climate.py: the Climate Goals list
exported as goals.climate / least_glazing / sensors.groups from a vertex group, the fields' ranges,
bad setups refused naming the goal and the group, a solve on climate goals alone whose figures and
Daylight Autonomy false colour are result.json's; a floor of three rooms with goals per room) and in
a window under Xvfb (python_tests/blender/screenshot_climate.py: on a floor of two rooms, goals added
and a solve started by real key presses mapped to Add Climate Goal and Solve Openings; the Results
panel lists the goals and the rooms, the sensors are drawn in their DA colours; the screenshot is
docs/blender-climate-goals.png)."""

import os
import shutil
import subprocess

import pytest

from test_blender_addon import BLENDER, HERE

XVFB_RUN = shutil.which("xvfb-run")
XDOTOOL = shutil.which("xdotool")


def test_climate_goals_exported_refused_and_solved(blender, tmp_path):
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_climate.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 11 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


@pytest.mark.skipif(None in (BLENDER, XVFB_RUN, XDOTOOL), reason="needs Blender, xvfb-run and xdotool")
def test_climate_goals_in_a_window(tmp_path):
    config, scripts = tmp_path / "config", tmp_path / "scripts"
    (scripts / "addons").mkdir(parents=True)
    os.symlink(os.path.join(os.path.dirname(HERE), "addon", "fenestra"), scripts / "addons" / "fenestra")
    env = dict(os.environ, BLENDER_USER_CONFIG=str(config), BLENDER_USER_SCRIPTS=str(scripts))
    # Preferences without the splash screen, which would cover the 3D View (and take the keys).
    subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr",
                    "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"],
                   env=env, check=True, capture_output=True, timeout=120)
    shot = tmp_path / "shots" / "climate.png"
    cmd = [XVFB_RUN, "-a", "-s", "-screen 0 1400x2100x24", BLENDER, "--window-geometry", "0", "0", "1400", "2100",
           "--python", os.path.join(HERE, "blender", "screenshot_climate.py"), "--", str(shot)]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env)
    checks = [line for line in r.stdout.splitlines() if line.startswith("CHECK")]
    assert r.returncode == 0 and "RESULT all checks ok" in r.stdout, "\n".join(checks) + r.stdout[-3000:] + r.stderr[-3000:]
    assert len(checks) == 6, checks
    assert shot.stat().st_size > 0
