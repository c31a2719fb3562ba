"""A chamfer's staircase of nested prisms as one triangle mesh, built from its layers' rings.

Pure numpy but for the polygon triangulation, passed in (geometry.solids gives manifold3d's).
Lengths in mm.
"""

from __future__ import annotations

from typing import Callable

import numpy as np


def staircase_mesh(rings: list[list[np.ndarray]], steps: list[float], thickness: float,
                   triangulate: Callable) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (N, 3) mm and triangles (M, 3) of the union of nested prisms: layer k (its
    rings, outer CCW and holes CW, ``rings[k]``; the most inset first, the full section last)
    extruded from ``steps[k]`` to ``thickness - steps[k]``. Layer k is the body's section
    from steps[k] to steps[k+1] and, mirrored, below the top, so the surface is the bottom
    and top caps of layer 0, each layer's walls over its heights, and at each step the ring
    between two layers, all on the layers' own vertices (no boolean: the union of large
    outlines costs seconds). ``triangulate``: rings (CCW material) -> triangles indexing
    their concatenated points."""
    points, triangles, count = [], [], 0

    def level(k: int, z: float) -> list[np.ndarray]:
        nonlocal count
        ids = []
        for ring in rings[k]:
            points.append(np.column_stack([ring, np.full(len(ring), z)]))
            ids.append(count + np.arange(len(ring)))
            count += len(ring)
        return ids

    def cap(ring_list: list[np.ndarray], ids: list[np.ndarray], up: bool) -> None:
        tri = np.concatenate(ids)[np.asarray(triangulate(ring_list), dtype=np.int64)]
        triangles.append(tri if up else tri[:, ::-1])

    top = len(rings) - 1
    spans = [(k, steps[k], steps[k + 1]) for k in range(top)] + \
        [(top, steps[top], thickness - steps[top])] + \
        [(k, thickness - steps[k + 1], thickness - steps[k]) for k in reversed(range(top))]
    placed = [(k, level(k, z0), level(k, z1)) for k, z0, z1 in spans]
    cap(rings[0], placed[0][1], up=False)
    cap(rings[0], placed[-1][2], up=True)
    for _, low, high in placed:
        for a, b in zip(low, high):
            # rings run CCW round material: the outward faces of a wall
            a1, b1 = np.roll(a, -1), np.roll(b, -1)
            triangles += [np.column_stack([a, a1, b1]), np.column_stack([a, b1, b])]
    for (k, _, high), (k1, low1, _) in zip(placed, placed[1:]):
        if k1 > k:      # stepping out: the ring between layer k1 and layer k faces down
            cap(rings[k1] + [r[::-1] for r in rings[k]], low1 + [i[::-1] for i in high], up=False)
        else:           # stepping in: the ring between layer k and layer k1 faces up
            cap(rings[k] + [r[::-1] for r in rings[k1]], high + [i[::-1] for i in low1], up=True)
    return np.concatenate(points), np.concatenate(triangles)
