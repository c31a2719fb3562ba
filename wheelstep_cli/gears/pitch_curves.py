"""Rolling pitch curves of a transmission law at a centre distance (SPEC §3).

With centre distance ``L`` (mm) the pitch radii are ``r = L / (1 + U)`` (pinion) and
``r_H = L - r`` (wheel), since ``r dtheta = r_H dphi`` and ``r + r_H = L``.
Convention (shared with the meshing check): the pinion's pitch point for carrier angle
phi lies at pinion body angle ``+theta(phi)``, the wheel's at wheel body angle ``-phi``.
Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.gears.transmission import TransmissionLaw


def pinion_radius(law: TransmissionLaw, phi, center_distance: float):
    """Pinion pitch radius r(phi) = L / (1 + U) in mm."""
    return center_distance / (1.0 + law.ratio(phi))


def wheel_radius(law: TransmissionLaw, phi, center_distance: float):
    """Wheel pitch radius r_H(phi) = L - r(phi) in mm."""
    return center_distance - pinion_radius(law, phi, center_distance)


@dataclass(frozen=True)
class PitchCurves:
    """Both pitch curves over one law period, densely sampled (closed forms, no sectors).

    ``phi`` driven angles (rad); ``pinion`` / ``wheel`` points (mm, own body frames);
    ``arc`` cumulative arc length (mm, same on both curves: they roll without slip);
    ``center_distance`` the distance they roll at (mm).
    """

    law: TransmissionLaw
    center_distance: float
    phi: np.ndarray
    pinion: np.ndarray
    wheel: np.ndarray
    arc: np.ndarray

    @property
    def period_arc(self) -> float:
        """Arc length of one period (mm), the same on both curves."""
        return float(self.arc[-1])


def pitch_curves(law: TransmissionLaw, center_distance: float, samples: int = 16384) -> PitchCurves:
    """Sample both pitch curves over one period starting at the law's first corner (or its start).

    The arc length uses ds^2 = r^2 dtheta^2 + dr^2 (true perimeter, radial term included).
    """
    start = law.corners[0] - law.phi_period if law.corners else law.phi_start
    phi = start + law.phi_period * np.linspace(0.0, 1.0, samples + 1)
    theta = law.pinion_angle(phi)
    if law.corners:
        # nudge the end samples inside the period so a kink lands exactly on the end points
        theta[0] = law.pinion_angle(start + 1e-12)
        theta[-1] = theta[0] + law.theta_period
    r = pinion_radius(law, phi, center_distance)
    pinion = np.column_stack([r * np.cos(theta), r * np.sin(theta)])
    r_h = center_distance - r
    wheel = np.column_stack([r_h * np.cos(-phi), r_h * np.sin(-phi)])
    ds = np.hypot(*np.diff(pinion, axis=0).T)
    arc = np.concatenate(([0.0], np.cumsum(ds)))
    return PitchCurves(law, float(center_distance), phi, pinion, wheel, arc)


def center_distance_for_module(law: TransmissionLaw, teeth_per_period: int, module: float) -> float:
    """Centre distance (mm) at which the pitch p = pi m fits ``teeth_per_period`` per period.

    The perimeter is proportional to L, so one evaluation at L = 1 suffices.
    """
    unit = pitch_curves(law, 1.0, 65536).period_arc
    return np.pi * module * teeth_per_period / unit
