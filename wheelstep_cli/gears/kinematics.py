"""Hub speed over one shoe cycle with a constant-speed motor, with and without the
non-circular gears (SPEC §2, §3).

Without them the motor drives the carrier through a circular pair of the same mean
ratio (``turns`` pinion turns per carrier turn), so the carrier turns at omega/turns and
the hub speed follows dX01/dphi. With them the carrier turns at omega_H = omega / U(phi)
and v = omega_H dX01/dphi = omega k / u is constant. Both make one shoe cycle in the
same time. The gears may follow another law whose driven angle is the carrier's (a
blended crank law, a law CSV): their ratio U(phi) is then the law's, and the hub speed
ripples as the law departs from the crank law. Speeds in mm/s, angles in rad; the report
(what ``wheelstep kinematics`` prints) in m/s and degrees.
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
    turns: int | float          # pinion turns per carrier turn (the law's mean ratio)
    ripple_plain: float         # peak-to-peak over time-mean without the gears (fraction)
    ripple_geared: float        # with them (fraction; 0 up to rounding on the crank law)
    range_plain: tuple          # (least, greatest) speed over the cycle without them, mm/s
    range_geared: tuple         # with them, mm/s

    @property
    def cycle_time(self) -> float:
        """Time for one shoe cycle (a quarter carrier turn), s; the same with or without."""
        return self.turns * (np.pi / 2.0) / self.motor_speed


def hub_kinematics(design: CrankMechanism, motor_speed: float, turns: int = 2,
                   count: int = 361, law=None) -> HubKinematics:
    """Hub speed over one shoe cycle at pinion (motor) speed ``motor_speed`` rad/s, with gears
    following ``law`` (a TransmissionLaw whose driven angle is the carrier's and that repeats
    within the shoe cycle; None: the crank law of ``turns``)."""
    if law is None:
        law = CrankLaw(design, turns)
    mean_ratio = law.theta_period / law.phi_period

    def speeds(phi):
        analogue, u_phi = design.speed_analogue(phi), law.ratio(phi)
        return motor_speed / mean_ratio * analogue, motor_speed / u_phi * analogue, u_phi

    phi = contact_angles(count)
    plain, geared, u_phi = speeds(phi)
    # the ripples of the cycle, not of the samples shown: ``count`` samples may step over the
    # extremes (4 miss phi = 0); the carrier's equal angle steps last U dphi / omega, so the
    # geared mean is weighted by U
    fine_plain, fine_geared, fine_u = speeds(contact_angles(max(count, RIPPLE_SAMPLES)))
    return HubKinematics(
        phi=phi, speed_plain=plain, speed_geared=geared, ratio=u_phi, motor_speed=float(motor_speed),
        turns=int(round(mean_ratio)) if abs(mean_ratio - round(mean_ratio)) < 1e-9 else float(mean_ratio),
        ripple_plain=speed_ripple(fine_plain), ripple_geared=speed_ripple(fine_geared, fine_u),
        range_plain=(float(fine_plain.min()), float(fine_plain.max())),
        range_geared=(float(fine_geared.min()), float(fine_geared.max())))


#: Samples of the shoe cycle the ripples are read on (odd: mid-stance, phi = 0, is one), at
#: least as many as shown: a cosine's peak is then within 1e-7 of its sampled maximum.
RIPPLE_SAMPLES = 36001


def require_shoe_cycle_period(law, param: str, value) -> None:
    """Refuse (DesignError of ``param`` = ``value``) a law that does not repeat within the
    shoe cycle (a quarter carrier turn): the hub speed of its gears has no cycle."""
    periods = law.wheel_periods
    require(periods % 4 == 0 and abs(law.phi_period * periods - 2.0 * np.pi) < 1e-6, param, value,
            f"repeats every {np.degrees(law.phi_period):.6g} deg of the driven angle; the mover's shoe "
            "cycle is a quarter carrier turn (90 deg), so the law's period must divide 90 deg")


def check_inputs(motor_rpm: float, points: int, rows: int) -> None:
    """Raise DesignError unless the motor speed is 1e-3..1e6 rpm, points 3..100000 and rows
    2..10000 (bounds that keep the work and the figures finite), and no more rows than points
    (the table prints samples: more rows than samples would print the samples only)."""
    require(np.isfinite(motor_rpm) and 1e-3 <= motor_rpm <= 1e6, "motor_rpm", motor_rpm,
            "must be 0.001..1e6 rpm")
    require(3 <= points <= 100_000, "points", points, "must be 3..100000")
    require(2 <= rows <= 10_000, "rows", rows, "must be 2..10000")
    require(rows <= points, "rows", rows, f"must be <= --points = {points} (the table prints samples of the "
                                          "cycle; give more --points for more rows)")


def hub_speed_study(design: CrankMechanism, turns: int, motor_rpm: float, points: int,
                    law=None) -> HubKinematics:
    """Hub kinematics at ``motor_rpm`` (pinion, rpm) over ``points`` samples of one cycle,
    with gears following ``law`` (None: the crank law)."""
    return hub_kinematics(design, motor_rpm * 2.0 * np.pi / 60.0, turns, points, law)


def _speeds(span: tuple, ripple: float) -> dict:
    return {"min_m_s": span[0] / 1000.0, "max_m_s": span[1] / 1000.0, "ripple_pct": 100.0 * ripple}


def kinematics_report(design: CrankMechanism, kin: HubKinematics, motor_rpm: float,
                      law: str = "the crank law") -> dict:
    """The mechanism, cycle time (s), mean speed and both speed curves (m/s) over the cycle;
    ``law`` says what the gears follow."""
    return {
        "a_mm": design.a, "b_mm": design.b, "c_mm": design.c, "r_min_mm": design.r_min,
        "turns": kin.turns, "motor_rpm": motor_rpm, "cycle_time_s": kin.cycle_time,
        "x_cycle_mm": design.x_cycle,
        "mean_speed_m_s": design.x_cycle / kin.cycle_time / 1000.0,
        "without_gears": _speeds(kin.range_plain, kin.ripple_plain),
        "with_gears": {**_speeds(kin.range_geared, kin.ripple_geared), "law": law},
        "curve": {"phi_deg": np.degrees(kin.phi), "without_m_s": kin.speed_plain / 1000.0,
                  "with_m_s": kin.speed_geared / 1000.0, "ratio_u": kin.ratio},
    }


def table_rows(samples: int, rows: int) -> np.ndarray:
    """Indices of about ``rows`` samples spread evenly over ``samples``, both ends included."""
    return np.unique(np.linspace(0, samples - 1, rows).round().astype(int))
