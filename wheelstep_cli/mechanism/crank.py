"""The crank mechanism of a wheel-step mover (SPEC §1-§2): one model for every command.

A hub carries four cranks; ``a`` is the distance from the hub axis to the crank axes,
``b`` the crank length, ``c`` the shoe strut length (mm). One shoe is in contact while
the hub (carrier) angle ``phi`` runs over [-pi/4, pi/4]; the next shoe repeats the
motion, so everything periodic here has period pi/2 in ``phi`` (rad).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError, require, rounded_down, rounded_up

#: Carrier angle of one shoe cycle (four shoes per turn), rad.
SHOE_CYCLE = np.pi / 2.0
#: Smallest sole curvature radius a design may choose, mm: far below any printable sole, and
#: far above the rounding of c = R_min - a + 4b.
MIN_R_MIN = 1e-3


def local_angle(phi):
    """Carrier angle folded into one shoe's contact range [-pi/4, pi/4) (rad) and its cycle index."""
    phi = np.asarray(phi, dtype=float)
    cycle = np.floor((phi + np.pi / 4.0) / SHOE_CYCLE)
    return phi - cycle * SHOE_CYCLE, cycle


@dataclass(frozen=True)
class CrankMechanism:
    """Mechanism lengths in mm: ``a`` hub to crank axes, ``b`` crank, ``c`` strut.

    Valid only with a, c > 0, b >= 0 (b = 0: no cranks, a plain wheel) and
    R_min = a - 4b + c >= :data:`MIN_R_MIN` (otherwise the sole has, in effect, a cusp, or
    a loop); k = a - b + c then is positive too.
    """

    a: float
    b: float
    c: float

    def __post_init__(self) -> None:
        _check_lengths(a=self.a, b=self.b, c=self.c)
        # the least R_min from_r_min takes, also for a strut given as c (a nanometre of slack
        # for the rounding of c = R_min - a + 4b); each limit printed rounded so that the value
        # copied from it passes
        if not self.r_min >= MIN_R_MIN - 1e-6:
            least = MIN_R_MIN
            why = (f" (sole curvature radius R_min = a - 4b + c = {self.r_min:.4g} mm must be >= {least:g} mm, "
                   "else the sole has, in effect, a cusp, or a loop)")
            raise DesignError("c", self.c, f"must be >= 4b - a + {least:g} = "
                              f"{_shown_up(4 * self.b - self.a + least)} mm" + why, {
                "b": (self.b, f"must be <= (a + c - {least:g})/4 = "
                              f"{rounded_down((self.a + self.c - least) / 4 + 1e-7, 4)} mm" + why),
                "a": (self.a, f"must be >= 4b - c + {least:g} = {_shown_up(4 * self.b - self.c + least)} mm" + why),
                "r_min": (self.r_min, f"must be >= {least:g} mm (a sole bent tighter has, in effect, a cusp)")})

    @classmethod
    def from_r_min(cls, a: float, b: float, r_min: float) -> "CrankMechanism":
        """Size the strut from the chosen smallest sole curvature radius: c = R_min - a + 4b (mm)."""
        require(bool(np.isfinite(r_min)) and r_min >= MIN_R_MIN, "r_min", r_min,
                f"must be >= {MIN_R_MIN:g} mm (a sole bent tighter has, in effect, a cusp)")
        _check_lengths(a=a, b=b)
        c = r_min - a + 4.0 * b
        if not c > 0:
            why = " (strut length c = R_min - a + 4b must be > 0)"
            raise DesignError("r_min", r_min, f"must be > a - 4b = {a - 4.0 * b:g} mm" + why, {
                "b": (b, f"must be > (a - R_min)/4 = {(a - r_min) / 4:g} mm" + why),
                "a": (a, f"must be < R_min + 4b = {r_min + 4.0 * b:g} mm" + why)})
        return cls(float(a), float(b), float(c))

    @property
    def r_min(self) -> float:
        """Smallest radius of curvature of the sole (at phi = 0), R_min = a - 4b + c, mm."""
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

    @property
    def mean_speed_analogue(self) -> float:
        """Mean of dX01/dphi over one shoe cycle, k + 6b/pi in mm/rad (= X01 / (pi/2))."""
        return self.x_cycle / SHOE_CYCLE

    def speed_analogue(self, phi):
        """dX01/dphi = k + 3b cos(2 phi_loc) in mm/rad: hub speed per unit carrier speed.

        Periodic over the shoe cycles: the next shoe takes over at phi = +-pi/4, where
        the analogue has its V-shaped minimum.
        """
        phi_loc, _ = local_angle(phi)
        return self.k + 3.0 * self.b * np.cos(2.0 * phi_loc)


def _check_lengths(**lengths: float) -> None:
    """a and c must be finite and > 0 mm, b finite and >= 0 mm."""
    for name, value in lengths.items():
        if name == "b":
            require(bool(np.isfinite(value)) and value >= 0, name, value, "must be >= 0 mm")
        else:
            require(bool(np.isfinite(value)) and value > 0, name, value, "must be > 0 mm")


def _shown_up(limit: float) -> str:
    """A lower limit (mm) to a thousandth, rounded up, without trailing zeros (340.001, 420)."""
    return rounded_up(limit - 1e-7, 3).rstrip("0").rstrip(".")
