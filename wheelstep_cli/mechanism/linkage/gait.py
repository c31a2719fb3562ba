"""Gait of a solved walking linkage: stride, lift, duty factor, foot and body speeds (SPEC §7).

Units: millimetres, radians, mm/s.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError
from wheelstep_cli.mechanism.linkage.solver import Linkage, Solution, is_full_cycle


@dataclass(frozen=True)
class Gait:
    """Foot path and what it means for walking, at a constant crank speed.

    Lengths mm, speeds mm/s. ``support`` marks the samples of the support phase: the
    contiguous part of the cycle, around the lowest point, within ``ground_tol`` of the
    ground line (the lowest level the foot reaches).
    """

    theta: np.ndarray
    foot: np.ndarray
    velocity: np.ndarray
    speed: np.ndarray
    support: np.ndarray
    ground_level: float
    ground_tol: float
    stride: float
    lift: float
    duty_factor: float
    body_speed: np.ndarray      # -vx of the foot while it stands, nan elsewhere
    omega: float


def gait(linkage: Linkage, solution: Solution, rpm: float, ground_tol: float | None = None) -> Gait:
    """Stride, lift, duty factor, foot and body speeds of the linkage's foot over one cycle.

    Velocities are the exact joint rates of :func:`solve` times the crank speed.
    ``ground_tol`` defaults to 1 % of the lift.
    """
    theta = solution.theta
    if not is_full_cycle(theta) or theta.size < 8:
        raise DesignError("samples", theta.size, "gait analysis needs one full crank turn of >= 8 samples")
    foot = solution.joints[linkage.foot]
    omega = rpm * 2 * np.pi / 60.0
    velocity = solution.rates[linkage.foot] * omega
    speed = np.hypot(velocity[:, 0], velocity[:, 1])
    depth = linkage.ground * foot[:, 1]          # grows toward the ground
    ground_level = float(depth.max())
    lift = float(depth.max() - depth.min())
    tol = 0.01 * lift if ground_tol is None else float(ground_tol)
    near = depth >= ground_level - tol
    support = _run_around(near, int(np.argmax(depth)))
    xs = foot[support, 0]
    stride = float(xs.max() - xs.min())
    body = np.full(theta.size, np.nan)
    body[support] = -velocity[support, 0]
    return Gait(theta=theta, foot=foot, velocity=velocity, speed=speed, support=support,
                ground_level=float(linkage.ground * ground_level), ground_tol=tol, stride=stride,
                lift=lift, duty_factor=float(support.mean()), body_speed=body, omega=omega)


def _run_around(mask: np.ndarray, k: int) -> np.ndarray:
    """The contiguous (cyclic) run of True in ``mask`` that contains index ``k`` (mask[k] True)."""
    if mask.all():
        return mask.copy()
    m = np.roll(mask, -k)                       # the run now starts at index 0 ...
    ahead = int(np.argmin(m))                   # ... and ends before the first False
    behind = int(np.argmin(m[::-1]))            # ... or wraps round from the end
    run = np.zeros_like(m)
    run[:ahead] = True
    if behind:
        run[-behind:] = True
    return np.roll(run, k)
