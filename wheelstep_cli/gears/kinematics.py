"""Hub speed over one shoe cycle with a constant-speed motor, with and without the
non-circular gears (SPEC §2, §3).

Without them the motor drives the carrier through a circular pair of the same mean
ratio (``turns`` pinion turns per carrier turn), so the carrier turns at omega/turns and
the hub speed follows dX01/dphi. With them the carrier turns at omega_H = omega / U(phi)
and v = omega_H dX01/dphi = omega k / u is constant. Both make one shoe cycle in the
same time. Speeds in mm/s, angles in rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
