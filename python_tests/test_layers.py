"""The native core's house rule: each layer includes only layers below it (docs/architecture.md)."""

import os
import subprocess
import sys

from conftest import ROOT


def test_no_include_runs_up_a_floor():
    r = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "check_layers.py")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
