"""Where a rack-cut pair stops being makeable: undercut and pointed teeth (SPEC §9).

The rack undercuts where the convex pitch curve bends tighter than a radius set by
the cutter; a tooth is pointed where its tip land falls below a floor, and is then
topped down to where the land is wide enough, or the design refused.
Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.cutter_limits import PRESSURE_ANGLE_DEG
from wheelstep_cli.gears.generation.envelope import PolarGrid, polyline_envelope
from wheelstep_cli.gears.generation.rack import RackCutter
from wheelstep_cli.gears.pitch_curves import PitchCurves
from wheelstep_cli.gears.transmission import TransmissionLaw


def curvature_radius(points: np.ndarray) -> np.ndarray:
    """Signed radius of curvature (mm) along a sampled curve; > 0 where convex (seen from outside)."""
    d1 = np.gradient(points, axis=0)
    d2 = np.gradient(d1, axis=0)
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    speed = np.hypot(d1[:, 0], d1[:, 1])
    orient = 1.0 if np.sum(points[:-1, 0] * points[1:, 1] - points[1:, 0] * points[:-1, 1]) > 0 else -1.0
    with np.errstate(divide="ignore"):
        return orient * speed**3 / cross


def min_convex_radius(law: TransmissionLaw, curves: PitchCurves) -> float:
    """Smallest convex radius of curvature (mm) of the pinion's pitch curve the rack rolls on.

    Corners are cut by the pivoting rack, and so are blended corners: both are left
    out. +inf when no part is convex.
    """
    rho = curvature_radius(curves.pinion)
    keep = np.ones(len(rho), dtype=bool)
    keep[:2] = keep[-2:] = False
    for smoothed in law.blended_corners:
        d = np.mod(curves.phi - smoothed + law.phi_period / 2.0, law.phi_period) - law.phi_period / 2.0
        keep &= np.abs(d) > 1.5 * law.blend_half_width
    rho = rho[keep]
    convex = rho[rho > 0]
    return float(convex.min()) if len(convex) else float("inf")


def undercut_limit(cutter: RackCutter, module: float) -> float:
    """Smallest convex pitch-curve radius of curvature (mm) a rack cuts without undercut."""
    a = cutter.pressure_angle
    # the cutter's addendum h_a0 is the gears' dedendum
    return module * (cutter.dedendum - cutter.fillet * (1.0 - np.sin(a))) / np.sin(a) ** 2


def undercut_remedy(cutter: RackCutter, module: float, rho: float, teeth_per_period: int,
                    pinion_periods: int) -> str:
    """Remedy text of :func:`undercut_options` (see there)."""
    options = undercut_options(cutter, module, rho, teeth_per_period, pinion_periods)
    angle = (f"pressure angle >= {options[1]['pressure_angle']:.1f} deg" if len(options) > 1
             else f"no pressure angle up to {PRESSURE_ANGLE_DEG[1]:g} deg helps")
    return f"use pinion z >= {options[0]['z']} or {angle}"


def undercut_options(cutter: RackCutter, module: float, rho: float, teeth_per_period: int,
                     pinion_periods: int) -> list[dict]:
    """The options at which the rack stops undercutting: ``[{"z": least tooth count}]`` and,
    when a pressure angle up to the cutter's greatest helps, ``{"pressure_angle": least, deg to 0.1}``.

    ``rho``: the pitch curve's smallest convex radius of curvature (mm). The count holds
    whether the pitch curves stay (the module shrinks as z grows) or the module stays (the
    curves grow with z): either way z x module / rho is what counts. A module is not offered:
    with a given module the curves scale with it and the undercut stays.
    """
    a = cutter.pressure_angle
    per_m = (cutter.dedendum - cutter.fillet * (1.0 - np.sin(a))) / np.sin(a) ** 2
    module_max = rho / per_m
    z_min = pinion_periods * int(np.ceil(teeth_per_period * module / module_max))
    lo, hi = a, np.radians(PRESSURE_ANGLE_DEG[1])
    f = lambda x: (cutter.dedendum - cutter.fillet * (1 - np.sin(x))) / np.sin(x) ** 2 * module - rho
    if f(hi) > 0:
        return [{"z": z_min}]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
    # to the 0.1 deg the text shows, rounded up so that the angle given clears the limit
    return [{"z": z_min}, {"pressure_angle": float(np.ceil(np.degrees(hi) * 10.0) / 10.0)}]


def top_pointed_teeth(grid: PolarGrid, radii: np.ndarray, pitch_radii: np.ndarray,
                      blank: np.ndarray, floor: float) -> tuple[np.ndarray, int, float, float]:
    """Top every tooth whose tip land is below ``floor`` mm down to where it is ``floor`` wide.

    Teeth are the runs of rays whose outline lies above the pitch curve. Returns the
    new radii, how many teeth were topped, the largest height removed (mm) and the
    smallest tip land left (mm).
    """
    above = radii > pitch_radii
    if above.all() or not above.any():
        return radii, 0, 0.0, 0.0
    first = int(np.argmin(above))
    order = np.roll(np.arange(len(radii)), -first)
    a = above[order].astype(np.int8)
    edges = np.diff(np.concatenate(([0], a, [0])))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    out = radii.copy()
    topped, worst, thinnest = 0, 0.0, np.inf
    for lo, hi in zip(starts, ends):                       # one iteration per tooth
        rays = order[lo:hi]
        if hi - lo < 3:
            continue                                        # a sliver above the pitch curve, no tooth
        uncut = radii[rays] >= blank[rays] - 1e-9
        land_now = grid.width * float(np.sum(blank[rays][uncut]))
        if land_now >= floor:
            thinnest = min(thinnest, land_now)
            continue
        r = np.sort(radii[rays])[::-1]
        land = np.arange(1, len(r) + 1) * grid.width * r    # land width if cut at r[k]
        k = int(np.argmax(land >= floor)) if np.any(land >= floor) else len(r) - 1
        out[rays] = np.minimum(out[rays], r[k])
        topped += 1
        worst = max(worst, float(r[0] - r[k]))
        thinnest = min(thinnest, float(land[k]))
    return out, topped, worst, thinnest


@dataclass(frozen=True)
class GearBody:
    """One gear's ray map before topping: its rays, pitch curve and blank (mm)."""

    name: str
    """``"pinion"`` or ``"wheel"`` (named in the refusal)."""
    grid: PolarGrid
    """The rays of one period."""
    curve: np.ndarray
    """Pitch curve over one period, (N, 2) mm in the gear frame."""
    blank: np.ndarray
    """Blank radius per ray, mm."""


@dataclass(frozen=True)
class ToppingLimits:
    """When a pointed tooth is topped and when the design is refused instead."""

    min_tip_land: float
    """Tip land floor, mm (GenerationSettings.min_tip_land at the pair's module)."""
    max_topping: float
    """Most height topped off, x module (GenerationSettings.max_topping)."""
    module: float
    """The pair's module, mm."""
    strict: bool
    """Refuse (True) or only top (False) when the topping costs more than ``max_topping``."""


def top_or_refuse(body: GearBody, radii: np.ndarray, cutter: RackCutter,
                  limits: ToppingLimits) -> tuple[np.ndarray, tuple[int, float], float]:
    """Top the gear's pointed teeth (see :func:`top_pointed_teeth`), or refuse when that costs
    more than max_topping x module: (new radii mm, (teeth topped, largest drop mm), thinnest land mm)."""
    pitch_r = polyline_envelope(body.grid, body.curve[None], nearest=False)
    new, count, drop, land = top_pointed_teeth(body.grid, radii, pitch_r, body.blank, limits.min_tip_land)
    module = limits.module
    if drop > limits.max_topping * module and limits.strict:
        # an ordinary tooth whose land is under the floor (the rack refuses spaces that close)
        # is topped by at most floor / (2 tan a), always under max_topping x module: the teeth
        # that cost more lie beside the pitch-curve corners
        remedy = "use a smaller addendum, a smaller pressure angle or more teeth (--z)"
        raise DesignError("addendum", cutter.addendum,
                          f"the {body.name} teeth come to a point (a {limits.min_tip_land:.3g} mm tip land "
                          f"needs {drop:.3f} mm off the tip, more than {limits.max_topping} x the "
                          f"module = {limits.max_topping * module:.3f} mm); {remedy}")
    return new, (count, drop), land
