"""Sensor grids over the rooms' floors, from a model's triangles (no bpy here): the Python face of
the native core's sensor_grid (native/src/study/sensor_grid.h; docs/scene-format.md, "Sensor
grids"). Blender's Add Sensor Grid and headless scripts make their grids with it."""

import numpy as np

from . import _core
from . import arguments as _arg


def sensor_grid(vertices, triangles, floors=None, height=0.8, spacing=0.5, inset=None):
    """Sensor grids over the upper faces of the rooms' floors.

    vertices: (n, 3) meters, in any coordinates (site coordinates are read in a local frame).
    triangles: (m, 3) vertex indices: every face that can bound a room (walls, floors, ceilings,
        furniture), so that the grid keeps off them.
    floors: (m,) bools marking the faces that may hold sensors (the chosen floor or room objects);
        None: every face.
    height: meters above the floor's upper face. spacing: meters between neighbouring sensors.
    inset: meters kept off the walls; None: half the spacing, at least 0.25 m.

    Returns a dict: "rooms", a list with one dict per room (by floor height, then x, then y):
    "points" (k, 3) meters, "floor_z" (k,) the floor's height under each point, "quads" (q, 4)
    neighbouring points' indices; "inset" (meters, as used) and "enclosed" (the floors are under
    ceilings; False when only open floors, such as a floor plane alone, were found)."""
    vertices = _arg.array(vertices, "vertices", "of shape (n, 3)", ndim=2)
    try:
        triangles = np.asarray(triangles)
    except (TypeError, ValueError):
        raise TypeError("triangles must be an array of vertex indices of shape (m, 3), got %s"
                        % _arg.shown(triangles)) from None
    if triangles.ndim != 2 or (triangles.size and not np.issubdtype(triangles.dtype, np.integer)):
        raise TypeError("triangles must be an array of vertex indices of shape (m, 3), got %s"
                        % _arg.shown(triangles))
    if floors is None:
        floors = np.ones(len(triangles), dtype=bool)
    else:
        floors = np.asarray(floors)
        if floors.dtype != np.bool_:
            raise TypeError("floors must be an array of True/False, one per triangle, got %s" % _arg.shown(floors))
    height = _arg.number(height, "height")
    spacing = _arg.number(spacing, "spacing")
    inset = _arg.optional_number(inset, "inset")
    return _core.sensor_grid(vertices, triangles.astype(np.int64, copy=False), floors, height, spacing, inset)
