"""The `fenestra` command of the installed wheel: the C++ program shipped inside this package.

The program replaces this process (os.execv), so its arguments, output, exit status and signals
(Ctrl-C, SIGTERM: docs/outputs.md) are the program's own. Runs on a Dask cluster are handed back
to this Python (FENESTRA_PYTHON) and this package (FENESTRA_ADDON_DIR), as native/cli does.
"""

import os
import sys

PROGRAM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fenestra")


def main():
    if not os.access(PROGRAM, os.X_OK):
        sys.exit("fenestra: error: the program %s is missing: this fenestra package was installed "
                 "without it (install the wheel, or use build/fenestra of a source build)" % PROGRAM)
    os.environ.setdefault("FENESTRA_PYTHON", sys.executable)
    os.environ.setdefault("FENESTRA_ADDON_DIR", os.path.dirname(os.path.dirname(PROGRAM)))
    os.execv(PROGRAM, ["fenestra"] + sys.argv[1:])


if __name__ == "__main__":
    main()
