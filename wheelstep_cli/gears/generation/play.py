"""How much backlash a law's hub speed tolerates (issue 13): the ripple a constant play costs.

A flank that carries an angular play delta of the wheel follows phi_law(theta) + delta:
the hub speed factor f is read delta off the angle the law compensates, so the hub speed
f(phi + delta) dphi/dtheta is no longer constant. Where the law has handover corners f's
slope jumps, and the hub speed steps by about delta times the jump of f'/f: on the source
design about 3.7 % per mm of normal play on the flank, whatever the teeth. The coast
flank used to carry 90 % of the play (1.96 % ripple on the default pair, drive 0.47 %).
Angles in radians, lengths in mm, ripple as a fraction.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.transmission import TransmissionLaw


class _Flank:
    """The law sampled once over a period (``samples`` pinion angles): a flank's hub speed
    for any constant lag without reading the law's angle and rate again."""

    def __init__(self, law: TransmissionLaw, samples: int = 4096):
        theta = law.theta_period * (np.arange(samples) + 0.5) / samples
        step = 1e-6
        self.law = law
        self.phi = np.asarray(law.carrier_angle(theta), dtype=float)
        self.rate = (np.asarray(law.carrier_angle(theta + step))
                     - np.asarray(law.carrier_angle(theta - step))) / (2 * step)

    def ripple(self, delta: float) -> float:
        """Peak-to-peak over mean hub speed (fraction) of the flank lagging by ``delta`` rad."""
        speed = np.asarray(self.law.hub_speed_factor(self.phi + delta), dtype=float) * self.rate
        mean = float(np.mean(speed))
        return float(np.ptp(speed)) / mean if mean > 0 else 0.0


def play_ripple(law: TransmissionLaw, delta: float, samples: int = 4096) -> float:
    """Hub speed ripple (fraction, peak-to-peak over mean) of a flank lagging the law by a
    constant wheel angle ``delta`` rad, over one period at ``samples`` pinion angles."""
    return _Flank(law, samples).ripple(delta)


def play_angle(backlash: float, wheel_curve: np.ndarray, pressure_angle: float) -> float:
    """Wheel angle (rad) one flank lags by when it carries half of ``backlash`` mm (normal):
    the half at the wheel's mean pitch radius (``wheel_curve`` (N, 2) mm), along the
    direction of motion."""
    mean_r = float(np.mean(np.hypot(*wheel_curve.T)))
    return backlash / 2.0 / (mean_r * np.cos(pressure_angle))


def largest_play(law: TransmissionLaw, budget: float, base: float = 0.0, upper: float = 0.05) -> float:
    """Largest wheel play angle (rad, <= ``upper``) whose ripple :func:`play_ripple` plus
    ``base`` (the rest of the flank's ripple, fraction) stays within ``budget`` (fraction);
    0 when even no play does."""
    return _largest_play(_Flank(law), budget, base, upper)


def _largest_play(flank: _Flank, budget: float, base: float, upper: float) -> float:
    """:func:`largest_play` of the sampled ``flank``."""
    if base + flank.ripple(0.0) > budget:
        return 0.0
    if base + flank.ripple(upper) <= budget:
        return upper
    lo, hi = 0.0, upper
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if base + flank.ripple(mid) <= budget else (lo, mid)
    return lo


def default_backlash(law: TransmissionLaw, wheel_curve: np.ndarray, pressure_angle: float,
                     budget: float, module: float) -> float:
    """Normal backlash (mm) generated teeth get when none is given: the most whose play
    costs each flank at most ``budget`` (fraction) of hub speed ripple, at most 0.25 x
    ``module`` mm (the usual allowance; a law with no hub speed factor takes that)."""
    usual = 0.25 * module
    # the budget is on top of the law's own ripple (a law that is not the crank law has one)
    flank = _Flank(law)
    play = _largest_play(flank, budget + flank.ripple(0.0), 0.0, 0.05)
    per_mm = play_angle(1.0, wheel_curve, pressure_angle)
    return float(min(usual, np.floor(1000.0 * play / per_mm) / 1000.0))
