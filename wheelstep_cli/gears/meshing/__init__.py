"""Meshing check of two gear outlines (SPEC §10): contact, backlash, TE, hub speed ripple.

Law-agnostic and pure numpy. Convention (both parts face-up as printed, seen from +z):
the pinion axis is at the origin, the wheel axis at ``(D, 0)``. At pinion angle
``theta`` the pinion (outline in its own frame) is rotated by ``-theta`` (clockwise)
about the origin, the wheel by ``pi + phi(theta)`` (counter-clockwise) about
``(D, 0)``. So the pinion's pitch point for ``theta`` lies at body angle ``+theta``
and the wheel's pitch point for ``phi`` at body angle ``-phi``.

The pinion drives. Under load the wheel lags: the **drive-side** contact is found
by rotating the wheel backwards (decreasing ``phi``) from the law's angle until its
outline first touches the pinion's; the **coast side** by rotating it forwards.
``TE = phi_drive - phi_law``; angular backlash ``= phi_coast - phi_drive``.

First contact between rotating polygons happens when a vertex of one meets an edge
of the other. Seen from the wheel axis, a wheel vertex at radius rho sweeps a circle
of that radius relative to the pinion and a pinion vertex sweeps a circle of its
radius relative to the wheel; intersecting those circles with the other outline's
edges gives, for every vertex/edge pair, the exact rotation to contact. Only the
vertices and edges inside the *mesh window* (a box round the line of centres,
between the two axes) take part.

Search (speed and memory only, the result is the same): pairs are found by sorting,
never in dense vertex x edge tables, and produced in bounded chunks. A first pass
looks only for contacts within ``REACH`` rad and skips vertices and edges whose
radial band cannot meet the other outline that close; a pose not settled within
``REACH`` is searched again over all pairs.

If the outlines overlap at the law's angle (a vertex of one lies inside the other),
the pose **interferes**; it is measured by the overlapping area (mm^2) and the
penetration depth (mm: the deepest such vertex's distance to the other outline).
Rigid teeth cannot take such a pose, so its contact angles are estimates: each
vertex inside counts as pressing on the flank it leaves by the smaller rotation
along its circle, giving a negative gap on that side (the drive side if it leaves
turning the wheel forwards). Summaries therefore also give the hub speed ripple
over the clear poses only.

Angles in radians, lengths in mm; degrees, arcminutes and % only in ``to_dict``.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Callable

import numpy as np

from wheelstep_cli.gears.threads import thread_map

#: Default poses per period: 64 per wheel tooth for the 24 teeth of the source
#: design's period (see ``benchmarks/meshcheck.py`` for the convergence study).
DEFAULT_SAMPLES = 1536
#: Default half-height of the mesh window as a fraction of the smaller gear's outer radius.
WINDOW_FRACTION = 0.25
#: Poses handled together in one vectorised batch (fewer for very large outlines).
BATCH = 64
#: Most outline points (poses x points of both outlines) in one batch; bounds its memory.
BATCH_POINTS = 1_000_000
#: Most vertex/edge candidate pairs held at once (about 100 bytes each in temporaries).
MAX_PAIRS = 1 << 19
#: First pass: only contacts within this wheel rotation (rad) are looked for; poses with
#: no contact that close are redone without the limit. Changes the speed, not the result.
REACH = 0.01


@dataclass(frozen=True)
class Transmission:
    """The motion the pair should have.

    ``driven_angle``: wheel angle phi(theta) in rad for pinion angles theta in rad
    (vectorised, continuous, increasing). ``period``: pinion angle (rad) after which
    the tooth pattern repeats. ``hub_speed_factor``: f(phi) such that the output
    speed is proportional to f(phi) * dphi/dtheta at constant pinion speed (None: 1).
    """

    driven_angle: Callable[[np.ndarray], np.ndarray]
    period: float
    hub_speed_factor: Callable[[np.ndarray], np.ndarray] | None = None


@dataclass(frozen=True)
class MeshingReport:
    """Per-pose results (arrays over the pinion angles ``theta``) and their summary.

    ``phi_law``, ``phi_drive``, ``phi_coast``: wheel angles (rad); NaN where no contact
    was found within the mesh window in that direction. ``interference``: per-pose
    overlap at the law's angle. ``overlap_area``: mm^2 per pose. ``penetration``: depth
    (mm) of the deepest vertex inside the other outline (0 when clear).
    ``hub_speed``: f(phi_drive) dphi_drive/dtheta (relative units), ``pitch_radius``:
    the wheel's instantaneous pitch radius (mm) at the installed distance.
    """

    theta: np.ndarray
    phi_law: np.ndarray
    phi_drive: np.ndarray
    phi_coast: np.ndarray
    interference: np.ndarray
    overlap_area: np.ndarray
    penetration: np.ndarray
    hub_speed: np.ndarray
    hub_speed_law: np.ndarray
    pitch_radius: np.ndarray
    distance: float
    period: float

    @property
    def transmission_error(self) -> np.ndarray:
        """phi_drive - phi_law (rad at the wheel)."""
        return self.phi_drive - self.phi_law

    @property
    def backlash(self) -> np.ndarray:
        """Angular backlash phi_coast - phi_drive (rad at the wheel)."""
        return self.phi_coast - self.phi_drive

    @property
    def backlash_mm(self) -> np.ndarray:
        """Backlash along the wheel's pitch curve (mm): pitch radius times angular backlash."""
        return self.pitch_radius * self.backlash

    @property
    def interferes(self) -> bool:
        return bool(np.any(self.interference))

    @property
    def contact_lost(self) -> bool:
        """True when at some pose no drive-side contact was found (teeth out of mesh)."""
        return bool(np.any(np.isnan(self.phi_drive)))

    @property
    def te_peak_to_peak(self) -> float:
        return _peak_to_peak(self.transmission_error)

    @property
    def te_max_step(self) -> float:
        """Largest change of TE between neighbouring poses (rad), the period wrapped.

        Shrinks with more samples while the drive-side motion is continuous; stays
        when the wheel jumps (contact hands over to a tooth that was not touching).
        Then the hub speed has spikes that grow with the sample count, and the ripple
        only means "at this sampling".
        """
        te = self.transmission_error
        return float(np.nanmax(np.abs(np.diff(np.append(te, te[:1])))))

    @property
    def hub_speed_ripple(self) -> float:
        """Peak-to-peak over mean of the hub speed from the drive-side contact (fraction)."""
        return _peak_to_peak(self.hub_speed) / float(np.nanmean(self.hub_speed))

    @property
    def clear(self) -> np.ndarray:
        """Poses whose hub speed comes from clear contact: neither they nor a neighbour interfere."""
        bad = self.interference | np.isnan(self.phi_drive)
        return ~(bad | np.roll(bad, 1) | np.roll(bad, -1))

    @property
    def hub_speed_ripple_clear(self) -> float:
        """Hub speed ripple (fraction) over the clear poses only; NaN if there are none.

        Where outlines overlap, the drive contact is a penetration estimate, not a
        motion; this figure shows what the teeth do where they do mesh.
        """
        clear = self.clear
        if not clear.any():
            return float("nan")
        v = self.hub_speed[clear]
        return _peak_to_peak(v) / float(np.nanmean(v))

    def to_dict(self) -> dict:
        """Summary in degrees, arcminutes, mm and % for JSON and tables."""
        arcmin = 60.0 * 180.0 / np.pi
        te = self.transmission_error
        return {
            "distance_mm": self.distance,
            "samples": int(len(self.theta)),
            "period_deg": float(np.degrees(self.period)),
            "interference": self.interferes,
            "interfering_poses": int(np.count_nonzero(self.interference)),
            "max_overlap_area_mm2": float(self.overlap_area.max()),
            "max_penetration_mm": float(self.penetration.max()),
            "contact_lost": self.contact_lost,
            "backlash_min_arcmin": _nan_none(np.nanmin(self.backlash) * arcmin),
            "backlash_max_arcmin": _nan_none(np.nanmax(self.backlash) * arcmin),
            "backlash_min_mm": _nan_none(np.nanmin(self.backlash_mm)),
            "backlash_max_mm": _nan_none(np.nanmax(self.backlash_mm)),
            "te_min_arcmin": _nan_none(np.nanmin(te) * arcmin),
            "te_max_arcmin": _nan_none(np.nanmax(te) * arcmin),
            "te_peak_to_peak_arcmin": _nan_none(self.te_peak_to_peak * arcmin),
            "te_max_step_arcmin": _nan_none(self.te_max_step * arcmin),
            "hub_speed_ripple_pct": _nan_none(100.0 * self.hub_speed_ripple),
            "hub_speed_ripple_clear_pct": _nan_none(100.0 * self.hub_speed_ripple_clear),
            "clear_poses": int(np.count_nonzero(self.clear)),
            "law_hub_speed_ripple_pct": float(
                100.0 * _peak_to_peak(self.hub_speed_law) / np.mean(self.hub_speed_law)),
        }


def _peak_to_peak(values: np.ndarray) -> float:
    if np.all(np.isnan(values)):
        return float("nan")
    return float(np.nanmax(values) - np.nanmin(values))


def _nan_none(value: float) -> float | None:
    return None if not np.isfinite(value) else float(value)


def _rotate(points: np.ndarray, angle) -> np.ndarray:
    """Rotate (..., 2) points by ``angle`` rad counter-clockwise about the origin.

    ``angle`` is a scalar or broadcasts against ``points[..., 0]``.
    """
    c, s = np.cos(angle), np.sin(angle)
    x, y = points[..., 0], points[..., 1]
    return np.stack([c * x - s * y, s * x + c * y], axis=-1)


def _wrap(angle: np.ndarray) -> np.ndarray:
    """Angles into (-pi, pi]."""
    return np.pi - np.mod(np.pi - angle, 2.0 * np.pi)


@dataclass(frozen=True)
class _Window:
    """Edges and vertices of one outline inside the mesh window, for a batch of poses.

    Flat arrays, grouped by pose: every edge (start ``e0``, end ``e1``) and vertex ``v``
    carries the index of its pose in ``e_pose`` / ``v_pose``.
    """

    e_pose: np.ndarray
    e0: np.ndarray
    e1: np.ndarray
    v_pose: np.ndarray
    v: np.ndarray


@dataclass(frozen=True)
class _Sorted:
    """One outline with its vertices and edges ordered by body angle, to cut windows out fast.

    ``v_angle``: the vertices' body angles (rad) sorted, listed twice (the second time
    + 2 pi) so that an angular range never wraps; ``v_index`` their vertices. ``e_angle``,
    ``e_index``: the same for the start angles of the short edges (edge i runs from vertex
    i to i + 1), ``e_sweep`` the largest angle and ``e_length`` the largest length (mm)
    of a short edge. ``e_always``: the other edges (long, or passing near the axis),
    tested in every pose.
    """

    points: np.ndarray
    v_angle: np.ndarray
    v_index: np.ndarray
    e_angle: np.ndarray
    e_index: np.ndarray
    e_sweep: float
    e_length: float
    e_always: np.ndarray


def _sorted_outline(points: np.ndarray, long_edge: float) -> _Sorted:
    """Prepare an outline (N, 2) for :func:`_window`; edges over ``long_edge`` mm are always tested."""
    nxt = np.roll(points, -1, axis=0)
    a0 = np.arctan2(points[:, 1], points[:, 0])
    # a segment not through the axis sees its angle change monotonically, by less than pi
    sweep = _wrap(np.arctan2(nxt[:, 1], nxt[:, 0]) - a0)
    length = np.hypot(nxt[:, 0] - points[:, 0], nxt[:, 1] - points[:, 1])
    short = (length <= long_edge) & (np.abs(sweep) <= 0.5)
    v_angle = np.mod(a0, 2.0 * np.pi)
    v_order = np.argsort(v_angle, kind="stable")
    e_start = np.mod(np.where(sweep >= 0.0, a0, a0 + sweep), 2.0 * np.pi)
    idx = np.flatnonzero(short)
    e_order = idx[np.argsort(e_start[idx], kind="stable")]
    twice = lambda a: np.concatenate([a, a + 2.0 * np.pi])  # noqa: E731
    return _Sorted(points, twice(v_angle[v_order]), np.tile(v_order, 2),
                   twice(e_start[e_order]), np.tile(e_order, 2),
                   float(np.abs(sweep[idx]).max(initial=0.0)), float(length[idx].max(initial=0.0)),
                   np.flatnonzero(~short))


def _sector(box, axis: np.ndarray, extra: float) -> tuple[float, float] | None:
    """World angles (lo, hi) rad, seen from ``axis``, of the edge box widened by ``extra`` mm.

    None when that box holds the axis (then every angle is in view).
    """
    xlo, xhi, half, margin = box
    grow = margin + extra + 1e-9
    x0, x1, y = xlo - grow, xhi + grow, half + grow
    if x0 <= axis[0] <= x1 and -y <= axis[1] <= y:
        return None
    centre = np.arctan2(-axis[1], 0.5 * (x0 + x1) - axis[0])
    corners = np.array([[x0, -y], [x0, y], [x1, -y], [x1, y]]) - axis
    rel = _wrap(np.arctan2(corners[:, 1], corners[:, 0]) - centre)
    return float(centre + rel.min()), float(centre + rel.max())


def _in_sector(angle2: np.ndarray, index2: np.ndarray, lo: np.ndarray, width: float):
    """(pose, index) of the entries whose sorted, doubled angles lie in [lo[pose], lo + width]."""
    lo = np.mod(lo - 1e-9, 2.0 * np.pi)
    first = np.searchsorted(angle2, lo, side="left")
    last = np.searchsorted(angle2, lo + width + 2e-9, side="right")
    return _expand(first, last - first, index2)


def _expand(first: np.ndarray, counts: np.ndarray, table: np.ndarray):
    """(owner, table[first[owner] + k]) for k < counts[owner], owners in order."""
    owner = np.repeat(np.arange(len(first)), counts)
    offsets = np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts)
    return owner, table[first[owner] + offsets]


def _window(outline: _Sorted, angle: np.ndarray, shift: np.ndarray | None,
            sector: tuple[float, float] | None, body_offset: np.ndarray, box) -> _Window:
    """Window parts of a closed outline, rotated by ``angle`` (poses,) rad and shifted by ``shift``.

    ``box`` = (x_lo, x_hi, half height, margin). Vertices: those inside the box.
    Edges: those whose bounding box meets the box widened by ``margin`` on every side,
    so every edge through the box is there, however long, and the outline round a
    vertex is in view within ``margin``. ``sector``: world angles seen from the axis
    holding every such vertex and an end of every such short edge; ``body_offset``
    (poses,): body angle minus world angle. Only those are posed and tested.
    """
    poses, n = len(angle), len(outline.points)
    if sector is None:
        v_pose, v_idx = np.repeat(np.arange(poses), n), np.tile(np.arange(n), poses)
        e_pose, e_idx = v_pose, v_idx
    else:
        lo = sector[0] + body_offset
        width = sector[1] - sector[0]
        v_pose, v_idx = _in_sector(outline.v_angle, outline.v_index, lo, width)
        e_pose, e_idx = _in_sector(outline.e_angle, outline.e_index, lo - outline.e_sweep,
                                   width + outline.e_sweep)
        if len(outline.e_always):
            e_pose = np.concatenate([e_pose, np.repeat(np.arange(poses), len(outline.e_always))])
            e_idx = np.concatenate([e_idx, np.tile(outline.e_always, poses)])
            order = np.argsort(e_pose, kind="stable")
            e_pose, e_idx = e_pose[order], e_idx[order]
    c, s = np.cos(angle), np.sin(angle)

    def pose_points(pose, idx):
        x, y = outline.points[idx, 0], outline.points[idx, 1]
        world = np.stack([c[pose] * x - s[pose] * y, s[pose] * x + c[pose] * y], axis=-1)
        return world if shift is None else world + shift

    xlo, xhi, half, margin = box
    v = pose_points(v_pose, v_idx)
    vertex = (v[:, 0] >= xlo) & (v[:, 0] <= xhi) & (np.abs(v[:, 1]) <= half)
    e0, e1 = pose_points(e_pose, e_idx), pose_points(e_pose, (e_idx + 1) % n)
    x, y, x1, y1 = e0[:, 0], e0[:, 1], e1[:, 0], e1[:, 1]
    edge = ((np.minimum(x, x1) <= xhi + margin) & (np.maximum(x, x1) >= xlo - margin)
            & (np.minimum(y, y1) <= half + margin) & (np.maximum(y, y1) >= -half - margin))
    return _Window(e_pose[edge], e0[edge], e1[edge], v_pose[vertex], v[vertex])


@dataclass(frozen=True)
class _EdgeTable:
    """Per-edge quantities about the wheel axis: the crossing quadratic's coefficients, the
    radial extent [lo, hi] (mm) and the angular extent [start, start + sweep] (rad)."""

    e0: np.ndarray
    d: np.ndarray
    dd: np.ndarray
    ed: np.ndarray
    ee: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    start: np.ndarray
    sweep: np.ndarray
    pose: np.ndarray


def _edge_table(edges: _Window) -> _EdgeTable:
    e0, e1 = edges.e0, edges.e1
    d = e1 - e0
    dd = np.einsum("ij,ij->i", d, d)
    ed = np.einsum("ij,ij->i", e0, d)
    ee = np.einsum("ij,ij->i", e0, e0)
    t_near = np.clip(-ed / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    lo = np.hypot(e0[:, 0] + t_near * d[:, 0], e0[:, 1] + t_near * d[:, 1])
    hi = np.sqrt(np.maximum(ee, np.einsum("ij,ij->i", e1, e1)))
    a0 = np.arctan2(e0[:, 1], e0[:, 0])
    sweep = _wrap(np.arctan2(e1[:, 1], e1[:, 0]) - a0)
    start = np.where(sweep >= 0.0, a0, a0 + sweep)
    # an edge through the axis is seen at every angle
    sweep = np.where(lo > 1e-12 * np.maximum(hi, 1.0), np.abs(sweep), 2.0 * np.pi)
    return _EdgeTable(e0, d, dd, ed, ee, lo, hi, start, sweep, edges.e_pose)


def _near_pairs(radius: np.ndarray, own: np.ndarray, r_pose: np.ndarray, edges: _EdgeTable,
                reach: float, max_pairs: int):
    """Chunks (rows, cols) of the vertex/edge pairs that can touch within ``reach`` (rad).

    Pairs of the same pose whose edge's radial extent holds the vertex's radius and,
    when ``reach`` is finite, whose edge's angular extent comes within ``reach`` of the
    vertex's angle ``own``; every such pair is there. Without a dense table: vertices
    are sorted by (pose, angle bin, radius); each edge looks up, in every bin its
    angular extent (widened by ``reach``) touches, the contiguous run of vertices whose
    radius lies in its radial extent. Chunks hold at most about ``max_pairs`` pairs, so
    memory stays bounded whatever the outline sizes.
    """
    if len(radius) == 0 or len(edges.lo) == 0:
        return
    two_pi = 2.0 * np.pi
    count = len(edges.lo)
    if np.isfinite(reach):
        bins = int(np.ceil(two_pi / (2.0 * reach)))
        width = two_pi / bins
        lo_angle = np.mod(edges.start - reach - 1e-9, two_pi)
        b0 = np.floor(lo_angle / width).astype(np.intp)
        b1 = np.floor((lo_angle + edges.sweep + 2.0 * reach + 2e-9) / width).astype(np.intp)
        span = np.minimum(b1 - b0 + 1, bins)
        v_bin = np.floor(np.mod(own, two_pi) / width).astype(np.intp) % bins
    else:
        bins, b0, span = 1, np.zeros(count, dtype=np.intp), np.ones(count, dtype=np.intp)
        v_bin = np.zeros(len(radius), dtype=np.intp)
    stride = 2.0 * max(float(edges.hi.max()), float(radius.max())) + 1.0
    tol = 1e-9 * stride
    key = (r_pose * bins + v_bin) * stride + radius
    order = np.argsort(key)
    key_sorted = key[order]
    del key
    q_edge, k = _expand(np.zeros(count, dtype=np.intp), span, np.arange(int(span.max())))
    base = (edges.pose[q_edge] * bins + (b0[q_edge] + k) % bins) * stride
    del k
    first = np.searchsorted(key_sorted, base + (edges.lo[q_edge] - tol), side="left")
    counts = np.searchsorted(key_sorted, base + (edges.hi[q_edge] + tol), side="right") - first
    del base
    ends = np.cumsum(counts)
    slack = reach + 1e-9
    i0 = 0
    while i0 < len(counts):
        done = ends[i0 - 1] if i0 else 0
        i1 = max(int(np.searchsorted(ends, done + max_pairs, side="right")), i0 + 1)
        queries, rows = _expand(first[i0:i1], counts[i0:i1], order)
        cols = q_edge[queries + i0]
        del queries
        keep = (edges.lo[cols] <= radius[rows]) & (edges.hi[cols] >= radius[rows])
        if np.isfinite(reach):
            # the crossing lies in the edge's angular extent, within reach of the vertex
            keep &= (np.mod(own[rows] - edges.start[cols] + slack, two_pi)
                     <= edges.sweep[cols] + 2.0 * slack)
        yield rows[keep], cols[keep]
        i0 = i1


def _rotations_to_touch(v: np.ndarray, v_pose: np.ndarray, edges: _EdgeTable, sign: float,
                        reach: float):
    """Smallest wheel rotations (rad) bringing each vertex onto an edge: (backwards, forwards).

    ``v`` relative to the wheel axis; a vertex at radius rho meets an edge where the
    circle of radius rho crosses it. ``sign`` = +1 for pinion vertices (they move
    +delta relative to the wheel when the wheel turns back by delta), -1 for wheel
    vertices. Only rotations up to ``reach`` are looked for (all of them when inf);
    inf where none is met.
    """
    back = np.full(len(v), np.inf)
    fwd = np.full(len(v), np.inf)
    radius = np.hypot(v[:, 0], v[:, 1])
    own = np.arctan2(v[:, 1], v[:, 0])
    for rows, cols in _near_pairs(radius, own, v_pose, edges, reach, MAX_PAIRS):
        a, b, c = edges.dd[cols], edges.ed[cols], edges.ee[cols] - radius[rows] ** 2
        disc = np.sqrt(np.maximum(b * b - a * c, 0.0))
        e0, d = edges.e0[cols], edges.d[cols]
        for root in (-1.0, 1.0):
            t = (-b + root * disc) / np.where(a > 0, a, 1.0)
            ok = (t >= 0.0) & (t <= 1.0) & (a > 0)
            t, r = t[ok], rows[ok]
            angle = np.arctan2(e0[ok, 1] + t * d[ok, 1], e0[ok, 0] + t * d[ok, 0])
            delta = _wrap(sign * (angle - own[r]))  # > 0: met turning the wheel backwards
            np.minimum.at(back, r[delta >= 0], delta[delta >= 0])
            np.minimum.at(fwd, r[delta <= 0], -delta[delta <= 0])
    if np.isfinite(reach):
        back[back > reach] = np.inf
        fwd[fwd > reach] = np.inf
    return back, fwd


def _gaps(back: np.ndarray, fwd: np.ndarray, inside: np.ndarray):
    """Signed drive and coast gaps (rad) of vertices from their rotations to touch.

    A vertex outside has the rotation to its first touch in each direction; a vertex
    inside counts as penetrating the flank it is nearer to (smaller exit rotation): on
    the drive side that gives a negative drive gap, on the coast side a negative coast
    gap.
    """
    # drive-side penetration is the one the wheel clears by turning forwards
    drive = np.where(inside, np.where(fwd <= back, -fwd, np.inf), back)
    coast = np.where(inside, np.where(back < fwd, -back, np.inf), fwd)
    return drive, coast


def _overlap_area(p_world: np.ndarray, w_world: np.ndarray, box) -> np.ndarray:
    """Areas (mm^2) where the posed outlines (poses, N, 2) overlap inside the mesh window."""
    import shapely

    xlo, xhi, half, _ = box
    a = shapely.clip_by_rect(shapely.polygons(p_world), xlo, -half, xhi, half)
    b = shapely.clip_by_rect(shapely.polygons(w_world), xlo, -half, xhi, half)
    return shapely.area(shapely.intersection(a, b))


#: Body-angle bins of the radial bands used to skip vertices far from the other outline.
BAND_BINS = 2048


def _radial_band(outline: _Sorted, half_width: float):
    """Least and greatest distance (mm) from its axis of the outline's edges seen within
    ``half_width`` rad of each of BAND_BINS body-angle bins: (rmin, rmax), inf / -inf where
    no edge is that near. None when the bins would not narrow anything down."""
    if not half_width < 0.5:
        return None
    points = outline.points
    nxt = np.roll(points, -1, axis=0)
    d = nxt - points
    dd = np.einsum("ij,ij->i", d, d)
    t_near = np.clip(-np.einsum("ij,ij->i", points, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    lo = np.hypot(points[:, 0] + t_near * d[:, 0], points[:, 1] + t_near * d[:, 1])
    hi = np.maximum(np.hypot(points[:, 0], points[:, 1]), np.hypot(nxt[:, 0], nxt[:, 1]))
    a0 = np.arctan2(points[:, 1], points[:, 0])
    sweep = _wrap(np.arctan2(nxt[:, 1], nxt[:, 0]) - a0)
    start = np.where(sweep >= 0.0, a0, a0 + sweep)
    sweep = np.where(lo > 1e-9 * np.maximum(hi, 1.0), np.abs(sweep), 2.0 * np.pi)
    width = 2.0 * np.pi / BAND_BINS
    grow = half_width + 1e-6
    b0 = np.floor(np.mod(start - grow, 2.0 * np.pi) / width).astype(np.intp)
    count = np.minimum(np.floor((sweep + 2.0 * grow) / width).astype(np.intp) + 2, BAND_BINS)
    owner, k = _expand(np.zeros(len(points), dtype=np.intp), count, np.arange(int(count.max())))
    cell = (b0[owner] + k) % BAND_BINS
    rmin = np.full(BAND_BINS, np.inf)
    rmax = np.full(BAND_BINS, -np.inf)
    np.minimum.at(rmin, cell, lo[owner])
    np.maximum.at(rmax, cell, hi[owner])
    return rmin, rmax


def _band_at(body: np.ndarray, band):
    """(distance from the axis, rmin, rmax) of the band at points (own frame of the band's
    outline, mm)."""
    rmin, rmax = band
    r = np.hypot(body[:, 0], body[:, 1])
    cell = (np.floor(np.mod(np.arctan2(body[:, 1], body[:, 0]), 2.0 * np.pi)
                     / (2.0 * np.pi / BAND_BINS)).astype(np.intp)) % BAND_BINS
    return r, rmin[cell], rmax[cell]


def _near_band(body: np.ndarray, slack: np.ndarray | float, band) -> np.ndarray:
    """Points (own frame of the band's outline, mm) within ``slack`` mm of its radial band."""
    if band is None:
        return np.ones(len(body), dtype=bool)
    r, rmin, rmax = _band_at(body, band)
    return (r + slack >= rmin) & (r - slack <= rmax)


def _contains(polygon, body: np.ndarray, band) -> np.ndarray:
    """Points (own frame of the polygon, mm) inside it. A point farther from the axis than
    every edge seen at its angle is outside (the ray out from the axis through it meets
    no edge beyond it), so only the others go to shapely."""
    import shapely

    maybe = np.ones(len(body), dtype=bool)
    if band is not None:
        r, _, rmax = _band_at(body, band)
        maybe = r <= rmax + 1e-9
    inside = np.zeros(len(body), dtype=bool)
    inside[maybe] = shapely.contains_xy(polygon, body[maybe, 0], body[maybe, 1])
    return inside


@dataclass(frozen=True)
class _Pair:
    """Both outlines prepared for the check, the mesh window and its angular sectors."""

    pinion: _Sorted
    wheel: _Sorted
    pinion_body: object
    wheel_body: object
    centre: np.ndarray
    box: tuple
    pinion_sector: tuple | None
    wheel_sector: tuple | None
    wheel_band: tuple | None    # radial band of the wheel seen by pinion vertices within REACH
    pinion_band: tuple | None   # radial band of the pinion seen by wheel vertices within REACH


def _prepare(pinion: np.ndarray, wheel: np.ndarray, distance: float, box) -> _Pair:
    import shapely

    long_edge = 0.1 * box[2]
    p, w = _sorted_outline(pinion, long_edge), _sorted_outline(wheel, long_edge)
    centre = np.array([distance, 0.0])
    pinion_body, wheel_body = shapely.Polygon(pinion), shapely.Polygon(wheel)
    shapely.prepare(pinion_body)
    shapely.prepare(wheel_body)
    # A wheel vertex turning by REACH about the wheel axis moves at most `move` mm, and
    # a point of a wheel edge lies within half its length of the edge's midpoint; seen
    # from the pinion axis (at least `near` mm away in the window) that is an angle of
    # asin(reach / near) at most. Likewise a pinion edge's points, from the wheel axis.
    move = REACH * float(np.hypot(wheel[:, 0], wheel[:, 1]).max()) + 0.5 * w.e_length
    near = box[0] - box[3] - w.e_length
    pinion_band = (_radial_band(p, float(np.arcsin(move / near)))
                   if 0.0 < move < 0.5 * near else None)
    near_w = distance - box[1] - box[3] - p.e_length
    wheel_band = (_radial_band(w, REACH + float(np.arcsin(0.5 * p.e_length / near_w)))
                  if 0.5 * p.e_length < 0.5 * near_w else None)
    return _Pair(p, w, pinion_body, wheel_body, centre, box,
                 _sector(box, np.zeros(2), p.e_length), _sector(box, centre, w.e_length),
                 wheel_band, pinion_band)


def _contacts(pair: _Pair, theta: np.ndarray, phi: np.ndarray):
    """Backward/forward wheel rotations to contact (rad) and interference for a batch of poses."""
    import shapely

    poses, centre, box = len(theta), pair.centre, pair.box
    pw = _window(pair.pinion, -theta, None, pair.pinion_sector, theta, box)
    ww = _window(pair.wheel, np.pi + phi, centre, pair.wheel_sector, -np.pi - phi, box)
    # vertices inside the other outline, tested in that outline's own frame
    pv_body = _rotate(pw.v - centre, -(np.pi + phi[pw.v_pose]))
    wv_body = _rotate(ww.v, theta[ww.v_pose])
    p_inside = _contains(pair.wheel_body, pv_body, pair.wheel_band)
    w_inside = _contains(pair.pinion_body, wv_body, pair.pinion_band)
    pw = _Window(pw.e_pose, pw.e0 - centre, pw.e1 - centre, pw.v_pose, pw.v - centre)
    ww = _Window(ww.e_pose, ww.e0 - centre, ww.e1 - centre, ww.v_pose, ww.v - centre)
    # vertices and edges that cannot meet the other outline within REACH (radial bands)
    rho_w = np.hypot(ww.v[:, 0], ww.v[:, 1])
    p_near = _near_band(pv_body, 1e-9, pair.wheel_band)
    w_near = _near_band(wv_body, REACH * rho_w + 1e-9, pair.pinion_band)
    half = lambda e: 0.5 * np.hypot(*(e.e1 - e.e0).T)  # noqa: E731
    mid = lambda e: 0.5 * (e.e0 + e.e1)  # noqa: E731
    # wheel edges: crossed by a pinion vertex that turned at most REACH about the wheel axis
    we_near = _near_band(_rotate(mid(ww) + centre, theta[ww.e_pose]),
                         REACH * np.sqrt(np.maximum(np.einsum("ij,ij->i", ww.e0, ww.e0),
                                                    np.einsum("ij,ij->i", ww.e1, ww.e1)))
                         + half(ww) + 1e-9, pair.pinion_band)
    # pinion edges: crossed by a wheel vertex at the same radius and within REACH of angle
    pe_near = _near_band(_rotate(mid(pw), -(np.pi + phi[pw.e_pose])), half(pw) + 1e-9,
                         pair.wheel_band)
    # the bands' angular margins allow for short edges only: never skip a longer one
    we_near |= half(ww) > 0.5 * pair.wheel.e_length
    pe_near |= half(pw) > 0.5 * pair.pinion.e_length
    sides = ((pw, p_inside, p_near, ww, we_near, 1.0),
             (ww, w_inside, w_near, pw, pe_near, -1.0))

    def pose_minima(reach, active):
        back, fwd = np.full(poses, np.inf), np.full(poses, np.inf)
        unsettled = np.zeros(poses, dtype=bool)
        for verts, inside, near, edges, e_near, sign in sides:
            sel = active[verts.v_pose]
            esel = active[edges.e_pose]
            if np.isfinite(reach):
                # a far vertex inside the other outline has no exit within reach
                unsettled[verts.v_pose[sel & ~near & inside]] = True
                sel &= near
                esel &= e_near
            table = _edge_table(_Window(edges.e_pose[esel], edges.e0[esel], edges.e1[esel],
                                        edges.v_pose, edges.v))
            v_back, v_fwd = _rotations_to_touch(verts.v[sel], verts.v_pose[sel], table, sign, reach)
            drive, coast = _gaps(v_back, v_fwd, inside[sel])
            np.minimum.at(back, verts.v_pose[sel], drive)
            np.minimum.at(fwd, verts.v_pose[sel], coast)
            lost = inside[sel] & np.isinf(v_back) & np.isinf(v_fwd)
            unsettled[verts.v_pose[sel][lost]] = True
        return back, fwd, unsettled

    # first only rotations within REACH: exact wherever a contact lies that close; the
    # other poses again without the limit
    back, fwd, unsettled = pose_minima(REACH, np.ones(poses, dtype=bool))
    redo = unsettled | ~(back <= REACH) | ~(fwd <= REACH)
    if redo.any():
        back_all, fwd_all, _ = pose_minima(np.inf, redo)
        back[redo], fwd[redo] = back_all[redo], fwd_all[redo]
    interference = np.zeros(poses, dtype=bool)
    interference[pw.v_pose[p_inside]] = True
    interference[ww.v_pose[w_inside]] = True
    area = np.zeros(poses)
    depth = np.zeros(poses)
    if interference.any():
        p_world = _rotate(pair.pinion.points[None, :, :], -theta[interference][:, None])
        w_world = _rotate(pair.wheel.points[None, :, :], np.pi + phi[interference][:, None]) + centre
        area[interference] = _overlap_area(p_world, w_world, box)
        for verts, inside, edges in ((pw, p_inside, ww), (ww, w_inside, pw)):
            np.maximum.at(depth, verts.v_pose[inside],
                          _depth(verts.v[inside], verts.v_pose[inside], edges))
    return back, fwd, interference, area, depth


def _depth(points: np.ndarray, pose: np.ndarray, edges: _Window) -> np.ndarray:
    """Distance (mm) of each point to the nearest window edge of the same pose."""
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
        i1 = max(int(np.searchsorted(ends, done + MAX_PAIRS, side="right")), i0 + 1)
        rows, cols = _expand(first[i0:i1], counts[i0:i1], np.arange(len(edges.e_pose)))
        rows += i0
        a, b, q = edges.e0[cols], edges.e1[cols], points[rows]
        d = b - a
        t = np.clip(np.einsum("ij,ij->i", q - a, d)
                    / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
        dist = np.hypot(*(a + t[:, None] * d - q).T)
        np.minimum.at(best, rows, dist)
        i0 = i1
    return best


def _periodic_derivative(theta: np.ndarray, values: np.ndarray, rise: float, period: float):
    """Central-difference d(values)/d(theta) over a period with values(theta + P) = values + rise."""
    ext_t = np.concatenate([[theta[-1] - period], theta, [theta[0] + period]])
    ext_v = np.concatenate([[values[-1] - rise], values, [values[0] + rise]])
    return np.gradient(ext_v, ext_t)[1:-1]


def mesh_window(pinion: np.ndarray, wheel: np.ndarray, distance: float,
                half_height: float | None = None) -> tuple[float, float, float, float]:
    """The mesh window (x_lo, x_hi, half height, margin) in mm, world frame.

    Contacts are searched for at the vertices inside the box; edges are taken from the
    box widened by the margin.
    """
    rp = float(np.hypot(pinion[:, 0], pinion[:, 1]).max())
    rw = float(np.hypot(wheel[:, 0], wheel[:, 1]).max())
    if half_height is None:
        half_height = WINDOW_FRACTION * min(rp, rw)
    # contacts lie between the wheel's tips (x = D - rw) and the pinion's (x = rp); the
    # margin keeps the outline round an overlapping vertex in view for its depth
    return distance - rw - 1e-6, rp + 1e-6, float(half_height), 0.25 * float(half_height)


def check_meshing(pinion: np.ndarray, wheel: np.ndarray, transmission: Transmission,
                  distance: float, samples: int = DEFAULT_SAMPLES,
                  window: float | None = None, start: float = 0.0,
                  progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Run the meshing check (SPEC §10) over one period of ``transmission``.

    ``pinion``, ``wheel``: closed outlines (N, 2) in mm in their own frames (any
    orientation). ``distance``: installed centre distance (mm). ``samples``: poses
    over the period, from ``start`` (rad). ``window``: half-height (mm) of the mesh
    window round the line of centres (default: 0.25 x the smaller outer radius).
    ``progress(done, total)`` is called after every batch of poses.
    """
    pinion = np.asarray(pinion, dtype=float)
    wheel = np.asarray(wheel, dtype=float)
    period = float(transmission.period)
    theta = start + period * np.arange(samples) / samples
    phi_law = np.asarray(transmission.driven_angle(theta), dtype=float)
    rise = float(transmission.driven_angle(np.array([start + period]))[0]
                 - transmission.driven_angle(np.array([start]))[0])
    box = mesh_window(pinion, wheel, distance, window)
    batch = max(1, min(BATCH, BATCH_POINTS // (len(pinion) + len(wheel))))

    delta_back = np.empty(samples)
    delta_fwd = np.empty(samples)
    interference = np.zeros(samples, dtype=bool)
    area = np.zeros(samples)
    penetration = np.zeros(samples)
    slices = [slice(lo, min(lo + batch, samples)) for lo in range(0, samples, batch)]
    # batches are independent and numpy / shapely release the GIL in their loops: threads
    # share the work between cores; each batch fills its own slice, so the result is the same.
    # Each thread prepares its own outlines (a prepared GEOS geometry is not thread-safe).
    own = threading.local()

    def batch_contacts(sl):
        if not hasattr(own, "pair"):
            own.pair = _prepare(pinion, wheel, distance, box)
        return _contacts(own.pair, theta[sl], phi_law[sl])

    for sl, result in zip(slices, thread_map(batch_contacts, slices)):
        delta_back[sl], delta_fwd[sl], interference[sl], area[sl], penetration[sl] = result
        if progress is not None:
            progress(sl.stop, samples)
    delta_back[~np.isfinite(delta_back)] = np.nan
    delta_fwd[~np.isfinite(delta_fwd)] = np.nan

    phi_drive = phi_law - delta_back
    phi_coast = phi_law + delta_fwd
    factor = transmission.hub_speed_factor
    f_drive = np.ones(samples) if factor is None else np.asarray(factor(phi_drive), dtype=float)
    f_law = np.ones(samples) if factor is None else np.asarray(factor(phi_law), dtype=float)
    hub_speed = f_drive * _periodic_derivative(theta, phi_drive, rise, period)
    law_rate = _periodic_derivative(theta, phi_law, rise, period)
    hub_speed_law = f_law * law_rate
    # instantaneous centre on the line of centres: r_w / r_p = dtheta/dphi, r_w + r_p = D
    pitch_radius = distance / (1.0 + law_rate)
    return MeshingReport(theta, phi_law, phi_drive, phi_coast, interference, area, penetration,
                         hub_speed, hub_speed_law, pitch_radius, float(distance), period)

