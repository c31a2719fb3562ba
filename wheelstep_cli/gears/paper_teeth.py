"""Sector-involute teeth of the source paper (SPEC §5) and the closed gear outlines.

Each sector is treated as a circular gear of its own pitch radius r_i with base
radius r_i - m (so its pressure angle varies from sector to sector). The pinion
has a tooth centred in each sector, the carrier wheel a space. Angles in
radians, lengths in mm; outlines are counter-clockwise polar (angle, radius).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from wheelstep_cli.errors import DesignError, require, rounded_down
from wheelstep_cli.gears.sectors import SectorPartition

#: Points per involute flank in the written outline (the tables keep the paper's five).
FLANK_POINTS = 12
#: Points on each tip land and root land.
LAND_POINTS = 4
#: Smallest tip land (mm) before a tooth counts as pointed.
MIN_TIP_LAND = 0.1


@dataclass(frozen=True)
class ToothForm:
    """Tooth heights and backlash: module m (mm) and normal backlash j_n (mm)."""

    module: float = 2.0
    backlash: float = 0.5

    def __post_init__(self) -> None:
        require(np.isfinite(self.module) and self.module > 0, "module", self.module, "must be > 0 mm")
        require(np.isfinite(self.backlash) and self.backlash >= 0, "backlash", self.backlash,
                "must be >= 0 mm")


@dataclass(frozen=True)
class FlankTable:
    """Flank angles (rad) of one gear, shape (sectors, points), at radii (mm) of the same shape.

    ``left`` is flank 1 (lower angle), ``right`` flank 2; for the pinion they bound
    a tooth, for the wheel a space.
    """

    left: np.ndarray
    right: np.ndarray
    radius: np.ndarray
    root_radius: np.ndarray
    tip_radius: np.ndarray
    period: float


def involute_polar_angle(base_radius, radius):
    """inv(alpha) = tan(alpha) - alpha with cos(alpha) = r_b / r (rad); 0 below the base."""
    cos_a = np.clip(np.asarray(base_radius) / np.asarray(radius), -1.0, 1.0)
    alpha = np.arccos(cos_a)
    return np.tan(alpha) - alpha


def _profile_radii(pitch_radius: np.ndarray, module: float, points: int) -> np.ndarray:
    """Radii from base (r - m) to tip (r + m), shape (sectors, points)."""
    steps = np.linspace(-1.0, 1.0, points)
    return pitch_radius[:, None] + module * steps[None, :]


def _sector_flanks(start, width, pitch_radius, form: ToothForm, points: int, sign: float,
                   period: float) -> FlankTable:
    """Flanks of a tooth (sign = +1, pinion) or a space (sign = -1, wheel) centred in each sector.

    flank 1 = start + width/4 + sign (dOmega - Omega_3 + Omega_j),
    flank 2 = start + 3 width/4 - sign (dOmega - Omega_3 + Omega_j)   (SPEC §5).
    """
    m = form.module
    base = pitch_radius - m
    radius = _profile_radii(pitch_radius, m, points)
    shift = (form.backlash / (4.0 * base))[:, None] - involute_polar_angle(base, pitch_radius)[:, None] \
        + involute_polar_angle(base[:, None], radius)
    start, width = start[:, None], width[:, None]
    left = start + width / 4.0 + sign * shift
    right = start + 3.0 * width / 4.0 - sign * shift
    return FlankTable(left, right, radius, pitch_radius - 1.25 * m, pitch_radius + m, period)


def pinion_flanks(part: SectorPartition, form: ToothForm, points: int = 5) -> FlankTable:
    """Pinion tooth flanks (SPEC §5): theta_ij (flank 1) and theta_sij (flank 2)."""
    return _sector_flanks(part.theta, part.dtheta, part.r_pinion, form, points, +1.0,
                          part.law.turns * np.pi / 2.0)


def wheel_flanks(part: SectorPartition, form: ToothForm, points: int = 5) -> FlankTable:
    """Carrier-wheel space flanks (SPEC §5): phi_ij (flank 1) and phi_sij (flank 2)."""
    return _sector_flanks(part.phi, part.dphi, part.r_wheel, form, points, -1.0, np.pi / 2.0)


def check_tooth_form(part: SectorPartition, form: ToothForm, least_module: float = 0.0,
                     backlash_per_module: float | None = None) -> None:
    """Reject modules the sectors cannot carry: negative radii, pointed or overlapping teeth;
    a refusal names the largest module that can, when that is at least ``least_module`` mm
    (the smallest a spec takes), else only the other remedies. ``backlash_per_module``: the
    backlash follows the module at this ratio (a default backlash), else it stays ``form``'s."""
    m = form.module
    smallest = float(min(part.r_pinion.min(), part.r_wheel.min()))
    require(smallest - 1.25 * m > 0, "module", m,
            f"must be < {rounded_down(smallest / 1.25, 3)} mm (root radius of the smallest sector must be > 0)")
    worst, gap = _tip_land_and_gap(part, form)
    if worst >= MIN_TIP_LAND and gap > 0:
        return
    largest = _largest_module(part, form, backlash_per_module)
    smaller = [f"--module {largest:g} or less"] if largest >= max(least_module, 0.01) else []
    if worst < MIN_TIP_LAND:
        remedies = [*smaller, "less backlash (--backlash)", "fewer teeth (--z: fewer teeth, longer pitch)"]
        error = DesignError("module", m, f"too large for the tooth pitch {part.arc:.3f} mm: teeth come "
                            f"to a point (tip land {worst:.3f} mm < {MIN_TIP_LAND} mm); use "
                            + ", ".join(remedies[:-1]) + " or " + remedies[-1])
    else:
        error = DesignError("module", m, f"too large for the tooth pitch {part.arc:.3f} mm: tooth spaces "
                            "close at the root" + (f"; use {smaller[0]}" if smaller else ""))
    if smaller:     # the one remedy with a value, for a script (--json) to apply
        error.remedy = {"module": float(f"{largest:g}")}
        error.remedies = [error.remedy]
    raise error


def _tip_land_and_gap(part: SectorPartition, form: ToothForm) -> tuple[float, float]:
    """(narrowest tip land, narrowest space bottom) in mm of both gears' teeth."""
    pinion = pinion_flanks(part, form)
    wheel = wheel_flanks(part, form)
    # Pinion tooth tip land and wheel tooth tip land (between sectors, continued periodically).
    pinion_tip = (pinion.right[:, -1] - pinion.left[:, -1]) * pinion.tip_radius
    wheel_next_left = np.append(wheel.left[1:, -1], wheel.left[0, -1] + np.pi / 2.0)
    wheel_tip = (wheel_next_left - wheel.right[:, -1]) * wheel.tip_radius
    # Pinion space bottom and wheel space bottom (at the root radius, flanks run radially).
    pinion_next_left = np.append(pinion.left[1:, 0], pinion.left[0, 0] + pinion.period)
    pinion_gap = (pinion_next_left - pinion.right[:, 0]) * pinion.root_radius
    wheel_gap = (wheel.right[:, 0] - wheel.left[:, 0]) * wheel.root_radius
    return float(min(pinion_tip.min(), wheel_tip.min())), float(min(pinion_gap.min(), wheel_gap.min()))


def _largest_module(part: SectorPartition, form: ToothForm, backlash_per_module: float | None) -> float:
    """The largest module (mm, rounded down to 0.01) below ``form``'s whose teeth keep their
    tip lands and space bottoms, with ``form``'s backlash, or with ``backlash_per_module`` x
    the module when the backlash follows the module (so the module named is the same
    whichever too-large module was given)."""
    lo, hi = 0.0, form.module
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        backlash = form.backlash if backlash_per_module is None else backlash_per_module * mid
        worst, gap = _tip_land_and_gap(part, replace(form, module=mid, backlash=backlash))
        lo, hi = (mid, hi) if worst >= MIN_TIP_LAND and gap > 0 else (lo, mid)
    return float(np.floor(lo * 100.0) / 100.0)


def pinion_outline(part: SectorPartition, form: ToothForm) -> np.ndarray:
    """Closed counter-clockwise pinion outline (K, 2) in mm over the whole turn."""
    flanks = pinion_flanks(part, form, FLANK_POINTS)
    angle, radius = _teeth_polar(flanks, tooth_between_flanks=True)
    return _repeat_polar(angle, radius, flanks.period, round(2.0 * np.pi / flanks.period))


def wheel_outline(part: SectorPartition, form: ToothForm) -> np.ndarray:
    """Closed counter-clockwise carrier-wheel outline (K, 2) in mm over the whole turn."""
    flanks = wheel_flanks(part, form, FLANK_POINTS)
    angle, radius = _teeth_polar(flanks, tooth_between_flanks=False)
    return _repeat_polar(angle, radius, flanks.period, 4)


def _teeth_polar(f: FlankTable, tooth_between_flanks: bool) -> tuple[np.ndarray, np.ndarray]:
    """Polar outline (angle rad, radius mm) of one period, counter-clockwise.

    Per sector: flank 1, the land between the flanks, flank 2, and the land to the
    next sector's flank 1. With a tooth between the flanks (pinion) the inner land
    is the tip and the land to the next sector the root; with a space (wheel) the
    other way round. Each flank continues radially from its base to the root circle;
    a land joining sectors of different radii blends them linearly.
    """
    root = f.root_radius[:, None]
    tip = f.tip_radius[:, None]
    flank1_angle = np.concatenate([f.left[:, :1], f.left], axis=1)          # root -> tip
    flank1_radius = np.concatenate([root, f.radius], axis=1)
    flank2_angle = np.concatenate([f.right[:, ::-1], f.right[:, :1]], axis=1)  # tip -> root
    flank2_radius = np.concatenate([f.radius[:, ::-1], root], axis=1)
    if tooth_between_flanks:
        inner_level, outer_level = tip, root
    else:
        flank1_angle, flank1_radius = flank1_angle[:, ::-1], flank1_radius[:, ::-1]
        flank2_angle, flank2_radius = flank2_angle[:, ::-1], flank2_radius[:, ::-1]
        inner_level, outer_level = root, tip

    t = np.linspace(0.0, 1.0, LAND_POINTS + 2)[1:-1][None, :]
    inner_angle = flank1_angle[:, -1:] + (flank2_angle[:, :1] - flank1_angle[:, -1:]) * t
    inner_radius = np.broadcast_to(inner_level, inner_angle.shape)
    next_start = np.roll(flank1_angle[:, :1], -1, axis=0)
    next_start[-1] += f.period
    outer_angle = flank2_angle[:, -1:] + (next_start - flank2_angle[:, -1:]) * t
    outer_radius = outer_level + (np.roll(outer_level, -1, axis=0) - outer_level) * t

    angle = np.concatenate([flank1_angle, inner_angle, flank2_angle, outer_angle], axis=1)
    radius = np.concatenate([flank1_radius, inner_radius, flank2_radius, outer_radius], axis=1)
    return angle.reshape(-1), radius.reshape(-1)


def _repeat_polar(angle: np.ndarray, radius: np.ndarray, period: float, copies: int) -> np.ndarray:
    """Repeat one period of a polar outline ``copies`` times and convert to x, y (mm)."""
    shifts = period * np.arange(copies)
    all_angle = (angle[None, :] + shifts[:, None]).reshape(-1)
    all_radius = np.tile(radius, copies)
    return np.column_stack([all_radius * np.cos(all_angle), all_radius * np.sin(all_angle)])
