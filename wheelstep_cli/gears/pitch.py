"""Pitch curves of the constant-hub-speed non-circular gear pair (SPEC §3).

The pinion (driving, angle ``theta``, pitch radius ``r``) drives the carrier wheel
(driven, angle ``phi``, pitch radius ``r_H``) with ``r + r_H = L`` and
``r dtheta = r_H dphi``. The law makes ``omega_H * dX01/dphi`` constant, where
``dX01/dphi = k + 3b cos 2phi`` and ``k = a - b + c``. It holds for the shoe in
contact (phi in [-pi/4, pi/4]) and repeats every pi/2 of the carrier.
Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import require

QUARTER = np.pi / 2.0


@dataclass(frozen=True)
class CrankLaw:
    """Mechanism lengths (mm), pinion turns per carrier turn and design centre distance (mm)."""

    a: float
    b: float
    c: float
    center_distance: float
    turns: int = 2

    def __post_init__(self) -> None:
        for name in ("a", "c", "center_distance"):
            value = getattr(self, name)
            require(np.isfinite(value) and value > 0, name.replace("_", "-"), value, "must be > 0 mm")
        require(np.isfinite(self.b) and self.b >= 0, "b", self.b, "must be >= 0 mm")
        require(self.turns in (2, 4), "turns", self.turns,
                "must be 2 (balanced pinion) or 4 (one pinion turn per shoe)")
        require(self.k > 0, "b", self.b, f"must be < a + c = {self.a + self.c:g} mm "
                "(hub speed analogue k = a - b + c must be > 0)")
        require(self.r_min > 0, "b", self.b,
                f"must be < (a + c)/4 = {(self.a + self.c) / 4:g} mm "
                "(sole curvature radius R_min = a - 4b + c must be > 0)")

    @property
    def k(self) -> float:
        """Hub height / mean speed analogue ``a - b + c`` in mm."""
        return self.a - self.b + self.c

    @property
    def r_min(self) -> float:
        """Smallest radius of curvature of the shoe sole ``a - 4b + c`` in mm."""
        return self.a - 4.0 * self.b + self.c

    @property
    def u(self) -> float:
        """Mean-ratio constant chosen so the pinion turns n*pi/4 per half shoe cycle."""
        return (self.turns * np.pi / 4.0) / (np.pi / 4.0 + 3.0 * self.b / (2.0 * self.k))


def local_angle(phi):
    """Carrier angle folded into the shoe-contact range [-pi/4, pi/4) and its quarter index."""
    phi = np.asarray(phi, dtype=float)
    quarter = np.floor((phi + np.pi / 4.0) / QUARTER)
    return phi - quarter * QUARTER, quarter


def hub_speed_analogue(law: CrankLaw, phi):
    """dX01/dphi = k + 3b cos(2 phi_loc) in mm/rad: hub speed per unit carrier speed."""
    phi_loc, _ = local_angle(phi)
    return law.k + 3.0 * law.b * np.cos(2.0 * phi_loc)


def ratio(law: CrankLaw, phi):
    """Transfer ratio U = omega/omega_H = r_H/r (dimensionless) at carrier angle phi."""
    return law.u * hub_speed_analogue(law, phi) / law.k


def pinion_radius(law: CrankLaw, phi):
    """Pinion pitch radius r(phi) in mm."""
    return law.center_distance / (1.0 + ratio(law, phi))


def wheel_radius(law: CrankLaw, phi):
    """Carrier-wheel pitch radius r_H(phi) = L - r(phi) in mm."""
    return law.center_distance - pinion_radius(law, phi)


def pinion_angle(law: CrankLaw, phi):
    """Pinion angle theta(phi) in rad, continued over every quarter (theta(0) = 0)."""
    phi_loc, quarter = local_angle(phi)
    local = law.u * (phi_loc + 3.0 * law.b * np.sin(2.0 * phi_loc) / (2.0 * law.k))
    return quarter * law.turns * np.pi / 2.0 + local


def carrier_angle(law: CrankLaw, theta, tol: float = 1e-13):
    """Inverse of :func:`pinion_angle`: carrier angle phi (rad) for pinion angle theta (rad).

    Vectorised Newton iteration on the monotone law (U > 0 everywhere).
    """
    theta = np.asarray(theta, dtype=float)
    period = law.turns * np.pi / 2.0
    quarter = np.floor((theta + period / 2.0) / period)
    local = theta - quarter * period
    phi = local * (np.pi / 2.0) / period
    for _ in range(50):
        step = (pinion_angle(law, phi) - local) / ratio(law, phi)
        phi = np.clip(phi - step, -np.pi / 4.0, np.pi / 4.0)
        if np.all(np.abs(step) < tol):
            break
    return phi + quarter * QUARTER
