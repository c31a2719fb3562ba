"""Figures of merit of one flank side (SPEC §10): F'i, f'i, band-limited hub speed ripple.

Measured the way a single-flank gear tester measures (ISO 1328-1 tangential composite
deviations): the transmission error of a flank side is expressed as a position error
along the wheel's pitch curve, ``e = r_H (phi_contact - phi_law)``, mean removed.
Unlike a pointwise finite difference of a faceted outline, these figures converge as
the number of poses grows. Inputs sampled at equal pinion-angle steps over one period.
Angles in rad, lengths in mm, ``e`` in micrometres.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

#: Harmonics of the tooth frequency the hub speed's TE keeps (SPEC §10).
BAND_HARMONICS = 3


@dataclass(frozen=True)
class Track:
    """What both flank sides share, per pose over one period of ``period`` rad of pinion.

    ``phi_law``: the law's wheel angle (rad); ``law_rate``: its dphi/dtheta;
    ``pitch_radius``: the wheel's pitch radius (mm); ``arc``: arc length along the wheel
    pitch curve from the first pose (mm), ``arc_total``: over the whole period (mm);
    ``pitch``: one tooth pitch (mm); ``harmonics``: Fourier harmonics of the period kept
    in the TE (3 tooth harmonics); ``factor(phi)``: hub speed per unit wheel speed
    (ones for a law with no mechanism).
    """

    period: float
    phi_law: np.ndarray
    law_rate: np.ndarray
    pitch_radius: np.ndarray
    arc: np.ndarray
    arc_total: float
    pitch: float
    harmonics: int
    factor: Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class FlankFigures:
    """The figures of one flank side.

    ``error_um``: e(theta) per pose (um, mean removed; NaN where no contact was found).
    ``total_um``: F'i, peak-to-peak of e over the period. ``tooth_um``: f'i, the largest
    peak-to-peak of e inside any window one tooth pitch long (arc length along the wheel
    pitch curve). ``ripple``: hub speed ripple (fraction) from the TE band-limited to
    ``BAND_HARMONICS`` tooth harmonics. ``max_step_um``: largest pose-to-pose change of e.
    """

    error_um: np.ndarray
    total_um: float
    tooth_um: float
    ripple: float
    max_step_um: float


def flank_figures(te: np.ndarray, track: Track, between: tuple | None = None) -> FlankFigures:
    """The figures of a flank side whose TE (rad at the wheel, per pose) is ``te``.

    ``between`` = (TE rad, pitch radius mm, arc mm) at poses measured between the equal
    steps (gears.meshing.peaks): F'i and f'i take them too (NaN ones left out); the ripple
    and the largest step are of the equal steps.
    """
    nan = float("nan")
    if not np.all(np.isfinite(te)):
        return FlankFigures(np.full(len(te), nan), nan, nan, nan, nan)
    # the mean is removed from the angle: a constant angular offset (backlash, thinning)
    # times the varying pitch radius is no position error
    mean_te = float(np.mean(te))
    e = 1000.0 * track.pitch_radius * (te - mean_te)
    low, rate = band_limited(te, track.harmonics, track.period)
    v = np.asarray(track.factor(track.phi_law + low), dtype=float) * (track.law_rate + rate)
    mean = float(np.mean(v))
    every, arc = e, track.arc
    if between is not None:
        te_b, radius_b, arc_b = between
        e_b = 1000.0 * radius_b * (te_b - mean_te)
        kept = np.isfinite(e_b)
        every, arc = np.concatenate([e, e_b[kept]]), np.concatenate([track.arc, arc_b[kept]])
        order = np.argsort(arc, kind="stable")
        every, arc = every[order], arc[order]
    return FlankFigures(e, float(np.ptp(every)),
                        window_peak_to_peak(every, arc, track.arc_total, track.pitch),
                        float(np.ptp(v)) / mean if mean > 0 else nan,
                        float(np.max(np.abs(np.diff(np.append(e, e[:1]))))))


def band_limited(values: np.ndarray, harmonics: int, period: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Periodic Fourier series of ``values`` (equal steps over one period of ``period``
    rad) keeping the harmonics 0..``harmonics``: (values, their derivative per rad)."""
    n = len(values)
    spectrum = np.fft.rfft(values)
    spectrum[harmonics + 1:] = 0.0
    omega = 2.0 * np.pi / period * np.arange(len(spectrum))
    return np.fft.irfft(spectrum, n), np.fft.irfft(1j * omega * spectrum, n)


def pitch_windows(arc: np.ndarray, total: float, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Per pose, the poses of the window ``length`` long (in ``arc``, increasing over one period
    of ``total``, wrapping round its end) that starts there: (index (n, width) into the values
    repeated twice, inside mask)."""
    n = len(arc)
    ends = np.searchsorted(np.concatenate([arc, arc + total]), arc + length, side="right")
    width = max(1, int((ends - np.arange(n)).max()))
    index = np.minimum(np.arange(n)[:, None] + np.arange(width)[None, :], 2 * n - 1)
    return index, index < ends[:, None]


def window_peak_to_peak(values: np.ndarray, arc: np.ndarray, total: float, length: float) -> float:
    """Largest peak-to-peak of periodic ``values`` inside any window ``length`` long in ``arc``.

    ``arc`` (same length as ``values``) increases over one period of ``total``; the
    window wraps round the period's end.
    """
    if len(values) < 2 or length >= total:
        return float(np.ptp(values))
    index, inside = pitch_windows(arc, total, length)
    window = np.concatenate([values, values])[index]
    hi = np.where(inside, window, -np.inf).max(axis=1)
    lo = np.where(inside, window, np.inf).min(axis=1)
    return float(np.max(hi - lo))


def pitch_arc(phi: np.ndarray, radius: np.ndarray, rise: float) -> tuple[np.ndarray, float]:
    """Arc length (mm) along a pitch curve r(phi) sampled over one period at increasing
    ``phi`` (rad), ``radius`` mm, the period's wheel angle ``rise`` rad: ds^2 = r^2 dphi^2
    + dr^2. Returns (arc per sample from 0 at the first, the period's total)."""
    phi = np.append(phi, phi[0] + rise)
    radius = np.append(radius, radius[0])
    mid = 0.5 * (radius[1:] + radius[:-1])
    steps = np.hypot(mid * np.diff(phi), np.diff(radius))
    arc = np.concatenate([[0.0], np.cumsum(steps)])
    return arc[:-1], float(arc[-1])


def count_teeth(outline: np.ndarray, pitch_radius: Callable[[np.ndarray], np.ndarray]) -> int:
    """Teeth of a pinion outline (N, 2) mm in its own frame (the closed polygon in order).

    ``pitch_radius(angle)``: the pitch curve's radius (mm) at body angles (rad). A tooth
    is a walk along the outline from well below the pitch curve to well above it (a
    quarter of the outline's largest reach either side, so facets and undercuts that
    wander round the pitch curve do not count twice).
    """
    angle = np.mod(np.arctan2(outline[:, 1], outline[:, 0]), 2.0 * np.pi)
    height = np.hypot(outline[:, 0], outline[:, 1]) - pitch_radius(angle)
    state = np.where(height > 0.25 * height.max(), 1,
                     np.where(height < 0.25 * height.min(), -1, 0))
    state = state[state != 0]
    return int(np.count_nonzero((state == 1) & (np.roll(state, 1) == -1)))
