"""The transmission law protocol: what a gear pair's motion must say about itself.

A law ties the driving (pinion) angle ``theta`` to the driven (wheel) angle ``phi``
(rad) over a period that repeats. Implementations: :class:`~wheelstep_cli.gears.laws.CrankLaw`
(the mover's constant-hub-speed law) and :class:`~wheelstep_cli.gears.laws.TabulatedLaw`
(samples from a CSV file, blends).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np


class TransmissionLaw(Protocol):
    """A periodic, monotone law theta(phi); angles in rad."""

    @property
    def phi_start(self) -> float:
        """Driven angle where one tabulated period starts, rad."""

    @property
    def phi_period(self) -> float:
        """Driven angle of one period, rad."""

    @property
    def theta_period(self) -> float:
        """Driving angle of one period, rad."""

    @property
    def corners(self) -> tuple[float, ...]:
        """Driven angles (rad, inside one period) where the ratio kinks."""

    @property
    def pinion_periods(self) -> int:
        """Periods per pinion turn."""

    @property
    def wheel_periods(self) -> int:
        """Periods per wheel turn."""

    def ratio(self, phi) -> np.ndarray:
        """U = dtheta/dphi (dimensionless) at driven angle phi."""

    def pinion_angle(self, phi) -> np.ndarray:
        """Driving angle for driven angle phi, continued over periods."""

    def carrier_angle(self, theta) -> np.ndarray:
        """Driven angle for driving angle theta (the inverse of pinion_angle)."""

    def hub_speed_factor(self, phi) -> np.ndarray:
        """Output speed per unit driven speed at phi (ones for a law with no mechanism)."""
