"""Climate goals in Blender: headless (python_tests/blender/addon_climate.py: the Climate Goals list
exported as goals.climate / least_glazing / sensors.groups from a vertex group, the fields' ranges,
bad setups refused naming the goal and the group, a solve on climate goals alone whose figures and
Daylight Autonomy false colour are result.json's) and in a window under Xvfb
(python_tests/blender/screenshot_climate.py: goals added with the + button and a solve started with
the Solve button, by real clicks; the Results panel lists the goals, the sensors are drawn in their
DA colours; the screenshot is docs/blender-climate-goals.png)."""

import os
import shutil
import subprocess

import pytest

from test_blender_addon import BLENDER, HERE, run_in_blender

XVFB_RUN = shutil.which("xvfb-run")
XDOTOOL = shutil.which("xdotool")


@pytest.mark.skipif(BLENDER is None, reason="Blender is not installed")
def test_climate_goals_exported_refused_and_solved(tmp_path):
    r = run_in_blender(tmp_path, os.path.join(HERE, "blender", "addon_climate.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 10 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]
