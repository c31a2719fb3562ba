"""Transmission laws for tests: any phi(theta) as a TransmissionLaw."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class FunctionLaw:
    """The law phi = ``driven(theta)`` (rad) repeating every ``theta_period`` rad of the pinion,
    with output speed factor ``hub(phi)`` (None: ones). Only what the meshing check reads."""

    driven: Callable[[np.ndarray], np.ndarray]
    theta_period: float
    hub: Callable[[np.ndarray], np.ndarray] | None = None
    corners: tuple[float, ...] = ()

    @property
    def phi_period(self) -> float:
        """Wheel angle (rad) over one period."""
        return float(self.driven(np.array([self.theta_period]))[0] - self.driven(np.zeros(1))[0])

    def carrier_angle(self, theta):
        return self.driven(theta)

    def hub_speed_factor(self, phi):
        phi = np.asarray(phi, dtype=float)
        return np.ones_like(phi) if self.hub is None else self.hub(phi)

    def ratio(self, phi):
        raise NotImplementedError("the meshing check reads only carrier_angle")

    def pinion_angle(self, phi):
        raise NotImplementedError("the meshing check reads only carrier_angle")
