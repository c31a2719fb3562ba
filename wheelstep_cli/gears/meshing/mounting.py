"""How much closer than designed a pair may be mounted: the least separation of its outlines.

At every pose of the law the wheel, moved a distance d toward the pinion along any
direction, can only overlap it if some point of its outline lies within d of the
pinion's. The least separation over the poses is therefore a mounted-distance tolerance
the outlines themselves guarantee (at those poses; between them the outlines move by
microns). Angles in radians, lengths in mm.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.transmission import TransmissionLaw
from wheelstep_cli.geometry.planar import polylines_distance


def _runs(inside: np.ndarray) -> list[np.ndarray]:
    """Index runs (contiguous along the closed outline) of the vertices flagged ``inside``,
    each extended by one vertex either side so its edges reach the region's border."""
    n = len(inside)
    if not inside.any():
        return []
    if inside.all():
        return [np.arange(n + 1) % n]
    starts = np.flatnonzero(inside & ~np.roll(inside, 1))
    ends = np.flatnonzero(inside & ~np.roll(inside, -1))
    # pair each start with the first end at or after it (a run may wrap past index 0)
    ends = ends[np.searchsorted(ends, starts) % len(ends)]
    return [np.arange(s - 1, (e if e >= s else e + n) + 2) % n for s, e in zip(starts, ends)]


def _sector(angles: np.ndarray, centre: float, half: float) -> np.ndarray:
    """Per vertex (polar ``angles``, rad): within ``half`` rad of ``centre``."""
    return np.abs(np.mod(angles - centre + np.pi, 2.0 * np.pi) - np.pi) <= half


def least_separation(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                     samples: int = 256, half_height: float | None = None) -> tuple[float, float]:
    """(least separation mm, pinion angle rad where it occurs) of two closed outlines (N, 2)
    mm in their own frames over ``samples`` poses of one period of ``law``, wheel axis at
    ``distance`` mm (the meshing check's convention, SPEC §10). Only the parts within
    ``half_height`` mm of the line of centres take part (None: a quarter of the smaller
    outer radius, the meshing check's window). 0 when they touch or overlap."""
    rp = float(np.hypot(pinion[:, 0], pinion[:, 1]).max())
    rw = float(np.hypot(wheel[:, 0], wheel[:, 1]).max())
    h = 0.25 * min(rp, rw) if half_height is None else float(half_height)
    # a vertex within h of the line of centres lies within this polar angle of it
    half_p = float(np.arcsin(min(1.0, h / max(1e-9, distance - rw))))
    half_w = float(np.arcsin(min(1.0, h / max(1e-9, distance - rp))))
    a_p, r_p = np.arctan2(pinion[:, 1], pinion[:, 0]), np.hypot(pinion[:, 0], pinion[:, 1])
    a_w, r_w = np.arctan2(wheel[:, 1], wheel[:, 0]), np.hypot(wheel[:, 0], wheel[:, 1])
    theta = law.theta_period * np.arange(samples) / samples
    phi = np.asarray(law.carrier_angle(theta), dtype=float)
    best, where = np.inf, 0.0
    for th, ph in zip(theta, phi):
        # pinion rotated by -theta: its body angle theta faces the wheel; wheel by pi + phi
        # about (distance, 0): its body angle -phi faces the pinion
        in_w, in_p = _sector(a_w, -ph, half_w), _sector(a_p, th, half_p)
        if not in_w.any() or not in_p.any():
            continue
        # only what can come within reach of the other: a pinion point nearer its axis than
        # the distance less the wheel's outermost radius in view is farther than the gap
        # found so far from every wheel point (and likewise)
        slack = min(best, h)
        near_p = in_p & (r_p >= distance - float(r_w[in_w].max()) - slack)
        near_w = in_w & (r_w >= distance - float(r_p[in_p].max()) - slack)
        c, s = np.cos(-th), np.sin(-th)
        p_runs = [pinion[r] @ np.array([[c, s], [-s, c]]) for r in _runs(near_p)]
        c, s = np.cos(np.pi + ph), np.sin(np.pi + ph)
        w_runs = [wheel[r] @ np.array([[c, s], [-s, c]]) + np.array([distance, 0.0]) for r in _runs(near_w)]
        if not p_runs or not w_runs:
            continue
        gap = polylines_distance(p_runs, w_runs)
        if gap < best:
            best, where = gap, float(th)
    return float(best), where
