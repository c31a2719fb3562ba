"""A transmission law read over its whole cycle: what outlines that do not repeat every
period of the law (a printed pair, SPEC §11) are checked over.

A designed pair repeats every period of its law, so one period shows every pose it takes.
A printed pair does not: each of its teeth is its own. Its poses repeat only when both gears
are back where they started, after lcm(pinion_periods, wheel_periods) periods of the law:
one wheel turn when the pinion's periods divide the wheel's (every crank law: 4 periods, in
which the pinion turns 2 or 1 times). Over that cycle every pinion tooth meets every wheel
tooth it will meet. Angles in rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wheelstep_cli.gears.transmission import TransmissionLaw


@dataclass(frozen=True)
class WholeCycle:
    """``law`` with its period taken as the whole cycle of :attr:`periods` law periods.

    What the meshing check reads (``carrier_angle``, ``theta_period``, ``corners``,
    ``hub_speed_factor``) and the law's other functions of angle, which continue over
    periods, are passed through. A cycle spans whole turns of both gears, so it has no
    whole number of periods per turn: it is a law to check outlines over, not to cut gears
    from (no ``pinion_periods`` / ``wheel_periods``; :attr:`pinion_turns` and
    :attr:`wheel_turns` say what a cycle turns).
    """

    law: TransmissionLaw

    @property
    def periods(self) -> int:
        """Law periods in the cycle: the least whole turn of both gears."""
        return math.lcm(int(self.law.pinion_periods), int(self.law.wheel_periods))

    @property
    def pinion_turns(self) -> int:
        """Pinion turns in the cycle."""
        return self.periods // int(self.law.pinion_periods)

    @property
    def wheel_turns(self) -> int:
        """Wheel turns in the cycle."""
        return self.periods // int(self.law.wheel_periods)

    @property
    def phi_start(self) -> float:
        """Driven angle where the cycle starts (the law's first period's start), rad."""
        return float(self.law.phi_start)

    @property
    def phi_period(self) -> float:
        """Driven angle of the cycle, rad."""
        return self.periods * float(self.law.phi_period)

    @property
    def theta_period(self) -> float:
        """Driving angle of the cycle, rad."""
        return self.periods * float(self.law.theta_period)

    @property
    def corners(self) -> tuple[float, ...]:
        """Driven angles (rad, in the cycle) where the ratio kinks: the law's in every period."""
        step = float(self.law.phi_period)
        return tuple(float(c) + k * step for k in range(self.periods) for c in self.law.corners)

    def ratio(self, phi) -> np.ndarray:
        """U = dtheta/dphi (dimensionless) at driven angle phi (rad): the law's."""
        return self.law.ratio(phi)

    def pinion_angle(self, phi) -> np.ndarray:
        """Driving angle (rad) for driven angle phi (rad): the law's, continued over periods."""
        return self.law.pinion_angle(phi)

    def carrier_angle(self, theta) -> np.ndarray:
        """Driven angle (rad) for driving angle theta (rad): the law's, continued over periods."""
        return self.law.carrier_angle(theta)

    def hub_speed_factor(self, phi) -> np.ndarray:
        """Output speed per unit driven speed at phi (rad): the law's."""
        return self.law.hub_speed_factor(phi)
