"""The transmission law a gear pair should follow: one protocol for every law.

The pinion (driving, angle ``theta``) drives the wheel (driven, angle ``phi``). Angles
in radians; array arguments and results are numpy arrays of the same shape.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np


class TransmissionLaw(Protocol):
    """A monotone, periodic law phi(theta) between the pinion and the wheel."""

    @property
    def phi_period(self) -> float:
        """Driven (wheel) angle (rad) after which the law repeats."""
        ...

    @property
    def theta_period(self) -> float:
        """Driving (pinion) angle (rad) after which the law repeats."""
        ...

    @property
    def corners(self) -> tuple[float, ...]:
        """Driven angles (rad, inside one period) where the ratio has a kink."""
        ...

    def ratio(self, phi: np.ndarray) -> np.ndarray:
        """Transfer ratio U = dtheta/dphi (dimensionless) at driven angles phi (rad)."""
        ...

    def pinion_angle(self, phi: np.ndarray) -> np.ndarray:
        """Driving angle theta (rad) for driven angles phi (rad), continued over periods."""
        ...

    def carrier_angle(self, theta: np.ndarray) -> np.ndarray:
        """Driven angle phi (rad) for driving angles theta (rad), continued over periods."""
        ...

    def hub_speed_factor(self, phi: np.ndarray) -> np.ndarray:
        """Output speed per unit driven speed at driven angles phi (rad); ones for a law
        with no mechanism behind it."""
        ...
