"""Transmission laws: the crank law of SPEC §3 and tabulated laws (CSV samples, blends).

A law ties the driving (pinion) angle ``theta`` to the driven (wheel, carrier) angle
``phi``, both in rad, over one period that repeats; both classes here satisfy
:class:`wheelstep_cli.gears.transmission.TransmissionLaw`. A law has no centre distance:
the pitch curves take it as an argument (see :mod:`wheelstep_cli.gears.pitch_curves`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.mechanism.crank import SHOE_CYCLE, CrankMechanism, local_angle

#: Samples per law period in tabulated laws (linear interpolation error ~1e-9 rad).
TABLE_SAMPLES = 8192
#: Pinion turns per carrier turn the crank law takes, and the limit a refusal states (the
#: configuration's field states it from here).
TURNS = (2, 4)
TURNS_LIMIT = "must be 2 (balanced pinion) or 4 (one pinion turn per shoe)"


@dataclass(frozen=True)
class CrankLaw:
    """The constant-hub-speed law of ``mechanism`` with ``turns`` pinion turns per carrier turn.

    The ratio U = dtheta/dphi = u (k + 3b cos 2phi_loc) / k makes omega_H dX01/dphi
    constant at constant pinion speed; its kink at each shoe handover (phi = +-pi/4)
    is a corner of both pitch curves. Closed forms throughout.
    """

    mechanism: CrankMechanism
    turns: int = 2

    def __post_init__(self) -> None:
        require(self.turns in TURNS, "turns", self.turns, TURNS_LIMIT)

    @property
    def u(self) -> float:
        """Mean-ratio constant chosen so the pinion turns n pi/4 per half shoe cycle."""
        k, b = self.mechanism.k, self.mechanism.b
        return (self.turns * np.pi / 4.0) / (np.pi / 4.0 + 3.0 * b / (2.0 * k))

    @property
    def phi_start(self) -> float:
        """Driven angle where the tabulated period starts (a shoe handover), rad."""
        return -np.pi / 4.0

    @property
    def phi_period(self) -> float:
        """Driven angle of one period (one shoe cycle), rad."""
        return SHOE_CYCLE

    @property
    def theta_period(self) -> float:
        """Driving angle of one period, n pi/2 rad."""
        return self.turns * np.pi / 2.0

    @property
    def corners(self) -> tuple[float, ...]:
        """Driven angles (rad, in the period) where the ratio kinks: the shoe handover."""
        return (np.pi / 4.0,) if self.mechanism.b > 0 else ()

    @property
    def pinion_periods(self) -> int:
        """Law periods per pinion turn."""
        return int(round(2.0 * np.pi / self.theta_period))

    @property
    def wheel_periods(self) -> int:
        """Law periods per wheel turn (four shoes)."""
        return 4

    @property
    def blended_corners(self) -> tuple[float, ...]:
        """Corners smoothed by a blend: none, the crank law is exact."""
        return ()

    @property
    def blend_half_width(self) -> float:
        """Half-width of the blend at the corners, rad: 0, the crank law is exact."""
        return 0.0

    def ratio(self, phi):
        """Transfer ratio U = omega/omega_H = r_H/r (dimensionless) at carrier angle phi (rad)."""
        return self.u * self.mechanism.speed_analogue(phi) / self.mechanism.k

    def pinion_angle(self, phi):
        """Pinion angle theta(phi) in rad, continued over every period (theta(0) = 0)."""
        phi_loc, cycle = local_angle(phi)
        k, b = self.mechanism.k, self.mechanism.b
        local = self.u * (phi_loc + 3.0 * b * np.sin(2.0 * phi_loc) / (2.0 * k))
        return cycle * self.turns * np.pi / 2.0 + local

    def carrier_angle(self, theta, tol: float = 1e-13):
        """Inverse of :meth:`pinion_angle`: carrier angle phi (rad) for pinion angle theta (rad).

        Vectorised Newton iteration on the monotone law (U > 0 everywhere).
        """
        theta = np.asarray(theta, dtype=float)
        period = self.turns * np.pi / 2.0
        cycle = np.floor((theta + period / 2.0) / period)
        local = theta - cycle * period
        phi = local * (np.pi / 2.0) / period
        for _ in range(50):
            step = (self.pinion_angle(phi) - local) / self.ratio(phi)
            phi = np.clip(phi - step, -np.pi / 4.0, np.pi / 4.0)
            if np.all(np.abs(step) < tol):
                break
        return phi + cycle * SHOE_CYCLE

    def hub_speed_factor(self, phi):
        """Hub speed per unit carrier speed, dX01/dphi (mm/rad): what the gears keep constant."""
        return self.mechanism.speed_analogue(phi)


@dataclass(frozen=True)
class TabulatedLaw:
    """One period of a law, tabulated on a uniform grid of the driven angle.

    ``phi`` (rad, uniform, one period plus the closing sample), ``theta`` (rad) and
    ``ratio_table`` = dtheta/dphi at those samples. ``corners``: driven angles (rad) where
    the ratio kinks; ``blended_corners``: corners a blend of half-width
    ``blend_half_width`` (rad) smoothed away. ``hub_factor``: the output speed per unit
    driven speed (None: 1, a law with no mechanism behind it).
    """

    phi: np.ndarray
    theta: np.ndarray
    ratio_table: np.ndarray
    corners: tuple[float, ...] = ()
    hub_factor: Callable[[np.ndarray], np.ndarray] | None = field(default=None, compare=False)
    blended_corners: tuple[float, ...] = ()
    blend_half_width: float = 0.0

    @property
    def phi_start(self) -> float:
        return float(self.phi[0])

    @property
    def phi_period(self) -> float:
        return float(self.phi[-1] - self.phi[0])

    @property
    def theta_period(self) -> float:
        return float(self.theta[-1] - self.theta[0])

    @property
    def pinion_periods(self) -> int:
        return int(round(2.0 * np.pi / self.theta_period))

    @property
    def wheel_periods(self) -> int:
        return int(round(2.0 * np.pi / self.phi_period))

    def _fold(self, phi):
        phi = np.asarray(phi, dtype=float)
        turns = np.floor((phi - self.phi[0]) / self.phi_period)
        return phi - turns * self.phi_period, turns

    def ratio(self, phi):
        """U = dtheta/dphi (dimensionless) at driven angle phi (rad)."""
        local, _ = self._fold(phi)
        return np.interp(local, self.phi, self.ratio_table)

    def pinion_angle(self, phi):
        """Driving angle theta (rad) for driven angle phi (rad), continued over periods."""
        local, turns = self._fold(phi)
        return np.interp(local, self.phi, self.theta) + turns * self.theta_period

    def carrier_angle(self, theta):
        """Driven angle phi (rad) for driving angle theta (rad)."""
        theta = np.asarray(theta, dtype=float)
        turns = np.floor((theta - self.theta[0]) / self.theta_period)
        local = theta - turns * self.theta_period
        return np.interp(local, self.theta, self.phi) + turns * self.phi_period

    def hub_speed_factor(self, phi):
        """Output speed per unit driven speed at phi (rad): the mechanism's, or 1."""
        if self.hub_factor is None:
            return np.ones_like(np.asarray(phi, dtype=float))
        return self.hub_factor(phi)


def blended_law(law, half_width: float):
    """The law with its ratio U(phi) smoothed by a periodic raised-cosine window.

    ``half_width`` (rad of the driven angle) is the window's half-width (0: the law
    itself). The convolution keeps the mean of U, so theta still closes exactly over a
    period; the hub speed factor is kept.
    """
    if half_width <= 0:
        return law
    n = TABLE_SAMPLES
    phi = law.phi_start + law.phi_period * np.arange(n) / n
    u = law.ratio(phi)
    step = law.phi_period / n
    offsets = np.arange(-n // 2, n // 2) * step
    window = np.where(np.abs(offsets) < half_width, 1.0 + np.cos(np.pi * offsets / half_width), 0.0)
    window = np.roll(window / window.sum(), -n // 2)
    smooth = np.real(np.fft.ifft(np.fft.fft(u) * np.fft.fft(window)))
    smooth = np.append(smooth, smooth[0])
    phi = np.append(phi, phi[0] + law.phi_period)
    theta = law.pinion_angle(phi[0]) + np.concatenate(
        ([0.0], np.cumsum(0.5 * (smooth[1:] + smooth[:-1]) * step)))
    # remove the trapezoid's tiny closure error so theta closes exactly
    theta += (law.theta_period - (theta[-1] - theta[0])) * (phi - phi[0]) / law.phi_period
    return TabulatedLaw(phi, theta, smooth, (), law.hub_speed_factor, law.corners, half_width)


def period_fault(theta_deg, phi_deg) -> tuple[str, int | None, float] | None:
    """The first way samples (deg) fail to run over one period of closed gears: (which angle,
    "driving" or "driven"; the index of the first sample that does not increase past the one
    before it, or None when instead its span, deg, is no 360/k), None when they run over one."""
    columns = (("driving", np.asarray(theta_deg, dtype=float)), ("driven", np.asarray(phi_deg, dtype=float)))
    for name, column in columns:
        still = np.diff(column) <= 0
        if np.any(still):
            return name, int(np.argmax(still)) + 1, 0.0
    for name, column in columns:
        span = float(column[-1] - column[0])
        count = 360.0 / span
        if abs(count - round(count)) >= 1e-6 or round(count) < 1:
            return name, None, span
    return None


def law_from_samples(theta_deg, phi_deg, param: str = "law_csv") -> TabulatedLaw:
    """A law from samples of the driven angle against the driving angle over one period (deg).

    The periodic part of phi(theta) is fitted by a Fourier series (least squares), so
    the ratio dtheta/dphi = 1/phi'(theta) is smooth. Both period lengths must divide
    a whole turn (closed gears).
    """
    theta = np.radians(np.asarray(theta_deg, dtype=float))
    phi = np.radians(np.asarray(phi_deg, dtype=float))
    require(theta.ndim == 1 and len(theta) >= 8 and len(theta) == len(phi), param, len(theta),
            "needs at least 8 rows of driving angle, driven angle (deg)")
    fault = period_fault(theta_deg, phi_deg)
    if fault is not None:
        name, at, span = fault
        raise (DesignError(param, "rows", "both angles must increase strictly over the period") if at is not None
               else DesignError(param, f"{span:g} deg", f"the {name} angle must span 360/k deg over one "
                                                        f"period (closed gears); it spans {span:g} deg"))
    theta_period, phi_period = theta[-1] - theta[0], phi[-1] - phi[0]
    slope = phi_period / theta_period
    t = (theta - theta[0]) / theta_period * 2.0 * np.pi
    rest = phi - phi[0] - slope * (theta - theta[0])
    harmonics = max(1, min(48, (len(t) - 2) // 3))
    k = np.arange(1, harmonics + 1)
    basis = np.concatenate([np.ones((len(t), 1)), np.cos(np.outer(t, k)), np.sin(np.outer(t, k))], axis=1)
    coef, *_ = np.linalg.lstsq(basis, rest, rcond=None)
    residual = float(np.max(np.abs(basis @ coef - rest)))
    require(residual < 1e-3, param, f"{np.degrees(residual):.3g} deg",
            f"the samples do not fit a smooth periodic law: they stray up to {np.degrees(residual):.3g} "
            "deg from it (at most 0.06 deg)")
    a, b = coef[1:1 + harmonics], coef[1 + harmonics:]
    grid_t = np.linspace(0.0, 2.0 * np.pi, TABLE_SAMPLES + 1)
    dt = theta_period / (2.0 * np.pi)
    phi_grid = phi[0] + slope * grid_t * dt + coef[0] + np.cos(np.outer(grid_t, k)) @ a \
        + np.sin(np.outer(grid_t, k)) @ b
    dphi_dtheta = slope + (-np.sin(np.outer(grid_t, k)) @ (a * k) + np.cos(np.outer(grid_t, k)) @ (b * k)) / dt
    if np.any(dphi_dtheta <= 0):
        raise DesignError(param, "law", "the driven angle must increase with the driving angle")
    phi_grid -= phi_grid[0] - phi[0]
    theta_grid = theta[0] + grid_t * dt
    return TabulatedLaw(phi_grid, theta_grid, 1.0 / dphi_dtheta)
