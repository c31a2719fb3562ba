"""Polar envelopes: the boundary of a gear carved by many poses of a cutter, ray by ray.

A gear outline is stored as its radius ``R[j]`` (mm) along rays at body angles
``start + (j + 0.5) * width`` (rad) over one symmetry period. Carving keeps, on every
ray, the nearest cutter crossing (the gear material runs from the centre to the
first cutter boundary); a blank keeps the farthest crossing of its offset curve.
Cutter boundaries are polylines; each segment is intersected with the rays it spans
by linear interpolation in polar coordinates (segments are short, so this is exact
to well under a micrometre). Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Segments spanning more than this angle (rad) are dropped (they pass near the origin).
MAX_SEGMENT_ANGLE = 0.25


@dataclass(frozen=True)
class PolarGrid:
    """Rays of one symmetry period: ``count`` rays from ``start`` over ``period`` rad."""

    start: float
    period: float
    count: int

    @property
    def width(self) -> float:
        return self.period / self.count

    @property
    def angles(self) -> np.ndarray:
        return self.start + (np.arange(self.count) + 0.5) * self.width


#: Nearest envelopes of many polylines fold every this many-th polyline first; the rest is
#: then skipped segment by segment where it cannot come nearer (see :func:`polyline_envelope`).
FIRST_STRIDE = 8

#: Margin (mm) below a segment's nearer end that its crossings may reach by rounding.
_ROUNDING = 1e-9


def polyline_envelope(grid: PolarGrid, points: np.ndarray, nearest: bool = True,
                      out: np.ndarray | None = None, reach: float = np.inf) -> np.ndarray:
    """Fold polylines into the grid: per ray the nearest (or farthest) crossing radius.

    ``points`` has shape (..., K, 2): any number of polylines of K points each
    (x, y in mm, in the gear's body frame). Rays no polyline crosses keep
    +inf (nearest) or -inf (farthest), or the value already in ``out``. Segments
    lying wholly beyond ``reach`` mm from the centre are skipped (they cannot cut).
    """
    pts = np.asarray(points, dtype=float).reshape(-1, points.shape[-2], 2)
    if out is None:
        out = np.full(grid.count, np.inf if nearest else -np.inf)
    if not nearest or len(pts) < 2 * FIRST_STRIDE:
        _fold(grid, pts, nearest, out, reach)
        return out
    # a nearest crossing is a minimum, so the order of folding cannot change it: a spread-out
    # sample first, then every segment wholly beyond what the rays it spans already hold is
    # skipped (most of a carving cutter lies beyond the envelope it carves)
    first = np.zeros(len(pts), dtype=bool)
    first[::FIRST_STRIDE] = True
    _fold(grid, pts[first], nearest, out, reach, cull=bool(np.isfinite(out).any()))
    _fold(grid, pts[~first], nearest, out, reach, cull=True)
    return out


def _fold(grid: PolarGrid, pts: np.ndarray, nearest: bool, out: np.ndarray, reach: float,
          cull: bool = False) -> None:
    """Fold the polylines (P, K, 2) mm into ``out`` (see :func:`polyline_envelope`); ``cull``
    (nearest only): skip the segments that cannot lower any ray of ``out`` they span."""
    x0, y0 = pts[:, :-1, 0].ravel(), pts[:, :-1, 1].ravel()
    x1, y1 = pts[:, 1:, 0].ravel(), pts[:, 1:, 1].ravel()
    r0, r1 = np.hypot(x0, y0), np.hypot(x1, y1)
    keep = np.minimum(r0, r1) < reach
    if not keep.all():
        x0, y0, x1, y1, r0, r1 = x0[keep], y0[keep], x1[keep], y1[keep], r0[keep], r1[keep]
    b0 = np.arctan2(y0, x0)
    b1 = b0 + np.arctan2(x0 * y1 - y0 * x1, x0 * x1 + y0 * y1)   # no unwrap needed
    keep = np.abs(b1 - b0) < MAX_SEGMENT_ANGLE
    b0, b1, r0, r1 = b0[keep], b1[keep], r0[keep], r1[keep]
    # ray index as a continuous coordinate: ray j sits at j
    i0 = (b0 - grid.start) / grid.width - 0.5
    i1 = (b1 - grid.start) / grid.width - 0.5
    lo = np.ceil(np.minimum(i0, i1)).astype(np.int64)
    hi = np.floor(np.maximum(i0, i1)).astype(np.int64)
    counts = np.maximum(hi - lo + 1, 0)
    hit = counts > 0
    if cull:
        # NaN never compares greater: such a segment is kept
        hit &= ~(np.minimum(r0, r1) - _ROUNDING > _range_max(out, lo, counts))
    lo, counts, i0, i1, r0, r1 = lo[hit], counts[hit], i0[hit], i1[hit], r0[hit], r1[hit]
    # most segments cross at most one ray: handle those without repeat()
    single = counts == 1
    rays = [lo[single]]
    span = i1 - i0
    span = np.where(span != 0, span, 1.0)
    radii = [r0[single] + (lo[single] - i0[single]) / span[single] * (r1[single] - r0[single])]
    multi = ~single
    if multi.any():
        lo_m, c_m = lo[multi], counts[multi]
        total = int(c_m.sum())
        seg = np.repeat(np.flatnonzero(multi), c_m)
        first = np.repeat(np.cumsum(c_m) - c_m, c_m)
        ray = np.repeat(lo_m, c_m) + (np.arange(total) - first)
        rays.append(ray)
        radii.append(r0[seg] + (ray - i0[seg]) / span[seg] * (r1[seg] - r0[seg]))
    ray = np.mod(np.concatenate(rays), grid.count)
    radius = np.concatenate(radii)
    if nearest:
        np.minimum.at(out, ray, radius)
    else:
        np.maximum.at(out, ray, radius)


def _range_max(values: np.ndarray, lo: np.ndarray, counts: np.ndarray, block: int = 32) -> np.ndarray:
    """Per range, a bound at or above the largest of the periodic ``values`` at indices
    lo .. lo + counts - 1: the largest over the ``block``-long blocks its ends lie in
    (+inf for a range longer than a block, -inf for an empty one)."""
    n = len(values)
    blocks = -(-n // block)
    padded = np.concatenate([values, np.full(blocks * block - n, -np.inf)])
    top = padded.reshape(blocks, block).max(axis=1)
    start = np.mod(lo, n)
    last = np.mod(lo + np.maximum(counts, 1) - 1, n)
    bound = np.maximum(top[start // block], top[last // block])
    return np.where(counts > block, np.inf, np.where(counts > 0, bound, -np.inf))


def miter_offset(points: np.ndarray, distance: float) -> np.ndarray:
    """Offset a closed polyline (K, 2) by ``distance`` mm to its right-hand side, one point per vertex.

    Each vertex moves along the bisector of its two segment normals by the miter
    length (capped at 1.25 x distance), so offset points stay at least ``distance``
    from both neighbouring edges; sharp convex corners are cut by at most 0.25 x distance.
    """
    pts = np.asarray(points, dtype=float)
    seg = np.roll(pts, -1, axis=0) - pts
    seg /= np.maximum(np.hypot(seg[:, 0], seg[:, 1]), 1e-300)[:, None]
    normal = np.column_stack([seg[:, 1], -seg[:, 0]])
    before = np.roll(normal, 1, axis=0)
    mid = before + normal
    length = np.maximum(np.hypot(mid[:, 0], mid[:, 1]), 1e-300)
    mid /= length[:, None]
    cos_half = np.clip(np.sum(mid * normal, axis=1), 0.8, 1.0)
    return pts + (distance / cos_half)[:, None] * mid


def offset_polyline(points: np.ndarray, distance: float, closed: bool = False,
                    fan: bool = True) -> np.ndarray:
    """Offset a polyline (K, 2) by ``distance`` mm to its right-hand side (outward for CW).

    Every vertex is offset along both adjacent segment normals and their bisector,
    so convex corners get a three-point fan and every offset point stays within
    ``distance`` of the original curve (never beyond the true offset region).
    Without ``fan`` a convex corner is bridged by a straight chord (tip relief there).
    """
    pts = np.asarray(points, dtype=float)
    ext = np.vstack([pts[-2:-1], pts, pts[1:2]]) if closed else \
        np.vstack([2 * pts[:1] - pts[1:2], pts, 2 * pts[-1:] - pts[-2:-1]])
    seg = np.diff(ext, axis=0)
    seg /= np.maximum(np.hypot(seg[:, 0], seg[:, 1]), 1e-300)[:, None]
    normal = np.column_stack([seg[:, 1], -seg[:, 0]])
    before, after = normal[:-1], normal[1:]
    mid = before + after
    mid /= np.maximum(np.hypot(mid[:, 0], mid[:, 1]), 1e-300)[:, None]
    normals = np.stack([before, mid, after] if fan else [before, after], axis=1)   # (K, 2|3, 2)
    return (pts[:, None, :] + distance * normals).reshape(-1, 2)


def outline_from_radii(grid: PolarGrid, radius: np.ndarray, copies: int) -> np.ndarray:
    """Closed counter-clockwise outline (N, 2) in mm: the period's rays repeated ``copies`` times."""
    angles = (grid.angles[None, :] + grid.period * np.arange(copies)[:, None]).ravel()
    r = np.tile(radius, copies)
    return np.column_stack([r * np.cos(angles), r * np.sin(angles)])
