"""Assembly phase of a gear pair: which body directions meet on the line of centres.

The meshing check (SPEC §10) poses the pinion at its origin turned by -theta and the wheel
at (D, 0) turned by pi + phi, with phi = law.carrier_angle(theta). So the pinion's body
direction theta and the wheel's body direction -phi lie on the line of centres, facing
each other. The carrier is at 0 when phi = 0 (a shoe in mid-stance: the law's period runs
from one shoe handover at -pi/4 to the next at +pi/4). Angles in radians, numpy only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class AssemblyPhase:
    """Body angles (rad, in each gear's own frame) that meet at the line of centres.

    ``pinion_mark``/``wheel_mark``: with the carrier at 0. ``handover_pinion`` /
    ``handover_wheel``: at each shoe handover of one wheel turn (phi = pi/4 + k pi/2 for the
    crank law; the law's period boundaries in general), both wrapped into [0, 2 pi).
    ``handover_phi``: the carrier angles of those handovers.
    """

    pinion_mark: float
    wheel_mark: float
    handover_phi: tuple[float, ...]
    handover_pinion: tuple[float, ...]
    handover_wheel: tuple[float, ...]


def _wrap(angle) -> np.ndarray:
    return np.mod(np.asarray(angle, dtype=float), 2.0 * np.pi)


def assembly_phase(law) -> AssemblyPhase:
    """The phase of a pair following ``law`` (a gears.transmission.TransmissionLaw)."""
    start = float(law.phi_start)
    period = float(law.phi_period)
    # handovers are the period boundaries (start at a handover); one wheel turn holds
    # wheel_periods of them
    count = max(1, int(law.wheel_periods))
    phi = start + period * np.arange(count)
    pinion = _wrap(law.pinion_angle(phi))
    return AssemblyPhase(float(_wrap(law.pinion_angle(0.0))), 0.0,
                         tuple(float(p) for p in phi),
                         tuple(float(p) for p in pinion), tuple(float(w) for w in _wrap(-phi)))


def phase_record(phase: AssemblyPhase) -> dict:
    """What gears.json says of the phase, in degrees at this edge."""
    deg = np.degrees
    return {
        "convention": "body angles in each gear's own frame (the written mesh's x axis = 0, "
                      "counter-clockwise seen from the top face); the two angles of a row face "
                      "each other on the line of centres",
        "carrier_zero": {"pinion_deg": float(deg(phase.pinion_mark)),
                         "wheel_deg": float(deg(phase.wheel_mark)),
                         "note": "a shoe in mid-stance; the timing marks point along these "
                                 "directions, the wheel's also marks the carrier's reference"},
        "handovers": [{"carrier_deg": float(deg(c)), "pinion_deg": float(deg(p)),
                       "wheel_deg": float(deg(w))}
                      for c, p, w in zip(phase.handover_phi, phase.handover_pinion,
                                         phase.handover_wheel)],
    }
