"""An opening's cutter as a solid in world space: the opening's surface, a grid of points with
their outward normals, swept from `margin` toward the sensors to `depth + margin` away from them.

A flat opening is the 2 x 2 grid of its corners, all with the rectangle's normal: a box. A curved
one is the result's `surface_grid`, so the cutter follows the wall. The solid is three layers of
the grid (room-side end, the surface itself, far end); only the boundary of the middle layer is
used, where the sides are split so the room-side part can be told apart.
"""

import numpy as np


def _unit(d):
    length = np.linalg.norm(d, axis=-1, keepdims=True)
    return d / np.where(length > 0, length, 1.0)


def _cells(grid):
    """Each grid cell's 4 corners in order around it: grid[R, C, ...] -> [(R-1)(C-1), 4, ...]."""
    corners = np.stack([grid[:-1, :-1], grid[:-1, 1:], grid[1:, 1:], grid[1:, :-1]], axis=2)
    return corners.reshape((-1, 4) + grid.shape[2:])


def _quad_planes(q):
    """(centres, normals) of quads q[..., 4, 3]; the normal is the cross product of the diagonals
    (the plane's for a planar quad, the mean one for a slightly twisted quad)."""
    return q.mean(axis=-2), np.cross(q[..., 2, :] - q[..., 0, :], q[..., 3, :] - q[..., 1, :])


def _bow(points, normals):
    """How far the surface may stray from the flat faces between grid neighbours, L apart, their
    normals turning by angle: L * angle / 8 for an arc, at most L * angle / 4 for a kink between
    them. Normals interpolated across a mesh's facets turn less than its kinks when the facets are
    wider than the grid's spacing; L * angle / 2 allows for facets up to twice as wide. 0 for a
    flat grid."""
    bow = 0.0
    for axis in (0, 1):
        a, b = np.swapaxes(points, 0, axis), np.swapaxes(normals, 0, axis)
        if a.shape[0] < 2:
            continue
        length = np.linalg.norm(a[1:] - a[:-1], axis=-1)
        angle = np.arctan2(np.linalg.norm(np.cross(b[1:], b[:-1]), axis=-1), np.sum(b[1:] * b[:-1], axis=-1))
        bow = max(bow, float((length * angle).max()) / 2.0)
    return bow


class Cutter:
    """points[R, C] on the opening's surface (row index along v, column along u) and unit normals
    pointing out through the wall; the solid spans -margin to depth + margin along them, the
    margin grown by the surface's bow between grid points."""

    def __init__(self, points, normals, depth, margin):
        self.points = np.asarray(points, np.float64)
        self.normals = _unit(np.asarray(normals, np.float64))
        rows, columns = self.points.shape[:2]
        if rows < 2 or columns < 2:
            raise ValueError("a cutter needs at least 2 x 2 grid points")
        # Between grid points the faces are flat and the wall is not: reach further by its bow.
        margin = margin + _bow(self.points, self.normals)
        self.near, self.far = -margin, depth + margin
        self.faces, self.room_side_faces = _faces(rows, columns)

    @classmethod
    def flat(cls, corners, toward_sensors, depth, margin):
        """The box of a flat rectangle (corners in order around it; the rectangle is spanned by the
        edges from the first one), its normal turned away from toward_sensors."""
        c = np.asarray(corners, np.float64)
        u, v = c[1] - c[0], c[3] - c[0]
        n = _unit(np.cross(u, v))
        if np.dot(toward_sensors, n) >= 0:
            n = -n
        points = np.array([[c[0], c[0] + u], [c[0] + v, c[0] + u + v]])
        return cls(points, np.broadcast_to(n, points.shape), depth, margin)

    @classmethod
    def from_grid(cls, grid, depth, margin):
        """From a result's "surface_grid" (rows, columns, row-major points and normals)."""
        shape = (grid["rows"], grid["columns"], 3)
        return cls(np.reshape(grid["points"], shape), np.reshape(grid["normals"], shape), depth, margin)

    def _grid(self, shrink):
        """The grid points, the outer rows and columns moved `shrink` inward along the surface."""
        p = self.points
        if not shrink:
            return p
        moved = p.copy()
        moved[0] += shrink * _unit(p[1] - p[0])
        moved[-1] += shrink * _unit(p[-2] - p[-1])
        moved[:, 0] += shrink * _unit(p[:, 1] - p[:, 0])
        moved[:, -1] += shrink * _unit(p[:, -2] - p[:, -1])
        return moved

    def outline(self, shrink=0.0):
        """The opening's boundary on the surface, in order around it."""
        return self._grid(shrink).reshape(-1, 3)[_ring(*self.points.shape[:2])]

    def vertices(self, shrink=0.0):
        """The room-side end (the R x C grid), the surface's boundary ring, the far end (the grid);
        with shrink, the opening shrunk by that much on each side."""
        p, n = self._grid(shrink).reshape(-1, 3), self.normals.reshape(-1, 3)
        return np.concatenate([p + self.near * n, self.outline(shrink), p + self.far * n])

    def contains(self, points, shrink):
        """Which points lie inside the solid, the opening shrunk by shrink: inside one of the grid
        cells swept through the wall, each a hexahedron bounded by the planes of its six faces."""
        p = self._grid(shrink)
        # cells[k, 8, 3]: each cell's corners at the room-side end, then at the far end.
        cells = np.concatenate([_cells(p + self.near * self.normals), _cells(p + self.far * self.normals)], axis=1)
        centres, normals = _quad_planes(cells[:, _HEXAHEDRON_FACES])
        # Outward: away from the cell's centre.
        inward = np.einsum("kfi,kfi->kf", cells.mean(axis=1)[:, None] - centres, normals) > 0
        normals[inward] *= -1
        offsets = np.einsum("kfi,kfi->kf", centres, normals)
        points = np.asarray(points, np.float64).reshape(-1, 3)
        inside = np.zeros(len(points), bool)
        lo, hi = cells.reshape(-1, 3).min(axis=0), cells.reshape(-1, 3).max(axis=0)
        candidates = np.flatnonzero(np.all((points > lo) & (points < hi), axis=1))
        step = max(1, (1 << 22) // offsets.size)  # bounded memory: points x cells x 6 at a time
        for start in range(0, len(candidates), step):
            chosen = candidates[start:start + step]
            side = np.einsum("mi,kfi->mkf", points[chosen], normals) - offsets
            inside[chosen] = np.any(np.all(side < 0, axis=2), axis=1)
        return inside


# A cell's faces, by its 8 corners: the two ends, then the four sides.
_HEXAHEDRON_FACES = np.array([(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)])


def _ring(rows, columns):
    """Grid indices around the boundary: along the first row, up the last column, back along the
    last row, down the first column."""
    index = np.arange(rows * columns).reshape(rows, columns)
    return np.concatenate([index[0, :-1], index[:-1, -1], index[-1, :0:-1], index[:0:-1, 0]])


def _faces(rows, columns):
    """Faces of Cutter.vertices: the room-side end and the sides up to the surface first (they
    are on the room side; returns their count), then the sides beyond it and the far end."""
    cells = _cells(np.arange(rows * columns).reshape(rows, columns))
    ring = _ring(rows, columns)
    k = np.arange(len(ring))
    middle, far = rows * columns, rows * columns + len(ring)
    nxt = (k + 1) % len(ring)
    near_sides = np.stack([ring[k], ring[nxt], middle + nxt, middle + k], axis=-1)
    far_sides = np.stack([middle + k, middle + nxt, far + ring[nxt], far + ring[k]], axis=-1)
    faces = [tuple(map(int, f)) for f in np.concatenate([cells, near_sides, far_sides, far + cells])]
    return faces, len(cells) + len(ring)
