"""Gear bodies from sampled curves: orientation, polar sweep, blank radii, written outlines.

Angles in radians, lengths in mm.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.generation.envelope import PolarGrid, offset_polyline, polyline_envelope
from wheelstep_cli.geometry.planar import simplify_ring


def outward_sign(points: np.ndarray) -> float:
    """+1 when the right-hand normal of the polyline (K, 2) points away from the origin, else -1."""
    seg = np.diff(points, axis=0)
    right = np.column_stack([seg[:, 1], -seg[:, 0]])
    return 1.0 if np.sum(right * points[:-1]) > 0 else -1.0


def polar_sweep(curve: np.ndarray) -> float:
    """Signed body angle (rad) a curve (K, 2) sweeps from its first to its last point."""
    return float(np.sum(np.diff(np.unwrap(np.arctan2(curve[:, 1], curve[:, 0])))))


def blank_radii(curve: np.ndarray, grid: PolarGrid, height: float, fan: bool = True) -> np.ndarray:
    """Farthest crossing per ray (mm) of the pitch curve offset outward by ``height`` mm.

    ``curve`` spans one period (grid.period rad of body angle); it is closed over the
    whole turn first so the corners between periods get their offset fans.
    """
    copies = int(round(2.0 * np.pi / grid.period))
    angles = grid.period * np.arange(copies) * np.sign(polar_sweep(curve))
    c, s = np.cos(angles), np.sin(angles)
    body = curve[:-1]
    full = np.concatenate([np.column_stack([ci * body[:, 0] - si * body[:, 1],
                                            si * body[:, 0] + ci * body[:, 1]]) for ci, si in zip(c, s)])
    if outward_sign(full) < 0:
        full = full[::-1]
    offset = offset_polyline(full, height, closed=True, fan=fan)
    offset = np.vstack([offset, offset[:1]])                 # close the loop
    return polyline_envelope(grid, offset[None], nearest=False)


def simplify_outline(outline: np.ndarray, tolerance: float = 0.001) -> np.ndarray:
    """Drop outline points within ``tolerance`` mm of the polyline (Douglas-Peucker) and spikes.

    ``outline``: closed (N, 2) array in mm. A spike is a vertex where the outline doubles
    back on itself (a zero-width sliver a boolean can leave); a few vectorised passes
    remove nested ones.
    """
    pts = simplify_ring(outline, tolerance)
    for _ in range(8):
        d_in = pts - np.roll(pts, 1, axis=0)
        d_out = np.roll(pts, -1, axis=0) - pts
        norm = np.hypot(d_in[:, 0], d_in[:, 1]) * np.hypot(d_out[:, 0], d_out[:, 1])
        cos = np.sum(d_in * d_out, axis=1) / np.maximum(norm, 1e-300)
        spike = (cos < -0.95) | (norm < 1e-18)
        if not spike.any():
            break
        spike &= ~np.roll(spike, 1)          # never drop two neighbours in one pass
        pts = pts[~spike]
    return pts
