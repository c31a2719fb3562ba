"""Equal-arc sector partition of the pitch curves, one tooth per sector (SPEC §4).

Each sector is a piece of a circular gear with its own pitch radius; all sectors
of both gears share one pitch-arc length. Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import require
from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.gears.pitch_curves import wheel_radius
from wheelstep_cli.gears.roots import bisect_increasing


@dataclass(frozen=True)
class SectorPartition:
    """Sectors of one carrier quarter and the matching pinion range.

    ``phi``/``theta`` are sector start angles (rad); ``dphi``/``dtheta`` widths (rad);
    ``r_wheel``/``r_pinion`` the sectors' pitch radii (mm); ``arc`` the common
    pitch arc (mm); ``carrier_arc`` the step-1 arc on the exact curve (mm);
    ``center_distance`` the design centre distance L_p (mm).
    """

    law: CrankLaw
    center_distance: float
    phi: np.ndarray
    dphi: np.ndarray
    r_wheel: np.ndarray
    theta: np.ndarray
    dtheta: np.ndarray
    r_pinion: np.ndarray
    arc: float
    carrier_arc: float

    @property
    def count(self) -> int:
        return len(self.phi)


def sectors_per_quarter(pinion_teeth: int, turns: int) -> int:
    """N = z n / 4 sectors per carrier quarter for a pinion of ``pinion_teeth`` teeth."""
    require(pinion_teeth >= 4, "z", pinion_teeth, "must be >= 4 teeth")
    require((pinion_teeth * turns) % 4 == 0, "z", pinion_teeth,
            f"must make z*n/4 whole sectors per carrier quarter (n = {turns}: "
            f"z a multiple of {4 // np.gcd(4, turns)})")
    return pinion_teeth * turns // 4


def _carrier_widths(law: CrankLaw, count: int, arc: float, center_distance: float) -> np.ndarray:
    """Sector widths dphi_i (rad) with r_H(phi_i + dphi_i/2) dphi_i = arc, from phi_1 = -pi/4.

    Solved as a whole-vector fixed point: the widths change slowly with their
    start angles, so the iteration contracts fast.
    """
    widths = np.full(count, (np.pi / 2.0) / count)
    for _ in range(200):
        starts = -np.pi / 4.0 + np.concatenate(([0.0], np.cumsum(widths)[:-1]))
        new = arc / wheel_radius(law, starts + widths / 2.0, center_distance)
        if np.max(np.abs(new - widths)) < 1e-15:
            return new
        widths = new
    return widths


def sector_partition(law: CrankLaw, count: int, center_distance: float) -> SectorPartition:
    """Equal-arc partition of one carrier quarter into ``count`` sectors at design centre
    distance ``center_distance`` mm (SPEC §4 steps 1-2)."""
    require(count >= 1, "z", count, "must give at least one sector per quarter")
    mean_radius = float(np.mean(wheel_radius(law, np.linspace(-np.pi / 4, np.pi / 4, 101), center_distance)))
    guess = mean_radius * (np.pi / 2.0) / count
    carrier_arc = bisect_increasing(
        lambda s: _carrier_widths(law, count, s, center_distance).sum() - np.pi / 2.0, 0.25 * guess, 4.0 * guess)
    dphi = _carrier_widths(law, count, carrier_arc, center_distance)

    L = center_distance
    span = law.turns * np.pi / 2.0
    arc = bisect_increasing(lambda l: np.sum(l / (L - l / dphi)) - span,
                            1e-12, L * dphi.min() * (1.0 - 1e-12))
    r_wheel = arc / dphi
    r_pinion = L - r_wheel
    dtheta = arc / r_pinion
    phi = -np.pi / 4.0 + np.concatenate(([0.0], np.cumsum(dphi)[:-1]))
    theta = -span / 2.0 + np.concatenate(([0.0], np.cumsum(dtheta)[:-1]))
    return SectorPartition(law, float(center_distance), phi, dphi, r_wheel, theta, dtheta, r_pinion, arc, carrier_arc)
