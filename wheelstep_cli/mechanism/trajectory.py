"""Foot trajectory from a support segment and three circular arcs (SPEC §8).

Frame (mm, radians): the support segment runs from A = (x0, y0) to D = (x0 + H, y0);
the foot lifts toward +y. Arc r1 is tangent to AD at A (centre O1 = A + (0, r1)),
arc r2 at D (O2 = D + (0, r2)); the top arc r3 touches both from outside, i.e. they lie
inside it: |O3 O1| = r3 - r1, |O3 O2| = r3 - r2. The tangent points are
B = O3 + r3 unit(O1 - O3) and C = O3 + r3 unit(O2 - O3).

The closed path is traversed counter-clockwise: A -> D along the support line, arc r2
from D up to C, arc r3 from C over the top to B, arc r1 from B down to A.

Given the clearance h_max (top of the path above AD), the top arc follows in closed
form: with k_i = h_max - 2 r_i > 0, eliminating r3 from the two tangency conditions
(O3 at height y0 + h_max - r3) gives (x3 - x1)^2 / k1 = (x3 - x2)^2 / k2, so

    x3 = (x1 sqrt(k2) + x2 sqrt(k1)) / (sqrt(k1) + sqrt(k2))
    r3 = (x3 - x1)^2 / (2 k1) + h_max / 2

which for r1 = r2 is SPEC's corrected 2 r3 = h_max + H^2 / (4 (h_max - 2 r2)).
Given r3, O3 is an intersection of two circles about O1 and O2; this takes the one on
the support-line side of O1 O2, the root of SPEC's symmetric formula
h_max = r3 + r2 - sqrt((r3 - r2)^2 - H^2/4).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError, require


@dataclass(frozen=True)
class Segment:
    """Straight piece from ``start`` to ``end`` (mm)."""

    start: np.ndarray
    end: np.ndarray

    def point(self, t):
        t = np.asarray(t, dtype=float)[..., None]
        return self.start + t * (self.end - self.start)

    def tangent(self, t):
        d = (self.end - self.start) / np.linalg.norm(self.end - self.start)
        return np.broadcast_to(d, np.shape(t) + (2,))

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.end - self.start))

    def top(self) -> float:
        return float(max(self.start[1], self.end[1]))


@dataclass(frozen=True)
class Arc:
    """Counter-clockwise arc about ``center``: angles ``start`` .. ``start + sweep`` (rad)."""

    center: np.ndarray
    radius: float
    start: float
    sweep: float

    def point(self, t):
        ang = self.start + np.asarray(t, dtype=float) * self.sweep
        return self.center + self.radius * np.stack([np.cos(ang), np.sin(ang)], axis=-1)

    def tangent(self, t):
        ang = self.start + np.asarray(t, dtype=float) * self.sweep
        return np.stack([-np.sin(ang), np.cos(ang)], axis=-1)

    @property
    def length(self) -> float:
        return float(self.radius * self.sweep)

    def top(self) -> float:
        """Highest y on the arc: the circle's top if the arc passes angle pi/2, else an end."""
        if (np.pi / 2 - self.start) % (2 * np.pi) <= self.sweep:
            return float(self.center[1] + self.radius)
        return float(max(self.point(0.0)[1], self.point(1.0)[1]))


@dataclass(frozen=True)
class FootPath:
    """The composed closed foot path and its construction points (mm)."""

    support_length: float
    y0: float
    r1: float
    r2: float
    r3: float
    h_max: float
    A: np.ndarray
    D: np.ndarray
    O1: np.ndarray
    O2: np.ndarray
    O3: np.ndarray
    B: np.ndarray
    C: np.ndarray
    pieces: tuple        # Segment AD, Arc r2 (D->C), Arc r3 (C->B), Arc r1 (B->A)

    @property
    def length(self) -> float:
        return float(sum(p.length for p in self.pieces))


#: Smallest arc radius (mm): below it an arc is a corner no printer or machine follows, and
#: its tangent points, found from the top arc's centre hundreds of mm away, lose their digits.
MIN_ARC = 0.01


def _check_common(support_length, r1, r2):
    require(support_length > 0, "support-length", support_length, "must be > 0 mm")
    require(r1 >= MIN_ARC, "r1", r1, f"must be >= {MIN_ARC:g} mm")
    require(r2 >= MIN_ARC, "r2", r2, f"must be >= {MIN_ARC:g} mm")


def top_arc_for_clearance(support_length, r1, r2, h_max, x0=0.0, y0=0.0):
    """Centre O3 and radius r3 of the top arc giving clearance ``h_max`` (closed form above)."""
    _check_common(support_length, r1, r2)
    big = max(r1, r2)
    require(h_max > 2 * big, "h-max", h_max,
            f"must be > 2 max(r1, r2) = {2 * big:g} mm for the top arc to touch both arcs from outside")
    x1, x2 = x0, x0 + support_length
    k1, k2 = h_max - 2 * r1, h_max - 2 * r2
    s1, s2 = np.sqrt(k1), np.sqrt(k2)
    x3 = (x1 * s2 + x2 * s1) / (s1 + s2)
    r3 = (x3 - x1) ** 2 / (2 * k1) + h_max / 2
    return np.array([x3, y0 + h_max - r3]), float(r3)


def top_arc_for_radius(support_length, r1, r2, r3, x0=0.0, y0=0.0, root="lower"):
    """Centre O3 of the top arc of radius ``r3``.

    Two centres satisfy both tangencies, mirror images across the line O1 O2;
    ``root="lower"`` (default) takes the one on the support-line side, SPEC's symmetric
    formula; ``"upper"`` the other, which gives a taller path with a top arc over 180 deg.
    """
    require(root in ("lower", "upper"), "o3-root", root, "must be lower or upper")
    _check_common(support_length, r1, r2)
    big = max(r1, r2)
    require(r3 > big, "r3", r3, f"must be > max(r1, r2) = {big:g} mm (the arcs lie inside the top arc)")
    o1 = np.array([x0, y0 + r1])
    o2 = np.array([x0 + support_length, y0 + r2])
    d = o2 - o1
    dist = float(np.linalg.norm(d))
    ra, rb = r3 - r1, r3 - r2
    need = (dist + r1 + r2) / 2
    require(ra + rb >= dist, "r3", r3,
            f"too small: the top arc cannot touch both arcs, needs r3 >= (|O1O2| + r1 + r2)/2 = {need:.4g} mm")
    along = (ra**2 - rb**2 + dist**2) / (2 * dist)
    h = np.sqrt(max(ra**2 - along**2, 0.0))
    u = d / dist
    perp = np.array([-u[1], u[0]])           # left of O1 -> O2, away from the support line
    return o1 + along * u + (h if root == "upper" else -h) * perp


def _angle(v) -> float:
    return float(np.arctan2(v[1], v[0]))


def _involved(param: str, sizes: dict[str, float | None]) -> tuple[str, ...]:
    """The sizes the rule of ``param`` depends on besides ``param`` itself: the clearance rule
    h_max > 2 max(r1, r2) only on the larger arc; the others on every size of the path."""
    if param == "h-max":
        big = max(sizes["r1"], sizes["r2"])
        return tuple(name for name in ("r1", "r2") if sizes[name] == big)
    return tuple(sizes)


def foot_path(support_length: float, r1: float, r2: float, r3: float | None = None,
              h_max: float | None = None, x0: float = 0.0, y0: float = 0.0,
              root: str = "lower") -> FootPath:
    """Compose the closed foot path from AD (length ``support_length`` at y = ``y0``) and three arcs.

    Give exactly one of ``r3`` and ``h_max`` (``root``: see :func:`top_arc_for_radius`). Raises DesignError where the arcs cannot be
    tangent or would not close into one convex loop.
    """
    if (r3 is None) == (h_max is None):
        raise DesignError("r3", "given" if r3 is not None else "missing", "give exactly one of --r3 and --h-max")
    try:
        return _foot_path(support_length, r1, r2, r3, h_max, x0, y0, root)
    except DesignError as err:   # every size of the path shares the blame for its shape
        sizes = {"support_length": support_length, "r1": r1, "r2": r2, "r3": r3, "h_max": h_max}
        raise err.tied_to({name: sizes[name] for name in _involved(err.param, sizes)}) from None


def _foot_path(support_length: float, r1: float, r2: float, r3: float | None, h_max: float | None,
               x0: float, y0: float, root: str) -> FootPath:
    if r3 is None:
        o3, r3 = top_arc_for_clearance(support_length, r1, r2, h_max, x0, y0)
    else:
        o3 = top_arc_for_radius(support_length, r1, r2, r3, x0, y0, root)
    a = np.array([x0, y0])
    dpt = np.array([x0 + support_length, y0])
    o1, o2 = a + [0.0, r1], dpt + [0.0, r2]
    b = o3 + r3 * (o1 - o3) / np.linalg.norm(o1 - o3)
    c = o3 + r3 * (o2 - o3) / np.linalg.norm(o2 - o3)
    two_pi = 2 * np.pi
    arc2 = Arc(o2, r2, -np.pi / 2, (_angle(c - o2) + np.pi / 2) % two_pi)
    arc3 = Arc(o3, r3, _angle(c - o3), (_angle(b - o3) - _angle(c - o3)) % two_pi)
    arc1 = Arc(o1, r1, _angle(b - o1), (-np.pi / 2 - _angle(b - o1)) % two_pi)
    # the pieces meet tangentially by construction, so the arcs turn a whole number of turns
    # (each sweep lies in [0, 2 pi)): one turn is a convex loop, none or two are not. A quarter
    # turn of margin either way keeps a path hundreds of metres long off the rounding of its
    # sweeps.
    turning = arc1.sweep + arc2.sweep + arc3.sweep
    require(abs(turning - two_pi) < 0.5 * np.pi, "r3", r3,
            "the arcs cannot be joined into one convex closed path (they turn "
            f"{np.degrees(turning):.1f} deg instead of 360)")
    pieces = (Segment(a, dpt), arc2, arc3, arc1)
    top = max(p.top() for p in pieces)
    return FootPath(support_length=float(support_length), y0=float(y0), r1=float(r1), r2=float(r2),
                    r3=float(r3), h_max=float(top - y0), A=a, D=dpt, O1=o1, O2=o2, O3=o3, B=b, C=c,
                    pieces=pieces)


def sample_path(path: FootPath, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Points of the closed path about ``spacing`` mm apart, every piece's ends included.

    Returns ``(points (N, 2), piece index (N,))``; the last point repeats the first (A).
    """
    pts, idx = [], []
    for i, piece in enumerate(path.pieces):
        n = max(2, int(np.ceil(piece.length / spacing)) + 1)
        t = np.linspace(0.0, 1.0, n)[:-1]
        pts.append(piece.point(t))
        idx.append(np.full(t.size, i))
    pts.append(path.A[None, :])
    idx.append(np.array([0]))
    return np.concatenate(pts), np.concatenate(idx)


def symmetric_clearance(support_length: float, r: float, r3: float) -> float:
    """SPEC §8 symmetric case: h_max = r3 + r - sqrt((r3 - r)^2 - H^2/4)."""
    return float(r3 + r - np.sqrt((r3 - r) ** 2 - support_length**2 / 4))


def symmetric_top_radius(support_length: float, r: float, h_max: float) -> float:
    """SPEC §8 symmetric case (corrected): 2 r3 = h_max + H^2 / (4 (h_max - 2 r))."""
    return float((h_max + support_length**2 / (4 * (h_max - 2 * r))) / 2)
