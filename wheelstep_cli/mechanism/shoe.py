"""Support shoe with the constant-hub-height sole, and the link sizing (SPEC §2).

Symbols: ``a`` hub axis to crank axes, ``b`` crank length, ``c`` shoe strut length,
``phi`` hub (carrier) angle; one shoe is in contact for phi in [-pi/4, pi/4].
The sole is given in the shoe's own frame: origin at the strut pivot, Y along the
strut towards the ground. Lengths in mm, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import require

#: Half of the contact range of one shoe, rad.
HALF_CYCLE = np.pi / 4.0


@dataclass(frozen=True)
class ShoeDesign:
    """Mechanism lengths in mm: ``a`` hub to crank axes, ``b`` crank, ``c`` strut.

    Valid only with R_min = a - 4b + c > 0 (otherwise the sole has a cusp or loop).
    """

    a: float
    b: float
    c: float

    def __post_init__(self) -> None:
        _check_lengths(a=self.a, b=self.b, c=self.c)
        require(self.r_min > 0, "c", self.c,
                f"must be > 4b - a = {4 * self.b - self.a:g} mm (sole curvature radius "
                f"R_min = a - 4b + c = {self.r_min:g} mm must be > 0, else the sole has a cusp or loop)")

    @classmethod
    def from_r_min(cls, a: float, b: float, r_min: float) -> "ShoeDesign":
        """Size the strut from the chosen smallest sole curvature radius: c = R_min - a + 4b."""
        require(bool(np.isfinite(r_min)) and r_min > 0, "rmin", r_min,
                "must be > 0 mm (the sole would have a cusp or loop)")
        _check_lengths(a=a, b=b)
        c = r_min - a + 4.0 * b
        require(c > 0, "rmin", r_min,
                f"must be > a - 4b = {a - 4.0 * b:g} mm (strut length c = R_min - a + 4b must be > 0)")
        return cls(float(a), float(b), float(c))

    @property
    def r_min(self) -> float:
        """Smallest radius of curvature of the sole (at phi = 0), mm."""
        return self.a - 4.0 * self.b + self.c

    @property
    def k(self) -> float:
        """a - b + c in mm: the hub height and the constant of the speed analogue."""
        return self.a - self.b + self.c

    @property
    def hub_height(self) -> float:
        """Hub axis height above the ground during contact, Y01 = a - b + c, mm (constant)."""
        return self.k

    @property
    def x_walk(self) -> float:
        """Walking part of the advance per shoe cycle, X_I = 6b, mm."""
        return 6.0 * self.b

    @property
    def x_cycle(self) -> float:
        """Hub advance per shoe cycle, X01 = (a - b + c) pi/2 + 3b, mm."""
        return self.k * np.pi / 2.0 + 3.0 * self.b

    @property
    def x_roll(self) -> float:
        """Rolling part X_II = X01 - X_I = 3b (pi/2 - 1) + R_min pi/2, mm (the sole's arc length)."""
        return self.x_cycle - self.x_walk

    @property
    def roll_share(self) -> float:
        """Rolling share X_II / X01 (a fraction, not per cent)."""
        return self.x_roll / self.x_cycle


def _check_lengths(**lengths: float) -> None:
    """a and c must be > 0 mm, b >= 0 mm (b = 0: no cranks, a plain wheel)."""
    for name, value in lengths.items():
        if name == "b":
            require(bool(np.isfinite(value)) and value >= 0, name, value, "must be >= 0 mm")
        else:
            require(bool(np.isfinite(value)) and value > 0, name, value, "must be > 0 mm")


def contact_angles(count: int) -> np.ndarray:
    """``count`` equally spaced hub angles over one shoe's contact, -pi/4..pi/4 inclusive, rad."""
    require(count >= 2, "points", count, "must be >= 2")
    return np.linspace(-HALF_CYCLE, HALF_CYCLE, count)


def sole_profile(design: ShoeDesign, phi) -> np.ndarray:
    """Sole points (X, Y) in mm in the shoe frame at hub angles ``phi``; shape (..., 2).

    Y1 = 4b cos phi - a, Y2 = a - 2b (1 + cos^2 phi) + c, X = Y2 sin phi, Y = Y1 + Y2 cos phi.
    """
    phi = np.asarray(phi, dtype=float)
    cos = np.cos(phi)
    y1 = 4.0 * design.b * cos - design.a
    y2 = design.a - 2.0 * design.b * (1.0 + cos**2) + design.c
    return np.stack([y2 * np.sin(phi), y1 + y2 * cos], axis=-1)


def sole_polar(design: ShoeDesign, phi) -> tuple[np.ndarray, np.ndarray]:
    """Polar form of the sole: radius rho (mm) from the pivot, angle alpha (rad) from the Y axis.

    alpha = atan(X / Y) as in SPEC §2, computed with atan2 so it stays right where Y < 0.
    """
    xy = sole_profile(design, phi)
    return np.hypot(xy[..., 0], xy[..., 1]), np.arctan2(xy[..., 0], xy[..., 1])


def sole_curvature_radius(design: ShoeDesign, phi):
    """Radius of curvature of the sole, R(phi) = a + c - b (6 cos^2 phi - 2), mm."""
    phi = np.asarray(phi, dtype=float)
    return design.a + design.c - design.b * (6.0 * np.cos(phi) ** 2 - 2.0)


def hub_speed_analogue(design: ShoeDesign, phi):
    """dX01/dphi = a - b + c + 3b cos 2phi in mm/rad: hub speed per unit carrier speed."""
    phi = np.asarray(phi, dtype=float)
    return design.k + 3.0 * design.b * np.cos(2.0 * phi)


def speed_ripple(speed: np.ndarray) -> float:
    """Peak-to-peak over mean of a speed sampled at equal time steps, both ends included.

    The mean is the trapezoidal time average, so the ends count half. A fraction.
    """
    speed = np.asarray(speed, dtype=float)
    mean = (speed.sum() - 0.5 * (speed[0] + speed[-1])) / (len(speed) - 1)
    return float((speed.max() - speed.min()) / mean)


def mean_hub_speed_analogue(design: ShoeDesign) -> float:
    """Mean of dX01/dphi over one shoe cycle, k + 6b/pi in mm/rad (= X01 / (pi/2))."""
    return design.x_cycle / (np.pi / 2.0)
