"""The wheel: carved by the pinion's outline moving along the exact law ("rotate and carve").

The wheel's outline is, ray by ray, the nearest crossing of the pinion's poses and
of the paths its outline points run between poses, in the wheel frame, widened by a
constant angular play. Angles in radians, lengths in mm.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from wheelstep_cli.gears.generation.envelope import PolarGrid, miter_offset, polyline_envelope
from wheelstep_cli.gears.generation.rack import RackCutter
from wheelstep_cli.gears.generation.settings import GenerationSettings
from wheelstep_cli.gears.transmission import TransmissionLaw
from wheelstep_cli.gears.threads import thread_map
from wheelstep_cli.geometry.planar import segmentize_ring


@dataclass(frozen=True)
class Carving:
    """How the pinion carves the wheel over one law period (mm, rad, counts)."""

    distance: float
    """Centre distance the pair rolls at, mm."""
    clearance: float
    """Normal dilation of the pinion outline before carving, mm."""
    poses: int
    """Pinion poses over the law period (the law's corners are added)."""
    window: float
    """Pinion outline taken into each pose: this body angle (rad) either side of the pitch point."""
    reach: float = np.inf
    """Outline segments wholly beyond this radius (mm, wheel frame) are skipped: they cannot cut."""
    play: float = 0.0
    """Angular play (rad of wheel angle) each side: the carving is widened to +-play."""
    lead: float = 0.0
    """Shift (-1..1) of the play window: +1 puts all play on the coast side."""
    path_run: int = 64
    """Poses whose outline points are followed as one path."""
    segment: float = 0.05
    """Longest piece (mm) the pinion outline is split into (its points' paths carve too)."""


def backlash_split(cutter: RackCutter, wheel_curve: np.ndarray,
                   settings: GenerationSettings) -> tuple[float, float]:
    """The wheel's share j_n/2 of the backlash as (normal clearance mm, angular play rad).

    Angular mode: a constant angular play (TE constant along the cycle) worth the share
    at the wheel's mean pitch radius, less a thin normal clearance that keeps the
    discretisation scallops from touching. Normal mode: all of it as clearance.
    """
    if settings.backlash_mode == "angular":
        clearance = min(cutter.backlash / 2.0, settings.scallop_clearance)
        mean_rh = float(np.mean(np.hypot(*wheel_curve.T)))
        play = (cutter.backlash / 2.0 - clearance) / (mean_rh * np.cos(cutter.pressure_angle))
        return clearance, play
    return cutter.backlash / 2.0, 0.0


def carve_by_pinion(law: TransmissionLaw, pinion_outline: np.ndarray, wheel_grid: PolarGrid,
                    carving: Carving) -> np.ndarray:
    """Nearest crossing per wheel ray (mm) of the pinion moving along the law (one law period).

    ``pinion_outline``: closed CCW outline (mm, pinion frame, ordered by polar angle
    overall), carved with as it is (only split into pieces of at most the carving's segment).
    Poses sample the driven angle uniformly (plus the law's corners); at each, the
    outline (dilated by the clearance) within the window of its pitch point is placed
    in the wheel frame (pinion rotated by -theta at the origin, wheel by pi + phi about
    (distance, 0)). The wheel is carved both by the outline in each pose and by the path
    of each outline point from pose to pose: the poses alone leave a scallop between the
    imprints of a sharp tooth tip, the paths alone one between neighbouring points of a
    flank. With play > 0 the carving is widened to the union over wheel turns in
    [-play, play] (shifted by the lead): a constant angular backlash, so the drive-side
    TE is constant along the cycle.
    """
    dense = segmentize_ring(pinion_outline, carving.segment)
    # outline is CCW: its right-hand normal points outward
    dilated = miter_offset(dense, carving.clearance) if carving.clearance > 0 else dense
    n_pts = len(dense)
    phi = law.phi_start + law.phi_period * (np.arange(carving.poses) + 0.5) / carving.poses
    if law.corners:
        phi = np.sort(np.append(phi, np.asarray(law.corners)))
    theta = law.pinion_angle(phi)
    start, end = _pose_windows(dense, theta, carving.window)
    width = int(np.max(end - start)) + 1
    distance, reach, path_run = carving.distance, carving.reach, carving.path_run

    def carve_run(i0: int) -> np.ndarray:
        # poses in runs of path_run (each run shares its last pose with the next): the outline
        # in each pose, and every outline point any pose of the run holds followed through it
        run = slice(i0, min(i0 + path_run, len(phi) - 1) + 1)
        idx = np.mod(start[run, None] + np.arange(width)[None, :], n_pts)
        radii = polyline_envelope(wheel_grid, in_wheel_frame(dilated[idx], theta[run], phi[run], distance),
                                  reach=reach)
        points = np.arange(int(start[run].min()), int(end[run].max()) + 1)
        path = in_wheel_frame(dilated[np.mod(points, n_pts)][None], theta[run], phi[run], distance)
        return polyline_envelope(wheel_grid, np.ascontiguousarray(path.transpose(1, 0, 2)), out=radii,
                                 reach=reach)

    radii = functools.reduce(np.minimum, thread_map(carve_run, range(0, len(phi) - 1, path_run)))
    if carving.play > 0:
        radii = widen(radii, carving.play / wheel_grid.width, carving.lead)
    return radii


def _pose_windows(dense: np.ndarray, theta: np.ndarray, window: float) -> tuple[np.ndarray, np.ndarray]:
    """Per pose, the first and one-past-last outline index within ``window`` rad of the pitch point.

    ``dense``: the outline (K, 2) mm, ordered by polar angle overall; ``theta``: pinion
    angles (rad) of the poses. A start may be negative: the window wraps past index 0.
    """
    n_pts = len(dense)
    angle = np.unwrap(np.arctan2(dense[:, 1], dense[:, 0]))
    reach_angle = np.maximum.accumulate(angle)
    local = angle[0] + np.mod(theta - angle[0], 2.0 * np.pi)
    start = np.searchsorted(reach_angle, local - window)
    end = np.searchsorted(reach_angle, local + window)
    # windows wrapping past the outline's start: look them up one turn on
    wrap = local - window < angle[0]
    start[wrap] = np.searchsorted(reach_angle, local[wrap] - window + 2.0 * np.pi) - n_pts
    return start, end


def in_wheel_frame(points: np.ndarray, theta: np.ndarray, phi: np.ndarray, distance: float) -> np.ndarray:
    """Pinion points (P or 1, K, 2; mm, pinion frame) in the wheel frame at poses (theta, phi) (P,).

    ``distance``: centre distance, mm; the wheel centre sits at (distance, 0) of the pinion's.
    """
    c, s = np.cos(-theta), np.sin(-theta)
    wx = c[:, None] * points[..., 0] - s[:, None] * points[..., 1] - distance
    wy = s[:, None] * points[..., 0] + c[:, None] * points[..., 1]
    ang = -(np.pi + phi)
    c, s = np.cos(ang), np.sin(ang)
    return np.stack([c[:, None] * wx - s[:, None] * wy, s[:, None] * wx + c[:, None] * wy], axis=-1)


def widen(radii: np.ndarray, span: float, lead: float) -> np.ndarray:
    """Periodic sliding minimum over +-span rays (fractional ends interpolated), shifted by lead*span.

    ``radii``: mm per ray; ``span``: rays (fractional). The union of the carving over all
    wheel turns in [-play, play] is, ray by ray, the smallest radius within +-play.
    """
    k = int(np.floor(span))
    if k > 0:
        padded = np.concatenate([radii[-k:], radii, radii[:k]])
        widened = np.lib.stride_tricks.sliding_window_view(padded, 2 * k + 1).min(axis=1)
    else:
        widened = radii
    n = len(radii)
    j = np.arange(n)
    for edge in (-span, span):
        lo = np.floor(j + edge).astype(np.int64)
        t = (j + edge) - lo
        widened = np.minimum(widened, (1 - t) * radii[lo % n] + t * radii[(lo + 1) % n])
    if lead:
        lo = np.floor(j + lead * span).astype(np.int64)
        t = (j + lead * span) - lo
        widened = (1 - t) * widened[lo % n] + t * widened[(lo + 1) % n]
    return widened


def notch_weight(grid: PolarGrid, notches: np.ndarray, half_width: float) -> np.ndarray:
    """Per ray of ``grid``: 1 within ``half_width`` rad of a notch (body angles ``notches``,
    rad), tapering to 0 over the last quarter of it, 0 beyond."""
    if half_width <= 0 or len(notches) == 0:
        return np.zeros(grid.count)
    off = np.abs(np.mod(grid.angles[:, None] - notches[None, :] + 0.5 * grid.period, grid.period)
                 - 0.5 * grid.period).min(axis=1)
    return np.clip((half_width - off) / (0.25 * half_width), 0.0, 1.0)


def head_on_relief(radii: np.ndarray, grid: PolarGrid, region: np.ndarray, depth: float,
                   max_angle: float) -> np.ndarray:
    """The ray map (mm per ray of ``grid``) with the surfaces that face the pinion head-on
    lowered by up to ``depth`` mm where ``region`` (per ray, 0..1) says.

    A ray whose surface normal makes an angle psi with its radius is lowered by depth x
    region x (cos psi - cos max_angle) / (1 - cos max_angle): space bottoms and tips by
    the full depth, nothing that leans more than ``max_angle`` rad (the flanks that drive
    stay as carved). Only material is removed.
    """
    if depth <= 0:
        return radii
    slope = (np.roll(radii, -1) - np.roll(radii, 1)) / (2.0 * grid.width)
    cos_psi = radii / np.hypot(radii, slope)
    floor = np.cos(max_angle)
    return radii - depth * region * np.clip((cos_psi - floor) / (1.0 - floor), 0.0, 1.0)


def level_space_ridges(radii: np.ndarray, pitch: np.ndarray) -> np.ndarray:
    """The ray map (mm per ray, periodic) with every ridge inside a tooth space cut down:
    within each run of rays below ``pitch`` (mm per ray, the wheel's pitch curve) the
    surface falls to its lowest point and rises again, no bump between.

    A bump in a space bottom faces the pinion's tip head-on and is never driven on (its
    normal runs through the axes); left where the relief lowered its sides only partly, it
    is what a pair mounted closer meets first. What falls into and rises out of the space
    without turning back stays as carved (a flank below the pitch curve that turns back by a
    few microns is cut to its running minimum); only material is removed.
    """
    below = radii < pitch
    if below.all() or not below.any():
        return radii
    shift = int(np.flatnonzero(~below)[0])   # start the walk outside a space
    r, b = np.roll(radii, -shift), np.roll(below, -shift)
    starts = np.flatnonzero(b & ~np.roll(b, 1))
    ends = np.flatnonzero(b & ~np.roll(b, -1)) + 1
    out = r.copy()
    for lo, hi in zip(starts, ends):
        space = r[lo:hi]
        # from each side the lowest point met so far: the higher of the two bounds the bottom
        out[lo:hi] = np.maximum(np.minimum.accumulate(space), np.minimum.accumulate(space[::-1])[::-1])
    return np.roll(out, shift)
