"""Where the posed outlines overlap: points inside, overlapping area, penetration depth.

Lengths in mm, areas in mm^2.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.meshing.outlines import MeshWindow, RadialBand, Window, band_at, expand
from wheelstep_cli.geometry.planar import clipped_overlap_areas, points_inside


def contains(polygon, body: np.ndarray, band: RadialBand | None, seen=None) -> np.ndarray:
    """Points (own frame of the prepared polygon, mm) inside it.

    A point farther from the axis than every edge seen at its angle is outside (the ray
    out from the axis through it meets no edge beyond it), so only the others are tested.
    ``seen``: :func:`band_at` of the points, when already known.
    """
    maybe = np.ones(len(body), dtype=bool)
    if band is not None:
        r, _, rmax = band_at(body, band) if seen is None else seen
        maybe = r <= rmax + 1e-9
    inside = np.zeros(len(body), dtype=bool)
    inside[maybe] = points_inside(polygon, body[maybe])
    return inside


def overlap_area(p_world: np.ndarray, w_world: np.ndarray, box: MeshWindow) -> np.ndarray:
    """Areas (mm^2) where the posed outlines (poses, N, 2) overlap inside the mesh window."""
    half = box.half_height
    return clipped_overlap_areas(p_world, w_world, (box.x_lo, -half, box.x_hi, half))


def depth(points: np.ndarray, pose: np.ndarray, edges: Window, max_pairs: int) -> np.ndarray:
    """Distance (mm) of each point to the nearest window edge of the same pose.

    Point/edge pairs are measured in chunks of about ``max_pairs``.
    """
    best = np.full(len(points), np.inf)
    if len(points) == 0:
        return np.zeros(0)
    # edges come grouped by pose: each point meets its pose's run
    first = np.searchsorted(edges.e_pose, pose, side="left")
    counts = np.searchsorted(edges.e_pose, pose, side="right") - first
    ends = np.cumsum(counts)
    i0 = 0
    while i0 < len(points):
        done = ends[i0 - 1] if i0 else 0
        i1 = max(int(np.searchsorted(ends, done + max_pairs, side="right")), i0 + 1)
        rows, cols = expand(first[i0:i1], counts[i0:i1], np.arange(len(edges.e_pose)))
        rows += i0
        a, b, q = edges.e0[cols], edges.e1[cols], points[rows]
        d = b - a
        t = np.clip(np.einsum("ij,ij->i", q - a, d)
                    / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
        dist = np.hypot(*(a + t[:, None] * d - q).T)
        np.minimum.at(best, rows, dist)
        i0 = i1
    return best
