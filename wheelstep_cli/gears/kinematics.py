"""Hub speed over one shoe cycle with a constant-speed motor, with and without the
non-circular gears (SPEC §2, §3).

Without them the motor drives the carrier through a circular pair of the same mean
ratio (``turns`` pinion turns per carrier turn), so the carrier turns at omega/turns and
the hub speed follows dX01/dphi. With them the carrier turns at omega_H = omega / U(phi)
and v = omega_H dX01/dphi = omega k / u is constant. Both make one shoe cycle in the
same time. Speeds in mm/s, angles in rad; the report (what ``wheelstep kinematics``
prints) in m/s and degrees.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import require
from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.mechanism.crank import CrankMechanism
from wheelstep_cli.mechanism.sole import contact_angles, speed_ripple


@dataclass(frozen=True)
class HubKinematics:
    """Hub speed samples over one shoe cycle (phi = -pi/4..pi/4, equally spaced)."""

    phi: np.ndarray             # hub (carrier) angle, rad
    speed_plain: np.ndarray     # circular gears, mm/s
    speed_geared: np.ndarray    # non-circular gears, mm/s
    ratio: np.ndarray           # U(phi) = omega / omega_H of the non-circular pair
    motor_speed: float          # rad/s
    turns: int

    @property
    def ripple_plain(self) -> float:
        """Peak-to-peak over time-mean without the non-circular gears (fraction)."""
        return speed_ripple(self.speed_plain)

    @property
    def ripple_geared(self) -> float:
        """Peak-to-peak over mean with them (fraction; 0 up to rounding)."""
        return float(np.ptp(self.speed_geared) / self.speed_geared.mean())

    @property
    def cycle_time(self) -> float:
        """Time for one shoe cycle (a quarter carrier turn), s; the same with or without."""
        return self.turns * (np.pi / 2.0) / self.motor_speed


def hub_kinematics(design: CrankMechanism, motor_speed: float, turns: int = 2,
                   count: int = 361) -> HubKinematics:
    """Hub speed over one shoe cycle at pinion (motor) speed ``motor_speed`` rad/s."""
    law = CrankLaw(design, turns)
    phi = contact_angles(count)
    analogue = design.speed_analogue(phi)
    u_phi = law.ratio(phi)
    return HubKinematics(
        phi=phi,
        speed_plain=motor_speed / turns * analogue,
        speed_geared=motor_speed / u_phi * analogue,
        ratio=u_phi,
        motor_speed=float(motor_speed),
        turns=turns,
    )


def check_inputs(motor_rpm: float, points: int, rows: int) -> None:
    """Raise DesignError unless the motor speed is 1e-3..1e6 rpm, points 3..100000 and rows
    2..10000 (bounds that keep the work and the figures finite)."""
    require(np.isfinite(motor_rpm) and 1e-3 <= motor_rpm <= 1e6, "motor_rpm", motor_rpm,
            "must be 0.001..1e6 rpm")
    require(3 <= points <= 100_000, "points", points, "must be 3..100000")
    require(2 <= rows <= 10_000, "rows", rows, "must be 2..10000")


def hub_speed_study(design: CrankMechanism, turns: int, motor_rpm: float, points: int) -> HubKinematics:
    """Hub kinematics at ``motor_rpm`` (pinion, rpm) over ``points`` samples of one cycle."""
    return hub_kinematics(design, motor_rpm * 2.0 * np.pi / 60.0, turns, points)


def _speeds(speed: np.ndarray, ripple: float) -> dict:
    return {"min_m_s": speed.min() / 1000.0, "max_m_s": speed.max() / 1000.0,
            "ripple_pct": 100.0 * ripple}


def kinematics_report(design: CrankMechanism, kin: HubKinematics, motor_rpm: float) -> dict:
    """The mechanism, cycle time (s), mean speed and both speed curves (m/s) over the cycle."""
    return {
        "a_mm": design.a, "b_mm": design.b, "c_mm": design.c, "r_min_mm": design.r_min,
        "turns": kin.turns, "motor_rpm": motor_rpm, "cycle_time_s": kin.cycle_time,
        "x_cycle_mm": design.x_cycle,
        "mean_speed_m_s": design.x_cycle / kin.cycle_time / 1000.0,
        "without_gears": _speeds(kin.speed_plain, kin.ripple_plain),
        "with_gears": _speeds(kin.speed_geared, kin.ripple_geared),
        "curve": {"phi_deg": np.degrees(kin.phi), "without_m_s": kin.speed_plain / 1000.0,
                  "with_m_s": kin.speed_geared / 1000.0, "ratio_u": kin.ratio},
    }


def table_rows(samples: int, rows: int) -> np.ndarray:
    """Indices of about ``rows`` samples spread evenly over ``samples``, both ends included."""
    return np.unique(np.linspace(0, samples - 1, rows).round().astype(int))
