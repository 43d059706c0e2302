"""Overlays drawn a little toward the viewer, so that they do not z-fight with the surface they
lie on. The Python gpu module of Blender 3.4 has no polygon offset; moving the points along the
view rays instead keeps them on the same pixels and only brings their depth forward."""

import numpy as np

FRACTION = 0.002  # of the distance to the eye: a few depth-buffer steps at any distance


def toward_viewer(points, region_data, fraction=FRACTION):
    """World points (n, 3) moved toward the 3D View's eye (perspective) or along its view
    direction (orthographic)."""
    view = np.array(region_data.view_matrix.inverted(), np.float64)
    if region_data.is_perspective:
        eye = view[:3, 3]
        return eye + (points - eye) * (1.0 - fraction)
    return points + view[:3, 2] * (fraction * region_data.view_distance)  # view +Z faces the viewer
