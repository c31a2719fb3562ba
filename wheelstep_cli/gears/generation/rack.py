"""The basic rack and its cutting poses along a pitch curve (SPEC §9).

The rack's pitch line rolls without slip on the gear's pitch curve; each rack tooth
may be tilted about its pitch point towards the radius; at a pitch-curve corner the
rack pivots about the corner point through part of the turn from each side.
Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.gears.cutter_limits import (ADDENDUM, CLEARANCE, DEDENDUM_MAX, FILLET, PRESSURE_ANGLE_DEG,
                                               range_text)
from wheelstep_cli.gears.generation.outline import outward_sign


@dataclass(frozen=True)
class RackCutter:
    """Basic rack: pressure angle (rad); addendum, dedendum, tip fillet radius as multiples of m.

    ``addendum`` is the gears' tooth height above the pitch curve, ``dedendum`` the
    depth below it (the cutter's tooth height), ``fillet`` the cutter's tip radius.
    ``backlash`` is the total normal backlash j_n (mm) of the pair. ``clearance`` (x m)
    is the tip clearance of the wheel's spaces below the pinion's tips (the pinion's own
    spaces end ``dedendum - addendum`` below the wheel's tips).
    """

    pressure_angle: float = np.radians(20.0)
    addendum: float = 1.0
    dedendum: float = 1.25
    fillet: float = 0.25
    backlash: float = 0.5
    clearance: float = 0.25

    def __post_init__(self) -> None:
        (a_lo, a_hi), (h_lo, h_hi) = PRESSURE_ANGLE_DEG, ADDENDUM
        require(np.radians(a_lo) <= self.pressure_angle <= np.radians(a_hi), "pressure_angle",
                float(np.degrees(self.pressure_angle)), range_text(PRESSURE_ANGLE_DEG, "deg"))
        require(h_lo <= self.addendum <= h_hi, "addendum", self.addendum, range_text(ADDENDUM, "x module"))
        if not self.addendum < self.dedendum <= DEDENDUM_MAX:
            # the rule ties the two: stated for the addendum too, so a refusal names the one given
            raise DesignError("dedendum", self.dedendum, f"must be > the addendum ({self.addendum:g} x "
                              f"module; the difference is the tip clearance) and <= {DEDENDUM_MAX:g} x module",
                              {"addendum": (self.addendum, f"must be < the dedendum ({self.dedendum:g} x "
                                                           "module; the difference is the tip clearance) "
                                                           f"and >= {h_lo:g} x module")}
                              if self.dedendum <= DEDENDUM_MAX else None)
        require(FILLET[0] <= self.fillet <= FILLET[1], "fillet", self.fillet, range_text(FILLET, "x module"))
        require(np.isfinite(self.backlash) and self.backlash >= 0, "backlash", self.backlash,
                "must be >= 0 mm")
        require(CLEARANCE[0] <= self.clearance <= CLEARANCE[1], "clearance", self.clearance,
                range_text(CLEARANCE, "x module"))

    @property
    def pinion_clearance(self) -> float:
        """Tip clearance (x m) of the pinion's spaces below the wheel's tips."""
        return self.dedendum - self.addendum


@dataclass(frozen=True)
class RackRolling:
    """How the rack cuts one period of a gear's pitch curve (mm, rad, counts)."""

    curve: np.ndarray
    """Pitch curve over one period, (N, 2) mm in the gear frame."""
    arc: np.ndarray
    """Arc length (mm) at each curve point, (N,), from 0."""
    pitch: float
    """Tooth pitch along the curve, mm."""
    rack_center: float
    """Arc position (mm) of a rack tooth centre when the rack touches the curve's start."""
    poses: int
    """Rolling poses over the period."""
    corner_poses: int
    """Pivot poses over a whole corner turn (only the pivot fractions of them are taken)."""
    period_angle: float
    """Body angle (rad) one period of the curve spans."""
    copies: int
    """Periods per gear turn."""
    tilt: float
    """Rack-tooth tilt towards the radius, fraction of mu (GenerationSettings.tilt)."""
    pivot: float
    """Fraction of the corner turn pivoted through from each side (GenerationSettings.pivot)."""


@dataclass(frozen=True)
class RackTeeth:
    """Rack points (K, 2) in rack coordinates (mm) and each point's tooth centre x (K,) mm."""

    points: np.ndarray
    tooth_x: np.ndarray


@dataclass(frozen=True)
class Frames:
    """Per pose (P,): the contact point (P, 2) mm, the unit tangent and the outward unit normal."""

    origin: np.ndarray
    tangent: np.ndarray
    normal: np.ndarray


def rack_profile(cutter: RackCutter, module: float, pitch: float, teeth: int,
                 flank_points: int = 2) -> np.ndarray:
    """Cutter polyline (K, 2) in rack coordinates (x along the pitch line, y outward, mm).

    ``teeth`` cutter teeth centred at x = (j - (teeth-1)/2) p; each cuts one space
    of the gear, reaching y = -dedendum m with tip fillets; between teeth the
    polyline runs at a height the gear blank never reaches. A flank is a straight line:
    ``flank_points`` points along it (2, its ends, is the same line; points between them
    only add work to the polygon booleans that cut the pinion).
    """
    a = cutter.pressure_angle
    tan_a, cos_a, sin_a = np.tan(a), np.cos(a), np.sin(a)
    h_f = cutter.dedendum * module
    rho = cutter.fillet * module
    # cutter tooth half thickness at the pitch line: p/4 plus the pinion's thinning j_n/4 (normal)
    half = pitch / 4.0 + cutter.backlash / (4.0 * cos_a)
    top = min(cutter.addendum * module + 0.15 * module, (pitch / 2.0 - half) / tan_a - 1e-3)
    if top <= cutter.addendum * module:
        land = 2.0 * (pitch / 2.0 - half - cutter.addendum * module * tan_a)
        why = (f"the teeth come to a point (the rack's tooth spaces close below the tip line, tip "
               f"land {land:.3f} mm at module {module:.3f} mm)")
        # the same rule solved for the backlash the user may have given instead of the addendum
        most = 4.0 * cos_a * (pitch / 4.0 - tan_a * (cutter.addendum * module + 1e-3))
        raise DesignError("addendum", cutter.addendum, f"{why}; use a smaller addendum, a smaller "
                          "pressure angle or more teeth (--z)", alternatives={
                              "backlash": (cutter.backlash, f"{why}; must be below {max(most, 0.0):.3f} mm"),
                              "pressure_angle": (np.degrees(a), f"{why}; use a smaller pressure angle")})
    require(flank_points >= 2, "flank_points", flank_points, "must be >= 2 (the flank's ends)")
    yc = -h_f + rho
    xc = half + (yc * sin_a - rho) / cos_a                 # right fillet centre
    if xc < 0.0:
        raise _no_tip_land(cutter, module, pitch)
    # right half of one cutter tooth, from the tip centre out to the top (the flat land from
    # the tip centre to the fillet is a straight line too: its ends are its points)
    tip = np.array([[0.0, -h_f]])
    arc_t = np.linspace(-np.pi / 2.0, -a, 10)
    fillet = np.column_stack([xc + rho * np.cos(arc_t), yc + rho * np.sin(arc_t)])
    y = np.linspace(yc - rho * sin_a, top, flank_points)[1:]
    flank = np.column_stack([half + y * tan_a, y])
    right = np.vstack([tip, fillet, flank, [[pitch / 2.0, top]]])
    tooth = np.vstack([right[::-1] * [-1.0, 1.0], right[1:]])   # left top -> tip -> right top
    shifts = (np.arange(teeth) - (teeth - 1) / 2.0) * pitch
    rack = (tooth[None, :, :] + np.column_stack([shifts, np.zeros(teeth)])[:, None, :])
    rack = rack[:, :-1].reshape(-1, 2)
    return np.vstack([rack, tooth[-1:] + [shifts[-1], 0.0]])


def _fillet_centre_x(cutter: RackCutter, module: float, pitch: float, angle: float, fillet: float) -> float:
    """x (mm) of the rack tooth's right tip-fillet centre at pressure angle ``angle`` (rad) with
    a fillet of ``fillet`` mm: the tip keeps a flat land while it is >= 0."""
    cos_a, sin_a = np.cos(angle), np.sin(angle)
    half = pitch / 4.0 + cutter.backlash / (4.0 * cos_a)
    return half + ((fillet - cutter.dedendum * module) * sin_a - fillet) / cos_a


def _no_tip_land(cutter: RackCutter, module: float, pitch: float) -> DesignError:
    """The refusal of a cutter whose tip fillets leave its tip no flat land: the largest fillet
    (x module) at its pressure angle, and the largest pressure angle (deg) at its fillet,
    both rounded to what, applied, keeps a land."""
    a, rho = cutter.pressure_angle, cutter.fillet * module
    # the centre's x is linear in the fillet: solved for it
    most_fillet = (_fillet_centre_x(cutter, module, pitch, a, 0.0)
                   / (1.0 - np.sin(a)) * np.cos(a)) / module
    lo, hi = np.radians(PRESSURE_ANGLE_DEG[0]), a
    if _fillet_centre_x(cutter, module, pitch, lo, rho) < 0.0:
        most_angle = None
    else:
        for _ in range(50):       # the land narrows as the flanks lean more
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if _fillet_centre_x(cutter, module, pitch, mid, rho) >= 0.0 else (lo, mid)
        most_angle = np.floor(10.0 * np.degrees(lo)) / 10.0
    why = "leaves the cutter tip no flat land"
    most = np.floor(1000.0 * most_fillet) / 1000.0
    angle_text = (f"{why} with fillet {cutter.fillet:g} x module; must be <= {most_angle:g} deg"
                  if most_angle is not None else
                  f"{why} with fillet {cutter.fillet:g} x module at any pressure angle; use a fillet "
                  f"<= {most:g} x module")
    # the dedendum's x is linear too: the deepest tooth that keeps a land at this fillet
    deepest = (_fillet_centre_x(cutter, module, pitch, a, rho) / (module * np.sin(a) / np.cos(a))
               + cutter.dedendum)
    deepest = np.floor(1000.0 * deepest) / 1000.0
    if most_fillet < 0.0:
        # no fillet helps: the flanks lean too far for the tooth's depth
        shallower = (f"must be <= {deepest:g} x module with fillet {cutter.fillet:g} x module"
                     if deepest > cutter.addendum else "use a smaller pressure angle")
        return DesignError("pressure_angle", float(np.degrees(a)), f"{why} even without a fillet; " + (
            f"must be <= {most_angle:g} deg with fillet {cutter.fillet:g} x module" if most_angle is not None
            else "use a smaller dedendum"), alternatives={"dedendum": (
                cutter.dedendum, f"{why} at pressure angle {np.degrees(a):g} deg even without a fillet; "
                f"{shallower}")})
    error = DesignError("fillet", cutter.fillet,
                        f"{why}; must be <= {most:g} x module at pressure angle {np.degrees(a):g} deg",
                        alternatives={"pressure_angle": (float(np.degrees(a)), angle_text)})
    if deepest > cutter.addendum:
        # limits, not remedies: a deeper tooth cut may still mesh outside the bounds
        error.alternatives["dedendum"] = (cutter.dedendum, f"{why} with fillet {cutter.fillet:g} x module at "
                                          f"pressure angle {np.degrees(a):g} deg; must be <= {deepest:g} x "
                                          f"module (or the fillet <= {most:g} x module)")
    return error


def rack_tooth_polygons(cutter: RackCutter, module: float, pitch: float, teeth: int = 5,
                        flank_points: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Closed cutter teeth in rack coordinates, shape (teeth, K, 2), and their centres x (mm).

    Each tooth runs from its left top over the tip to its right top and closes far
    outside the blank, so a tooth can be tilted about its pitch point on its own.
    """
    one = rack_profile(cutter, module, pitch, 1, flank_points)
    far = one[:, 1].max() + 4.0 * module
    closed = np.vstack([one, [[one[-1, 0], far], [one[0, 0], far]]])
    centres = (np.arange(teeth) - (teeth - 1) / 2.0) * pitch
    return closed[None, :, :] + np.column_stack([centres, np.zeros(teeth)])[:, None, :], centres


def pivot_fractions(count: int, pivot: float) -> np.ndarray:
    """Fractions of the corner turn the pivoting rack takes: [0, pivot] and [1 - pivot, 1]."""
    f = np.linspace(0.0, 1.0, count)
    return f[(f <= pivot + 1e-12) | (f >= 1.0 - pivot - 1e-12)]


def curve_frames(points: np.ndarray, arc: np.ndarray, s: np.ndarray, sign: float) -> Frames:
    """Point, unit tangent and outward unit normal at arc positions s (mm) on a sampled curve.

    ``sign``: +1 when the curve's right-hand normal points outward (see ``outward_sign``).
    """
    x = np.interp(s, arc, points[:, 0])
    y = np.interp(s, arc, points[:, 1])
    seg = np.diff(points, axis=0)
    seg /= np.hypot(seg[:, 0], seg[:, 1])[:, None]
    idx = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(seg) - 1)
    tangent = seg[idx]
    normal = sign * np.column_stack([tangent[:, 1], -tangent[:, 0]])
    return Frames(np.column_stack([x, y]), tangent, normal)


def radial_tilt(curve: np.ndarray, arc: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """Angle mu(s) (rad) between the pitch-curve normal and the radius vector, as a function of arc.

    Tilting a rack tooth by -mu turns its axis from the pitch-curve normal to the
    radius: both flanks then meet the direction of motion at the pressure angle.
    """
    seg = np.diff(curve, axis=0)
    mid = 0.5 * (curve[1:] + curve[:-1])
    radial = mid / np.hypot(mid[:, 0], mid[:, 1])[:, None]
    cross = radial[:, 0] * seg[:, 1] - radial[:, 1] * seg[:, 0]
    mu = np.arctan2(np.sum(radial * seg, axis=1), cross)
    s_mid = 0.5 * (arc[1:] + arc[:-1])
    total = arc[-1]
    return lambda s: np.interp(np.mod(s, total), s_mid, mu)


def place_rack(frames: Frames, teeth: RackTeeth, rel_shift: np.ndarray, tilt_of_arc,
               arc_at_contact: np.ndarray) -> np.ndarray:
    """Rack points in the gear frame for poses (P,): (P, K, 2) mm, each tooth tilted about its pitch point.

    ``rel_shift``: per pose, the template's x offset (mm); ``tilt_of_arc``: tilt (rad)
    of a tooth centred at an arc position (None: no tilt); ``arc_at_contact``: per
    pose, the contact arc (mm).
    """
    rack = teeth.points
    rx = rack[None, :, 0] + rel_shift[:, None]
    ry = np.broadcast_to(rack[None, :, 1], rx.shape)
    if tilt_of_arc is not None:
        # a tooth's tilt is one angle for all its points: found per tooth, then spread
        centres, tooth = np.unique(teeth.tooth_x, return_inverse=True)
        per_tooth = centres[None, :] + rel_shift[:, None]
        tau = tilt_of_arc(arc_at_contact[:, None] + per_tooth)
        centre = per_tooth[:, tooth]
        dx = rx - centre
        c, s = np.cos(tau)[:, tooth], np.sin(tau)[:, tooth]
        rx, ry = centre + c * dx - s * ry, s * dx + c * ry
    return (frames.origin[:, None, :] + rx[..., None] * frames.tangent[:, None, :]
            + ry[..., None] * frames.normal[:, None, :])


def rack_poses(rolling: RackRolling, teeth: RackTeeth) -> list[np.ndarray]:
    """Rack points (mm, gear frame) in every cutting pose over one period of the curve.

    The first array holds the rolling poses (P, K, 2); where the period ends in a
    corner (the tangent jumps) a second holds the pivot poses about the corner point.
    """
    curve, arc, pitch = rolling.curve, rolling.arc, rolling.pitch
    sign = outward_sign(curve)
    mu = radial_tilt(curve, arc)
    tilt = rolling.tilt
    tilt_fn = (lambda a: -tilt * mu(a)) if tilt else None
    s = (np.arange(rolling.poses) + 0.5) * arc[-1] / rolling.poses
    frames = curve_frames(curve, arc, s, sign)
    shift = np.mod(rolling.rack_center - s + pitch / 2.0, pitch) - pitch / 2.0
    worlds = [place_rack(frames, teeth, shift, tilt_fn, s)]
    corner = _corner_poses(rolling, teeth, sign, tilt_fn)
    if corner is not None:
        worlds.append(corner)
    return worlds


def _corner_poses(rolling: RackRolling, teeth: RackTeeth, sign: float, tilt_fn) -> np.ndarray | None:
    """Rack points (P, K, 2) mm pivoting about the curve's start corner, or None without a corner."""
    curve, pitch = rolling.curve, rolling.pitch
    # the tangent arriving at the start corner: the period's end tangent, rotated back one period
    c, sn = np.cos(-rolling.period_angle), np.sin(-rolling.period_angle)
    t_end = curve[-1] - curve[-2]
    t_in = np.array([c * t_end[0] - sn * t_end[1], sn * t_end[0] + c * t_end[1]])
    t_out = curve[1] - curve[0]
    turn = np.arctan2(t_in[0] * t_out[1] - t_in[1] * t_out[0], np.dot(t_in, t_out))
    if not (rolling.corner_poses > 0 and abs(turn) > 1e-6):
        return None
    angles = np.arctan2(t_in[1], t_in[0]) + turn * pivot_fractions(rolling.corner_poses, rolling.pivot)
    count = len(angles)
    tangent = np.column_stack([np.cos(angles), np.sin(angles)])
    normal = sign * np.column_stack([tangent[:, 1], -tangent[:, 0]])
    shift = np.full(count, np.mod(rolling.rack_center + pitch / 2.0, pitch) - pitch / 2.0)
    origin = np.broadcast_to(curve[0], (count, 2))
    return place_rack(Frames(origin, tangent, normal), teeth, shift, tilt_fn, np.zeros(count))
