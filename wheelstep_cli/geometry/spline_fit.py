"""Closed polylines (mm) as a few cubic B-spline edges within a stated distance.

A generated gear outline is a polyline of 5 000-20 000 points. Written to STEP as it is,
every segment becomes a planar side face: tens of megabytes that OpenCASCADE takes minutes
to read. Here each ring is cut at its corners into runs, each run is fitted by a smoothing
cubic spline (FITPACK, chord-length parameter) whose distance to the run, both ways
(Hausdorff), is at most ``FitSettings.tolerance``; a run that cannot be fitted is split
where it deviates most, down to single segments. The fitted pieces are then joined into
composite clamped cubic B-splines, one edge between two sharp corners, so a CAD kernel sees
a few hundred faces at most. Pieces meet exactly at the ring's own points (C0).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import splev, splprep

from wheelstep_cli.geometry.planar import drop_repeated_points

DEGREE = 3
#: A fit is kept when its sampled distance is within this share of the tolerance: the curve
#: between two samples can stray a little further than at them.
SAMPLING_MARGIN = 0.9
#: Largest distance (mm) between two curve samples of a fit's check (a segment's length over
#: its sample count; at least 8 a segment).
SAMPLE_SPACING = 0.01


@dataclass(frozen=True)
class FitSettings:
    """How closely and how coarsely a ring is fitted.

    tolerance: largest distance (mm) between the fitted curve and the polyline, both ways.
    corner_window, corner_angle: a point where the direction of the chords to the points
        ``corner_window`` mm before and after it turns by more than ``corner_angle`` degrees
        starts a new run before any fitting (finds tooth tips and steps at once).
    edge_angle: pieces meeting at a turn above this (degrees) start a new edge.
    max_edges: at most this many edges a ring; the sharpest joins are kept as edge ends.
    max_run: longest run (points) given to one spline fit.
    """

    tolerance: float = 0.005
    corner_window: float = 0.1
    corner_angle: float = 60.0
    edge_angle: float = 30.0
    max_edges: int = 400
    max_run: int = 2000


@dataclass(frozen=True)
class BSpline:
    """A clamped planar B-spline: ``knots`` (non-decreasing, mm-free parameter), ``poles``
    (N, 2) mm, ``degree``; its ends are its first and last pole."""

    knots: np.ndarray
    poles: np.ndarray
    degree: int = DEGREE

    def points(self, per_span: int = 16) -> np.ndarray:
        """Points (M, 2) mm along the curve, ``per_span`` per knot span, both ends included."""
        spans = np.unique(self.knots)
        u = np.concatenate([np.linspace(a, b, per_span, endpoint=False)
                            for a, b in zip(spans[:-1], spans[1:])] + [spans[-1:]])
        return np.stack(splev(u, (self.knots, [self.poles[:, 0], self.poles[:, 1]], self.degree)), 1)


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance (mm) of points ``p`` to segments ``a``-``b`` (broadcast, last axis xy)."""
    ab = b - a
    t = np.clip(((p - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-30), 0.0, 1.0)
    q = p - (a + t[..., None] * ab)
    return np.sqrt((q * q).sum(-1))


def _deviation(run: np.ndarray, u: np.ndarray, tck) -> tuple[float, int]:
    """The Hausdorff distance (mm) between ``run`` (points at parameters ``u``) and the spline
    ``tck``, the curve sampled at least 8 times a segment and every SAMPLE_SPACING mm, and the
    index of the run's segment where it is largest.

    Each curve sample in [u_i, u_i+1] is measured against segments i-1..i+1 and each run
    point against the curve between its neighbours' parameters: a nearest point outside these
    windows is only closer, so the samples' distances are not underestimated."""
    m = len(run)
    counts = np.maximum(np.ceil(np.linalg.norm(np.diff(run, axis=0), axis=1) / SAMPLE_SPACING), 8).astype(int)
    starts = np.concatenate([[0], np.cumsum(counts)])          # the sample at run point i
    owner = np.repeat(np.arange(m - 1), counts)                 # each sample's segment
    step = (np.arange(starts[-1]) - starts[owner]) / counts[owner]
    params = np.append(u[owner] + step * (u[owner + 1] - u[owner]), u[-1])
    curve = np.stack(splev(params, tck), 1)
    owner = np.append(owner, m - 2)
    to_run = np.full(len(curve), np.inf)
    for shift in (-1, 0, 1):
        i = np.clip(owner + shift, 0, m - 2)
        to_run = np.minimum(to_run, _segment_distance(curve, run[i], run[i + 1]))
    point = np.arange(m)
    first, last = starts[np.maximum(point - 1, 0)], starts[np.minimum(point + 1, m - 1)]
    window = last - first                                       # curve segments a run point meets
    who = np.repeat(point, window)
    j = first[who] + np.arange(window.sum()) - np.repeat(np.cumsum(window) - window, window)
    to_curve = np.minimum.reduceat(_segment_distance(run[who], curve[j], curve[j + 1]),
                                   np.cumsum(window) - window)
    if to_run.max() >= to_curve.max():
        return float(to_run.max()), int(owner[np.argmax(to_run)])
    return float(to_curve.max()), min(int(np.argmax(to_curve)), m - 2)


def _fit_run(run: np.ndarray, tolerance: float) -> tuple[BSpline | None, int]:
    """A cubic spline through ``run``'s end points within ``tolerance`` (mm), or None and the
    segment where the best try deviated most."""
    m = len(run)
    u = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(run, axis=0), axis=1))])
    u /= u[-1]
    weights = np.ones(m)
    weights[[0, -1]] = 100.0           # hold the ends; they are snapped exactly below
    worst = m // 2
    for smoothing in (m * (tolerance / 3.0) ** 2, m * (tolerance / 10.0) ** 2):
        with warnings.catch_warnings():
            # FITPACK warns when it stops short of the smoothing asked; the distance check decides
            warnings.simplefilter("ignore")
            try:
                (knots, coefficients, degree), _ = splprep(run.T, u=u, w=weights, s=smoothing,
                                                           k=DEGREE, quiet=2)
            except ValueError:
                return None, worst
        n = len(knots) - degree - 1
        poles = np.stack([np.asarray(c)[:n] for c in coefficients], 1)
        poles[0], poles[-1] = run[0], run[-1]
        distance, worst = _deviation(run, u, (knots, [poles[:, 0], poles[:, 1]], degree))
        if distance <= SAMPLING_MARGIN * tolerance:
            return BSpline(np.asarray(knots, dtype=float), poles, degree), worst
    return None, worst


def _line(a: np.ndarray, b: np.ndarray) -> BSpline:
    """The segment a-b as a cubic B-spline (poles at thirds)."""
    poles = a + np.linspace(0.0, 1.0, DEGREE + 1)[:, None] * (b - a)
    poles[-1] = b                      # a + 1 * (b - a) may miss b by an ulp
    return BSpline(np.repeat([0.0, 1.0], DEGREE + 1), poles)


def corner_points(ring: np.ndarray, window: float, angle: float) -> list[int]:
    """Indices of ``ring`` (N, 2, closed implicitly) where the chords to the points
    ``window`` mm before and after turn by more than ``angle`` degrees (local maxima)."""
    n = len(ring)
    tripled = np.vstack([ring, ring, ring])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(tripled, axis=0), axis=1))])
    i = np.arange(n, 2 * n)
    back = np.clip(np.searchsorted(s, s[i] - window, side="right") - 1, 0, i - 1)
    ahead = np.minimum(np.maximum(np.searchsorted(s, s[i] + window, side="left"), i + 1), 3 * n - 1)
    v1, v2 = tripled[i] - tripled[back], tripled[ahead] - tripled[i]
    turn = np.degrees(np.abs(np.arctan2(v1[:, 0] * v2[:, 1] - v1[:, 1] * v2[:, 0],
                                        (v1 * v2).sum(1))))
    peak = (turn > angle) & (turn >= np.roll(turn, 1)) & (turn >= np.roll(turn, -1))
    return np.flatnonzero(peak).tolist()


def fit_pieces(ring: np.ndarray, settings: FitSettings) -> list[BSpline]:
    """``ring`` (N, 2) mm, closed implicitly, as consecutive B-spline pieces within the
    settings' tolerance; piece k ends where piece k+1 starts, the last where the first starts."""
    ring = np.asarray(ring, dtype=float)
    n = len(ring)
    cuts = corner_points(ring, settings.corner_window, settings.corner_angle)
    if len(cuts) < 2:
        cuts = sorted(set(cuts) | {0, n // 2})
    closed = np.vstack([ring, ring])
    todo = [(a, b) for a, b in zip(cuts, cuts[1:] + [cuts[0] + n])][::-1]
    pieces = []
    while todo:
        first, last = todo.pop()
        if last - first == 1:
            pieces.append(_line(closed[first], closed[last]))
            continue
        spline, worst = (None, (last - first) // 2) if (
            last - first < DEGREE + 1 or last - first > settings.max_run) else \
            _fit_run(closed[first:last + 1], settings.tolerance)
        if spline is not None:
            pieces.append(spline)
            continue
        middle = first + min(max(worst, 1), last - first - 1)
        todo += [(middle, last), (first, middle)]
    return pieces


def _turn(before: BSpline, after: BSpline) -> float:
    """Turn (degrees) of the direction where ``before`` ends and ``after`` starts."""
    d1, d2 = before.poles[-1] - before.poles[-2], after.poles[1] - after.poles[0]
    return float(np.degrees(abs(np.arctan2(d1[0] * d2[1] - d1[1] * d2[0], d1 @ d2))))


def joined(pieces: list[BSpline]) -> BSpline:
    """Consecutive clamped cubic pieces as one composite B-spline, C0 where they meet
    (knot of multiplicity ``DEGREE``), each piece over one unit of parameter."""
    knots, poles = [np.zeros(DEGREE + 1)], [pieces[0].poles[:1]]
    for k, piece in enumerate(pieces):
        span = piece.knots[-1] - piece.knots[0]
        inner = (piece.knots[DEGREE + 1:-DEGREE - 1] - piece.knots[0]) / span
        ends = np.full(DEGREE if k < len(pieces) - 1 else DEGREE + 1, k + 1.0)
        knots += [k + inner, ends]
        poles.append(piece.poles[1:])
    return BSpline(np.concatenate(knots), np.concatenate(poles), DEGREE)


def fit_ring(ring: np.ndarray, settings: FitSettings = FitSettings()) -> list[BSpline]:
    """``ring`` (N, 2) mm as closed consecutive composite B-spline edges: one edge between
    joins turning more than ``edge_angle`` degrees, at most ``max_edges`` (the sharpest)."""
    # a repeated point would be a zero-length piece with no direction, hiding a corner beside it
    ring = drop_repeated_points(ring, tol=0.0)
    if len(ring) < 3:
        raise ValueError(f"a ring needs 3 distinct points, got {len(ring)}")
    pieces = fit_pieces(ring, settings)
    turns = np.array([_turn(pieces[k - 1], pieces[k]) for k in range(len(pieces))])
    sharp = np.flatnonzero(turns > settings.edge_angle)
    if len(sharp) > settings.max_edges:
        sharp = np.sort(sharp[np.argsort(-turns[sharp], kind="stable")[:settings.max_edges]])
    if len(sharp) == 0:
        sharp = np.array([0])
    starts = sharp.tolist()
    return [joined([pieces[k % len(pieces)] for k in range(a, b)])
            for a, b in zip(starts, starts[1:] + [starts[0] + len(pieces)])]
