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

from dataclasses import dataclass
from typing import Callable

import numpy as np

#: Default poses per period: 64 per wheel tooth for the 24 teeth of the source
#: design's period (see ``benchmarks/meshcheck.py`` for the convergence study).
DEFAULT_SAMPLES = 1536
#: Default half-height of the mesh window as a fraction of the smaller gear's outer radius.
WINDOW_FRACTION = 0.25
#: Poses handled together in one vectorised batch.
BATCH = 64


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

    Flat arrays: every edge (start ``e0``, end ``e1``) and vertex ``v`` carries the
    index of its pose in ``e_pose`` / ``v_pose``; ``v_body`` is the vertex's index in
    the outline.
    """

    e_pose: np.ndarray
    e0: np.ndarray
    e1: np.ndarray
    v_pose: np.ndarray
    v: np.ndarray


def _window(world: np.ndarray, box: tuple[float, float, float, float]) -> _Window:
    """Window parts of a closed outline posed as ``world`` (poses, N, 2).

    ``box`` = (x_lo, x_hi, half height, margin). Vertices: those inside the box.
    Edges: those whose bounding box meets the box widened by ``margin`` on every side,
    so every edge through the box is there, however long, and the outline round a
    vertex is in view within ``margin``.
    """
    xlo, xhi, half, margin = box
    x, y = world[..., 0], world[..., 1]
    vertex = (x >= xlo) & (x <= xhi) & (np.abs(y) <= half)
    x1, y1 = np.roll(x, -1, axis=1), np.roll(y, -1, axis=1)  # edge i: vertex i -> i+1
    edge = ((np.minimum(x, x1) <= xhi + margin) & (np.maximum(x, x1) >= xlo - margin)
            & (np.minimum(y, y1) <= half + margin) & (np.maximum(y, y1) >= -half - margin))
    e_pose, e_idx = np.nonzero(edge)
    v_pose, v_idx = np.nonzero(vertex)
    n = world.shape[1]
    return _Window(e_pose, world[e_pose, e_idx], world[e_pose, (e_idx + 1) % n],
                   v_pose, world[v_pose, v_idx])


def _radial_candidates(radius, r_pose, lo, hi, e_pose):
    """Pairs (i, j) of the same pose with lo[j] <= radius[i] <= hi[j], without a dense table.

    Every edge's radial range is at most ``max(hi - lo)`` long, so the candidates of a
    radius are a contiguous run of the edges sorted by (pose, lo).
    """
    if len(radius) == 0 or len(lo) == 0:
        return np.empty(0, dtype=np.intp), np.empty(0, dtype=np.intp)
    span = float(np.max(hi - lo))
    stride = 2.0 * (max(float(hi.max()), float(radius.max())) + span) + 1.0
    key = e_pose * stride + lo
    order = np.argsort(key)
    key_sorted = key[order]
    r_key = r_pose * stride + radius
    first = np.searchsorted(key_sorted, r_key - span - 1e-9 * stride, side="left")
    last = np.searchsorted(key_sorted, r_key + 1e-9 * stride, side="right")
    counts = last - first
    rows = np.repeat(np.arange(len(radius)), counts)
    offsets = np.arange(len(rows)) - np.repeat(np.cumsum(counts) - counts, counts)
    cols = order[first[rows] + offsets]
    keep = ((e_pose[cols] == r_pose[rows]) & (lo[cols] <= radius[rows])
            & (hi[cols] >= radius[rows]))
    return rows[keep], cols[keep]


def _circle_edge_angles(radius, r_pose, e0, e1, e_pose):
    """Angles (about the origin) where circles of ``radius`` cross edges e0->e1 of their pose.

    Returns (row index into radius, angle rad) for every crossing, both roots.
    """
    d = e1 - e0
    dd = np.einsum("ij,ij->i", d, d)
    ed = np.einsum("ij,ij->i", e0, d)
    ee = np.einsum("ij,ij->i", e0, e0)
    t_near = np.clip(-ed / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    lo = np.hypot(e0[:, 0] + t_near * d[:, 0], e0[:, 1] + t_near * d[:, 1])
    hi = np.sqrt(np.maximum(ee, np.einsum("ij,ij->i", e1, e1)))
    rows, cols = _radial_candidates(radius, r_pose, lo, hi, e_pose)
    a, b, c = dd[cols], ed[cols], ee[cols] - radius[rows] ** 2
    disc = np.sqrt(np.maximum(b * b - a * c, 0.0))
    keep_rows, angles = [], []
    for sign in (-1.0, 1.0):
        t = (-b + sign * disc) / np.where(a > 0, a, 1.0)
        ok = (t >= 0.0) & (t <= 1.0) & (a > 0)
        px = e0[cols, 0] + t * d[cols, 0]
        py = e0[cols, 1] + t * d[cols, 1]
        keep_rows.append(rows[ok])
        angles.append(np.arctan2(py, px)[ok])
    return np.concatenate(keep_rows), np.concatenate(angles)


def _vertex_gaps(vertices: _Window, inside: np.ndarray, edges: _Window, sign: float):
    """Signed drive and coast gaps (rad of wheel rotation) of each vertex to the other outline.

    ``vertices`` of one outline and ``edges`` of the other, relative to the wheel
    axis; ``inside``: vertex lies inside the other outline. ``sign`` = +1 for pinion
    vertices (they move +delta relative to the wheel when the wheel turns back by
    delta), -1 for wheel vertices. A vertex outside has the rotation to its first touch
    in each direction; a vertex inside counts as penetrating the flank it is nearer to
    (smaller exit rotation): on the drive side that gives a negative drive gap, on the
    coast side a negative coast gap. inf where nothing is met in the window.
    """
    v = vertices.v
    rows, edge_angle = _circle_edge_angles(np.hypot(v[:, 0], v[:, 1]), vertices.v_pose,
                                           edges.e0, edges.e1, edges.e_pose)
    own = np.arctan2(v[rows, 1], v[rows, 0])
    delta = _wrap(sign * (edge_angle - own))  # > 0: met turning the wheel backwards
    back = np.full(len(v), np.inf)
    fwd = np.full(len(v), np.inf)
    np.minimum.at(back, rows[delta >= 0], delta[delta >= 0])
    np.minimum.at(fwd, rows[delta <= 0], -delta[delta <= 0])
    # a vertex inside exits at `back` (wheel backwards) or `fwd`; drive-side penetration
    # is the one the wheel clears by turning forwards
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


def _contacts(pinion, wheel, pinion_body, wheel_body, theta, phi, centre, box):
    """Backward/forward wheel rotations to contact (rad) and interference for a batch of poses."""
    import shapely

    poses = len(theta)
    p_world = _rotate(pinion[None, :, :], -theta[:, None])
    w_world = _rotate(wheel[None, :, :], np.pi + phi[:, None]) + centre
    pw = _window(p_world, box)
    ww = _window(w_world, box)
    # vertices inside the other outline, tested in that outline's own frame
    pv_body = _rotate(pw.v - centre, -(np.pi + phi[pw.v_pose]))
    wv_body = _rotate(ww.v, theta[ww.v_pose])
    p_inside = shapely.contains_xy(wheel_body, pv_body[:, 0], pv_body[:, 1])
    w_inside = shapely.contains_xy(pinion_body, wv_body[:, 0], wv_body[:, 1])
    pw = _Window(pw.e_pose, pw.e0 - centre, pw.e1 - centre, pw.v_pose, pw.v - centre)
    ww = _Window(ww.e_pose, ww.e0 - centre, ww.e1 - centre, ww.v_pose, ww.v - centre)
    back = np.full(poses, np.inf)
    fwd = np.full(poses, np.inf)
    for verts, inside, edges, sign in ((pw, p_inside, ww, 1.0), (ww, w_inside, pw, -1.0)):
        drive, coast = _vertex_gaps(verts, inside, edges, sign)
        np.minimum.at(back, verts.v_pose, drive)
        np.minimum.at(fwd, verts.v_pose, coast)
    interference = np.zeros(poses, dtype=bool)
    interference[pw.v_pose[p_inside]] = True
    interference[ww.v_pose[w_inside]] = True
    area = np.zeros(poses)
    depth = np.zeros(poses)
    if interference.any():
        area[interference] = _overlap_area(p_world[interference], w_world[interference], box)
        for verts, inside, edges in ((pw, p_inside, ww), (ww, w_inside, pw)):
            np.maximum.at(depth, verts.v_pose[inside],
                          _depth(verts.v[inside], verts.v_pose[inside], edges))
    return back, fwd, interference, area, depth


def _depth(points: np.ndarray, pose: np.ndarray, edges: _Window) -> np.ndarray:
    """Distance (mm) of each point to the nearest window edge of the same pose."""
    if len(points) == 0:
        return np.zeros(0)
    # edges come grouped by pose (np.nonzero order): each point meets its pose's run
    first = np.searchsorted(edges.e_pose, pose, side="left")
    last = np.searchsorted(edges.e_pose, pose, side="right")
    counts = last - first
    rows = np.repeat(np.arange(len(points)), counts)
    cols = first[rows] + np.arange(len(rows)) - np.repeat(np.cumsum(counts) - counts, counts)
    a, b, q = edges.e0[cols], edges.e1[cols], points[rows]
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", q - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300),
                0.0, 1.0)
    dist = np.hypot(*(a + t[:, None] * d - q).T)
    best = np.full(len(points), np.inf)
    np.minimum.at(best, rows, dist)
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
    import shapely

    pinion = np.asarray(pinion, dtype=float)
    wheel = np.asarray(wheel, dtype=float)
    period = float(transmission.period)
    theta = start + period * np.arange(samples) / samples
    phi_law = np.asarray(transmission.driven_angle(theta), dtype=float)
    rise = float(transmission.driven_angle(np.array([start + period]))[0]
                 - transmission.driven_angle(np.array([start]))[0])
    box = mesh_window(pinion, wheel, distance, window)
    centre = np.array([distance, 0.0])
    pinion_body = shapely.Polygon(pinion)
    wheel_body = shapely.Polygon(wheel)
    shapely.prepare(pinion_body)
    shapely.prepare(wheel_body)

    delta_back = np.empty(samples)
    delta_fwd = np.empty(samples)
    interference = np.zeros(samples, dtype=bool)
    area = np.zeros(samples)
    penetration = np.zeros(samples)
    for lo in range(0, samples, BATCH):
        sl = slice(lo, min(lo + BATCH, samples))
        delta_back[sl], delta_fwd[sl], interference[sl], area[sl], penetration[sl] = _contacts(
            pinion, wheel, pinion_body, wheel_body, theta[sl], phi_law[sl], centre, box)
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

