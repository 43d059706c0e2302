"""The solve's life cycle in Blender, headless (python_tests/blender/addon_solve.py): Solve refused
outside Object Mode, the study folder replaced only by a solve that succeeds, the cost model's
refusal with the element size that fits, and the contributions kept for a re-solve when only goals
or solver settings change. The modal path, with real key events, is in test_blender_gui.py."""

import os

from test_blender_addon import HERE


def test_solve_life_cycle(blender, tmp_path):
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_solve.py"), str(tmp_path / "out"))
    print(r.stdout[-3000:])
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 5 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]
