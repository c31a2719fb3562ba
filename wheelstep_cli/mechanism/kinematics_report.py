"""What ``wheelstep kinematics`` reports: hub speed over one shoe cycle with a constant-speed
motor, without and with the non-circular gears, as plain data (m/s, deg at the edge)."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.errors import require
from wheelstep_cli.mechanism.kinematics import HubKinematics, hub_kinematics
from wheelstep_cli.mechanism.shoe import ShoeDesign


def check_inputs(motor_rpm: float, points: int, rows: int) -> None:
    """Raise DesignError unless the motor speed (rpm) is > 0, points >= 3 and rows >= 2."""
    require(np.isfinite(motor_rpm) and motor_rpm > 0, "motor-rpm", motor_rpm, "must be > 0")
    require(points >= 3, "points", points, "must be >= 3")
    require(rows >= 2, "rows", rows, "must be >= 2")


def hub_speed_study(design: ShoeDesign, turns: int, motor_rpm: float, points: int) -> HubKinematics:
    """Hub kinematics at ``motor_rpm`` (pinion, rpm) over ``points`` samples of one cycle."""
    return hub_kinematics(design, motor_rpm * 2.0 * np.pi / 60.0, turns, points)


def _speeds(speed: np.ndarray, ripple: float) -> dict:
    return {"min_m_s": speed.min() / 1000.0, "max_m_s": speed.max() / 1000.0,
            "ripple_pct": 100.0 * ripple}


def kinematics_report(design: ShoeDesign, kin: HubKinematics, motor_rpm: float) -> dict:
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
