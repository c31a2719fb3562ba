"""Law-agnostic pitch-curve pairs: any monotone transmission law -> both rolling pitch curves.

A transmission law ties the driving (pinion) angle ``theta`` to the driven (wheel)
angle ``phi``. Everything here is parametrised by the driven angle ``phi`` over one
period: the ratio ``U(phi) = dtheta/dphi``, the pinion angle ``theta(phi)`` and its
inverse. With centre distance ``L`` the rolling pitch curves are
``r(phi) = L / (1 + U)`` (pinion) and ``r_H(phi) = L U / (1 + U)`` (wheel), since
``r dtheta = r_H dphi`` and ``r + r_H = L``.

Physical convention (shared with the meshing check): the pinion's pitch point for
carrier angle phi lies at pinion body angle ``+theta(phi)``, the wheel's at wheel body
angle ``-phi``. Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.gears import pitch as crank

#: Samples per law period in tabulated laws (linear interpolation error ~1e-9 rad).
TABLE_SAMPLES = 8192


@dataclass(frozen=True)
class PitchLaw:
    """One period of a transmission law, tabulated on a uniform grid of the driven angle.

    ``phi`` (rad, uniform, one period plus the closing sample), ``theta`` (rad) and
    ``ratio`` = dtheta/dphi at those samples. ``corners`` lists driven angles (rad,
    inside the period) where the ratio has a kink (pitch curves have corners there).
    ``hub_factor`` optionally maps phi to the hub speed analogue (mm/rad).
    """

    phi: np.ndarray
    theta: np.ndarray
    ratio_table: np.ndarray
    center_distance: float
    corners: tuple[float, ...] = ()
    hub_factor: object = field(default=None, compare=False)
    exact: object = field(default=None, compare=False)   # CrankLaw for closed forms
    blended_corners: tuple[float, ...] = ()   # corners (rad) smoothed by a blend ...
    blend_half_width: float = 0.0             # ... of this half-width (rad)

    @property
    def phi_period(self) -> float:
        return float(self.phi[-1] - self.phi[0])

    @property
    def theta_period(self) -> float:
        return float(self.theta[-1] - self.theta[0])

    @property
    def pinion_periods(self) -> int:
        """Law periods per pinion turn."""
        return int(round(2.0 * np.pi / self.theta_period))

    @property
    def wheel_periods(self) -> int:
        """Law periods per wheel turn."""
        return int(round(2.0 * np.pi / self.phi_period))

    def _fold(self, phi):
        phi = np.asarray(phi, dtype=float)
        turns = np.floor((phi - self.phi[0]) / self.phi_period)
        return phi - turns * self.phi_period, turns

    def ratio(self, phi):
        """U = dtheta/dphi (dimensionless) at driven angle phi (rad)."""
        if self.exact is not None:
            return crank.ratio(self.exact, phi)
        local, _ = self._fold(phi)
        return np.interp(local, self.phi, self.ratio_table)

    def pinion_angle(self, phi):
        """Driving angle theta (rad) for driven angle phi (rad), continued over periods."""
        if self.exact is not None:
            return crank.pinion_angle(self.exact, phi)
        local, turns = self._fold(phi)
        return np.interp(local, self.phi, self.theta) + turns * self.theta_period

    def carrier_angle(self, theta):
        """Driven angle phi (rad) for driving angle theta (rad): the law the check follows."""
        if self.exact is not None:
            return crank.carrier_angle(self.exact, theta)
        theta = np.asarray(theta, dtype=float)
        turns = np.floor((theta - self.theta[0]) / self.theta_period)
        local = theta - turns * self.theta_period
        return np.interp(local, self.theta, self.phi) + turns * self.phi_period

    def pinion_radius(self, phi):
        """Pinion pitch radius r = L/(1+U) in mm."""
        return self.center_distance / (1.0 + self.ratio(phi))

    def wheel_radius(self, phi):
        """Wheel pitch radius r_H = L U/(1+U) in mm."""
        u = self.ratio(phi)
        return self.center_distance * u / (1.0 + u)

    def scaled(self, center_distance: float) -> "PitchLaw":
        """The same law at another centre distance (mm)."""
        return PitchLaw(self.phi, self.theta, self.ratio_table, center_distance, self.corners,
                        self.hub_factor, _scaled_exact(self.exact, center_distance),
                        self.blended_corners, self.blend_half_width)


def _scaled_exact(exact, center_distance):
    if exact is None:
        return None
    return crank.CrankLaw(exact.a, exact.b, exact.c, center_distance, exact.turns)


def crank_pitch_law(law: crank.CrankLaw) -> PitchLaw:
    """The constant-hub-speed crank law of SPEC §3 (closed forms; corners at the handovers)."""
    phi = np.linspace(-np.pi / 4.0, np.pi / 4.0, TABLE_SAMPLES + 1)
    corners = (np.pi / 4.0,) if law.b > 0 else ()
    return PitchLaw(phi, crank.pinion_angle(law, phi), crank.ratio(law, phi), law.center_distance,
                    corners, lambda p: crank.hub_speed_analogue(law, p), law)


def blended_pitch_law(law: PitchLaw, half_width: float) -> PitchLaw:
    """The law with its ratio U(phi) smoothed by a periodic raised-cosine window.

    ``half_width`` (rad of the driven angle) is the window's half-width. The
    convolution keeps the mean of U, so theta still closes exactly over a period.
    """
    if half_width <= 0:
        return law
    n = TABLE_SAMPLES
    phi = law.phi[0] + law.phi_period * np.arange(n) / n
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
    return PitchLaw(phi, theta, smooth, law.center_distance, (), law.hub_factor, None,
                    law.corners, half_width)


def law_from_samples(theta_deg: np.ndarray, phi_deg: np.ndarray, center_distance: float,
                     param: str = "law-csv") -> PitchLaw:
    """A law from samples of the driven angle against the driving angle over one period (deg).

    The periodic part of phi(theta) is fitted by a Fourier series (least squares), so
    the ratio dtheta/dphi = 1/phi'(theta) is smooth. Both period lengths must divide
    a whole turn (closed gears).
    """
    theta = np.radians(np.asarray(theta_deg, dtype=float))
    phi = np.radians(np.asarray(phi_deg, dtype=float))
    require(theta.ndim == 1 and len(theta) >= 8 and len(theta) == len(phi), param, len(theta),
            "needs at least 8 rows of driving angle, driven angle (deg)")
    require(bool(np.all(np.diff(theta) > 0)) and bool(np.all(np.diff(phi) > 0)), param, "rows",
            "both angles must increase strictly over the period")
    theta_period, phi_period = theta[-1] - theta[0], phi[-1] - phi[0]
    for name, span in (("driving", theta_period), ("driven", phi_period)):
        count = 2.0 * np.pi / span
        require(abs(count - round(count)) < 1e-6 and round(count) >= 1, param, f"{np.degrees(span):g} deg",
                f"the {name} angle must span 360/k deg over one period (closed gears)")
    slope = phi_period / theta_period
    t = (theta - theta[0]) / theta_period * 2.0 * np.pi
    rest = phi - phi[0] - slope * (theta - theta[0])
    harmonics = max(1, min(48, (len(t) - 2) // 3))
    k = np.arange(1, harmonics + 1)
    basis = np.concatenate([np.ones((len(t), 1)), np.cos(np.outer(t, k)), np.sin(np.outer(t, k))], axis=1)
    coef, *_ = np.linalg.lstsq(basis, rest, rcond=None)
    residual = float(np.max(np.abs(basis @ coef - rest)))
    require(residual < 1e-3, param, f"{np.degrees(residual):.3g} deg",
            "the samples do not fit a smooth periodic law (residual > 0.06 deg)")
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
    return PitchLaw(phi_grid, theta_grid, 1.0 / dphi_dtheta, center_distance)


def read_law_csv(path, center_distance: float) -> PitchLaw:
    """Read ``driving_deg, driven_deg`` rows (header lines allowed) and build the law."""
    from pathlib import Path

    text = Path(path).read_text()
    rows = []
    for line in text.splitlines():
        cells = [c.strip() for c in line.replace(";", ",").split(",") if c.strip()]
        if len(cells) < 2:
            continue
        try:
            rows.append((float(cells[0]), float(cells[1])))
        except ValueError:
            continue  # a header line
    require(len(rows) >= 8, "law-csv", str(path), "needs at least 8 numeric rows 'driving_deg, driven_deg'")
    data = np.array(rows)
    return law_from_samples(data[:, 0], data[:, 1], center_distance)


@dataclass(frozen=True)
class PitchCurves:
    """Both pitch curves over one law period, densely sampled (closed forms, no sectors).

    ``phi`` driven angles (rad); ``pinion`` / ``wheel`` points (mm, own body frames);
    ``arc`` cumulative arc length (mm, same on both curves: they roll without slip).
    """

    law: PitchLaw
    phi: np.ndarray
    pinion: np.ndarray
    wheel: np.ndarray
    arc: np.ndarray

    @property
    def period_arc(self) -> float:
        return float(self.arc[-1])


def pitch_curves(law: PitchLaw, samples: int = 16384) -> PitchCurves:
    """Sample both pitch curves over one period starting at the law's first corner (or phi[0]).

    The arc length uses ds^2 = r^2 dtheta^2 + dr^2 (true perimeter, radial term included).
    """
    start = law.corners[0] - law.phi_period if law.corners else law.phi[0]
    phi = start + law.phi_period * np.linspace(0.0, 1.0, samples + 1)
    # nudge the end samples inside the period so a kink lands exactly on the end points
    theta = law.pinion_angle(phi)
    if law.corners:
        theta[0] = law.pinion_angle(start + 1e-12)
        theta[-1] = theta[0] + law.theta_period
    r = law.pinion_radius(phi)
    pinion = np.column_stack([r * np.cos(theta), r * np.sin(theta)])
    r_h = law.center_distance - r
    wheel = np.column_stack([r_h * np.cos(-phi), r_h * np.sin(-phi)])
    # Simpson-like accuracy from a fine trapezoid on the exact samples
    ds = np.hypot(*np.diff(pinion, axis=0).T)
    arc = np.concatenate(([0.0], np.cumsum(ds)))
    return PitchCurves(law, phi, pinion, wheel, arc)


def center_distance_for_module(law: PitchLaw, teeth_per_period: int, module: float) -> float:
    """Centre distance (mm) at which the pitch p = pi m fits ``teeth_per_period`` per period.

    The perimeter is proportional to L, so one evaluation at L = 1 suffices.
    """
    unit = pitch_curves(law.scaled(1.0), 65536).period_arc
    return np.pi * module * teeth_per_period / unit
