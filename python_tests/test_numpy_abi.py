"""The native module reads NumPy 1.x arrays only (pybind11 2.10): under NumPy 2 every array would be
misread without an error, so importing fenestra there is refused, naming the NumPy found and the fix."""

import os
import subprocess
import sys

from conftest import ROOT, write_small_room


def import_with_numpy_version(tmp_path, version):
    """Imports fenestra in a fresh Python whose `numpy` reports `version`."""
    stub = tmp_path / "numpy"
    stub.mkdir()
    (stub / "__init__.py").write_text("__version__ = %r\n" % version)
    code = ("import sys\nsys.path[:0] = [%r, %r]\nimport fenestra\n"
            % (str(tmp_path), os.path.join(ROOT, "addon")))
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)


def test_numpy_2_refused_at_import(tmp_path):
    run = import_with_numpy_version(tmp_path, "2.1.0")
    assert run.returncode != 0
    last = run.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: Fenestra's native module reads NumPy 1.x arrays only"), run.stderr
    assert "NumPy 2.1.0" in last and str(tmp_path / "numpy") in last and 'numpy>=1.23,<2' in last, last


def test_the_real_numpy_is_accepted(tmp_path):
    """The Python running the tests has NumPy 1.x, and arrays cross the module intact: each sensor
    its own value (the misread arrays of NumPy 2 repeat the first)."""
    import numpy as np
    import fenestra
    assert int(np.__version__.split(".")[0]) < 2
    scene = fenestra.load_scene(str(write_small_room(tmp_path / "room", paths=256)))
    values, stderr = fenestra.evaluate(scene, [{"corners": [[0.5, 0, 0.5], [2.5, 0, 0.5], [2.5, 0, 2.0],
                                                            [0.5, 0, 2.0]]}])
    assert values.shape == stderr.shape == (3,)
    assert np.all(values > 0) and len(set(values.tolist())) == 3, values
