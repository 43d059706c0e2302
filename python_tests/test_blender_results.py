"""A result made visible, in Blender: headless (python_tests/blender/addon_results.py: false colour
values and scales, each sensor by object and vertex, the goal plot, Preview Sky's exposure and live
strength, the domain highlight cut by the result, Clear Results and Clear Domain), and in a real
window under Xvfb (python_tests/blender/screenshot_results.py: screenshots of the 3D View show a
sky that is neither white nor black, brighter when the strength is raised, the legend's colour
bar and title, and Inspect Sensors labelling the sensor under the pointer; and
python_tests/blender/screenshot_annual.py: Annual Daylight run from its button on a climate sky, the
sensors drawn in the colours of their daylight autonomy and the legend's bar and title)."""

import os
import shutil
import subprocess

import pytest

from test_blender_addon import BLENDER, HERE

XVFB_RUN = shutil.which("xvfb-run")


def test_results_made_visible_and_cleared(blender, tmp_path):
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_results.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 9 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


@pytest.mark.skipif(BLENDER is None or XVFB_RUN is None, reason="needs Blender and xvfb-run")
def test_viewport_screenshots_show_the_sky_and_the_legend(tmp_path):
    config, scripts = tmp_path / "config", tmp_path / "scripts"
    (scripts / "addons").mkdir(parents=True)
    os.symlink(os.path.join(os.path.dirname(HERE), "addon", "fenestra"), scripts / "addons" / "fenestra")
    env = dict(os.environ, BLENDER_USER_CONFIG=str(config), BLENDER_USER_SCRIPTS=str(scripts))
    # Preferences without the splash screen, which would cover the 3D View.
    subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr",
                    "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"],
                   env=env, check=True, capture_output=True, timeout=120)
    out = tmp_path / "shots"
    cmd = [XVFB_RUN, "-a", "-s", "-screen 0 1400x1000x24", BLENDER, "--enable-event-simulate", "--window-geometry", "0", "0", "1400", "1000",
           "--python", os.path.join(HERE, "blender", "screenshot_results.py"), "--", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env)
    checks = [line for line in r.stdout.splitlines() if line.startswith("CHECK")]
    assert r.returncode == 0 and "RESULT all checks ok" in r.stdout, "\n".join(checks) + r.stdout[-3000:] + r.stderr[-3000:]
    assert len(checks) == 10, checks
    for name in ("sky.png", "sky_brighter.png", "results.png", "hover.png"):
        assert (out / name).stat().st_size > 0


@pytest.mark.skipif(BLENDER is None or XVFB_RUN is None, reason="needs Blender and xvfb-run")
def test_annual_daylight_in_a_window(tmp_path):
    config, scripts = tmp_path / "config", tmp_path / "scripts"
    (scripts / "addons").mkdir(parents=True)
    os.symlink(os.path.join(os.path.dirname(HERE), "addon", "fenestra"), scripts / "addons" / "fenestra")
    env = dict(os.environ, BLENDER_USER_CONFIG=str(config), BLENDER_USER_SCRIPTS=str(scripts))
    subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr",
                    "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"],
                   env=env, check=True, capture_output=True, timeout=120)
    shot = tmp_path / "shots" / "annual.png"
    cmd = [XVFB_RUN, "-a", "-s", "-screen 0 1400x2100x24", BLENDER, "--window-geometry", "0", "0", "1400", "2100",
           "--python", os.path.join(HERE, "blender", "screenshot_annual.py"), "--", str(shot)]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env)
    checks = [line for line in r.stdout.splitlines() if line.startswith("CHECK")]
    assert r.returncode == 0 and "RESULT all checks ok" in r.stdout, "\n".join(checks) + r.stdout[-3000:] + r.stderr[-3000:]
    assert len(checks) == 5, checks
    assert shot.stat().st_size > 0
