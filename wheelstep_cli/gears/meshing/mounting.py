"""How much closer than designed a pair may be mounted: the least separation of its outlines.

At every pose of the law the wheel, moved a distance d toward the pinion along any
direction, can only overlap it if some point of its outline lies within d of the
pinion's. The least separation over the poses is therefore a mounted-distance tolerance
the outlines themselves guarantee (at the poses sampled, refined round the closest ones).
Angles in radians, lengths in mm.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.threads import thread_map
from wheelstep_cli.gears.transmission import TransmissionLaw
from wheelstep_cli.geometry.planar import polylines_distance, simplify_ring


#: Douglas-Peucker tolerance (mm) the outlines are thinned to before the distance queries.
THIN = 0.002


def _runs(index: np.ndarray, n: int) -> list[np.ndarray]:
    """Runs (contiguous along a closed outline of ``n`` vertices) of the sorted vertex
    ``index``, each extended by one vertex either side so its edges reach the region's
    border (a run through the last vertex continues at the first)."""
    if len(index) == 0:
        return []
    if len(index) == n:
        return [np.arange(n + 1) % n]
    cuts = np.flatnonzero(np.diff(index) > 1) + 1
    runs = [np.arange(r[0] - 1, r[-1] + 2) % n for r in np.split(index, cuts)]
    if len(runs) > 1 and index[0] == 0 and index[-1] == n - 1:
        runs = [np.concatenate([runs[-1][:-1], runs[0][1:]])] + runs[1:-1]
    return runs


class _Polar:
    """An outline's vertices sorted by polar angle, for the ones within a sector."""

    def __init__(self, outline: np.ndarray):
        self.outline = outline
        angle = np.arctan2(outline[:, 1], outline[:, 0])
        self.order = np.argsort(angle)
        self.sorted = angle[self.order]
        self.radius = np.hypot(outline[:, 0], outline[:, 1])

    def sector(self, centre: float, half: float) -> np.ndarray:
        """Vertex indices (unsorted) within ``half`` rad of the polar angle ``centre``."""
        lo = np.mod(centre - half + np.pi, 2.0 * np.pi) - np.pi
        hi = lo + 2.0 * half
        a, b = np.searchsorted(self.sorted, [lo, min(hi, np.pi)])
        picked = self.order[a:b]
        if hi > np.pi:
            picked = np.concatenate([picked, self.order[:np.searchsorted(self.sorted, hi - 2.0 * np.pi)]])
        return picked


def least_separation(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                     samples: int = 192, half_height: float | None = None,
                     refine: int = 24) -> tuple[float, float]:
    """(least separation mm, pinion angle rad where it occurs) of two closed outlines (N, 2)
    mm in their own frames over one period of ``law``, wheel axis at ``distance`` mm (the
    meshing check's convention, SPEC §10): ``samples`` poses, then the ``refine`` closest
    of them again at 7 poses either side between their neighbours, eighths of a step apart
    (a tip passing a root is closest for a fraction of a sample step). Only the parts within ``half_height`` mm
    of the line of centres take part (None: a quarter of the smaller outer radius, the
    meshing check's window). 0 when they touch or overlap; less the thinning's
    error (twice :data:`THIN`), so never more than the true gap."""
    # thinned by THIN mm the outlines have fewer vertices for the distance queries; each
    # moved by at most that, so the gap found less twice it is still a lower bound
    pinion, wheel = _Polar(simplify_ring(pinion, THIN)), _Polar(simplify_ring(wheel, THIN))
    step = law.theta_period / samples
    theta = step * np.arange(samples)
    coarse = _gaps_over(pinion, wheel, law, distance, half_height, theta, np.inf)
    # on a grid of eighths of a step, each pose once: neighbouring candidates share the poses
    # between them, and the coarse poses are measured already
    eighths = (8 * np.argsort(coarse)[:refine][:, None] + np.arange(-7, 8)[None, :]).ravel()
    eighths = np.unique(eighths[eighths % 8 != 0])
    fine = step * eighths / 8.0
    fine_gaps = _gaps_over(pinion, wheel, law, distance, half_height, fine, float(coarse.min()))
    every, at = np.concatenate([coarse, fine_gaps]), np.concatenate([theta, fine])
    k = int(np.argmin(every))
    return max(0.0, float(every[k]) - 2.0 * THIN), float(np.mod(at[k], law.theta_period))


#: Blocks of poses measured apart (each on its own thread, from its own least gap): a fixed
#: count, so every pose's figure is the same whatever the machine's cores.
BLOCKS = 8


def _gaps_over(pinion: _Polar, wheel: _Polar, law, distance, half_height, theta: np.ndarray,
               best: float) -> np.ndarray:
    """The least distance (mm) of the posed outlines at each pinion angle ``theta`` (rad),
    exact wherever it is at most ``best`` mm or the least within its block (others may
    come out larger); the blocks shared by threads."""
    phi = np.asarray(law.carrier_angle(theta), dtype=float)
    blocks = np.array_split(np.arange(len(theta)), BLOCKS)

    def block(index: np.ndarray) -> np.ndarray:
        gaps = _Gaps(pinion, wheel, distance, half_height, best)
        return np.array([gaps(theta[i], phi[i]) for i in index], dtype=float)

    return np.concatenate(list(thread_map(block, blocks)))


class _Gaps:
    """The least distance (mm) between the two posed outlines at a pose, or more than the
    least gap found so far (``best`` mm at the start) where it cannot be less."""

    def __init__(self, pinion: _Polar, wheel: _Polar, distance, half_height, best: float = np.inf):
        self.pinion, self.wheel, self.distance = pinion, wheel, float(distance)
        rp, rw = float(self.pinion.radius.max()), float(self.wheel.radius.max())
        self.h = 0.25 * min(rp, rw) if half_height is None else float(half_height)
        # a vertex within h of the line of centres lies within this polar angle of it
        self.half_p = float(np.arcsin(min(1.0, self.h / max(1e-9, distance - rw))))
        self.half_w = float(np.arcsin(min(1.0, self.h / max(1e-9, distance - rp))))
        self.best = best    # the least gap found so far: farther parts need not take part

    def __call__(self, th: float, ph: float) -> float:
        """The gap at pinion angle ``th`` and wheel angle ``ph`` (rad)."""
        distance, p, w = self.distance, self.pinion, self.wheel
        # pinion rotated by -theta: its body angle theta faces the wheel; wheel by pi + phi
        # about (distance, 0): its body angle -phi faces the pinion
        in_w, in_p = w.sector(-ph, self.half_w), p.sector(th, self.half_p)
        if len(in_w) == 0 or len(in_p) == 0:
            return np.inf
        # only what can come closer than the least gap found so far: a pinion point nearer its
        # axis than the distance less the wheel's outermost radius in view less that gap is
        # farther from every wheel point (and likewise); a larger gap here is not the least
        slack = min(self.best, self.h)
        near_p = np.sort(in_p[p.radius[in_p] >= distance - float(w.radius[in_w].max()) - slack])
        near_w = np.sort(in_w[w.radius[in_w] >= distance - float(p.radius[in_p].max()) - slack])
        c, s = np.cos(-th), np.sin(-th)
        p_runs = [p.outline[r] @ np.array([[c, s], [-s, c]]) for r in _runs(near_p, len(p.outline))]
        c, s = np.cos(np.pi + ph), np.sin(np.pi + ph)
        w_runs = [w.outline[r] @ np.array([[c, s], [-s, c]]) + np.array([distance, 0.0])
                  for r in _runs(near_w, len(w.outline))]
        if not p_runs or not w_runs:
            return np.inf
        gap = polylines_distance(p_runs, w_runs)
        self.best = min(self.best, gap)
        return gap
