"""The native module as the add-on sees it: available or not (and why), and what it accepts."""

import os
import sys
import tempfile

_accepts = {}

# One domain quad and one sensor: enough for the native loader to read a sky or a solver section.
_PROBE_OBJ = "g probe\nusemtl probe\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n"


def unavailable():
    """None when the native module is loaded, else a sentence saying why it is not."""
    from ...native_status import import_error
    if import_error is None:
        return None
    return ("The native module fenestra._core could not be loaded into Blender's Python %d.%d (%s). "
            "Build it for this Python with `make build`, then restart Blender."
            % (sys.version_info[0], sys.version_info[1], import_error))


def probe_scene(directory, **sections):
    """A native scene of one quad and one sensor with the given sections (sky, solver, ...)."""
    from ... import api as fenestra
    with open(os.path.join(directory, "probe.obj"), "w") as f:
        f.write(_PROBE_OBJ)
    scene = {"fenestra": 1, "geometry": "probe.obj", "materials": {"probe": {"type": "diffuse"}},
             "opening_domain": {"groups": ["probe"], "element_size": 0.5},
             "sensors": {"points": [[0.5, 1.0, 0.5]]}}
    scene.update(sections)
    return fenestra.scene_from_dict(scene, directory)


def accepts_constraints():
    """Whether this build's scene loader knows the solver's "constraints" section."""
    if "constraints" not in _accepts:
        with tempfile.TemporaryDirectory() as directory:
            try:
                probe_scene(directory, solver={"constraints": {}})
                _accepts["constraints"] = True
            except ValueError:
                _accepts["constraints"] = False
    return _accepts["constraints"]
