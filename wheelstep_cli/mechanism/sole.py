"""The support shoe's sole: the constant-hub-height profile of SPEC §2.

Symbols: ``a`` hub axis to crank axes, ``b`` crank length, ``c`` shoe strut length,
``phi`` hub (carrier) angle; one shoe is in contact for phi in [-pi/4, pi/4].
The sole is given in the shoe's own frame: origin at the strut pivot, Y along the
strut towards the ground. Lengths in mm, angles in radians.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.errors import require
from wheelstep_cli.mechanism.crank import CrankMechanism

#: Half of the contact range of one shoe, rad.
HALF_CYCLE = np.pi / 4.0


def contact_angles(count: int) -> np.ndarray:
    """``count`` equally spaced hub angles over one shoe's contact, -pi/4..pi/4 inclusive, rad."""
    require(count >= 2, "points", count, "must be >= 2")
    return np.linspace(-HALF_CYCLE, HALF_CYCLE, count)


def sole_profile(design: CrankMechanism, phi) -> np.ndarray:
    """Sole points (X, Y) in mm in the shoe frame at hub angles ``phi``; shape (..., 2).

    Y1 = 4b cos phi - a, Y2 = a - 2b (1 + cos^2 phi) + c, X = Y2 sin phi, Y = Y1 + Y2 cos phi.
    """
    phi = np.asarray(phi, dtype=float)
    cos = np.cos(phi)
    y1 = 4.0 * design.b * cos - design.a
    y2 = design.a - 2.0 * design.b * (1.0 + cos**2) + design.c
    return np.stack([y2 * np.sin(phi), y1 + y2 * cos], axis=-1)


def sole_polar(design: CrankMechanism, phi) -> tuple[np.ndarray, np.ndarray]:
    """Polar form of the sole: radius rho (mm) from the pivot, angle alpha (rad) from the Y axis.

    alpha = atan(X / Y) as in SPEC §2, computed with atan2 so it stays right where Y < 0.
    """
    xy = sole_profile(design, phi)
    return np.hypot(xy[..., 0], xy[..., 1]), np.arctan2(xy[..., 0], xy[..., 1])


def sole_curvature_radius(design: CrankMechanism, phi):
    """Radius of curvature of the sole, R(phi) = a + c - b (6 cos^2 phi - 2), mm."""
    phi = np.asarray(phi, dtype=float)
    return design.a + design.c - design.b * (6.0 * np.cos(phi) ** 2 - 2.0)


def speed_ripple(speed: np.ndarray, dwell: np.ndarray | None = None) -> float:
    """Peak-to-peak over mean of a speed sampled at equal time steps, both ends included, or
    at steps whose durations are in proportion to ``dwell`` (per sample).

    The mean is the trapezoidal time average, so the ends count half. A fraction.
    """
    speed = np.asarray(speed, dtype=float)
    weight = np.ones(len(speed))
    weight[[0, -1]] = 0.5
    if dwell is not None:
        weight = weight * np.asarray(dwell, dtype=float)
    return float((speed.max() - speed.min()) / (np.sum(weight * speed) / weight.sum()))


def sole_table(design: CrankMechanism, count: int = 7) -> np.ndarray:
    """Rows (phi deg, X, Y, rho, alpha deg, R) at ``count`` hub angles over the contact, mm."""
    phi = contact_angles(count)
    xy = sole_profile(design, phi)
    rho, alpha = sole_polar(design, phi)
    return np.column_stack([np.degrees(phi), xy, rho, np.degrees(alpha),
                            sole_curvature_radius(design, phi)])
