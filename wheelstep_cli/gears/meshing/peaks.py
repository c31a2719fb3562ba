"""The transmission error's peaks measured between the poses (SPEC §10: F'i, f'i that converge).

A flank's TE is the first contact over several tooth pairs: where contact hands over from
one pair to the next the curve has a kink (a sharp least TE on the drive side, a sharp
greatest on the coast side) that lies between two poses, so peak-to-peak figures read off
the equal-step poses fall short of the continuous ones (the default pair's F'i by 7 %, f'i
by 13 %). The extremes that decide F'i and f'i are therefore searched again between the
poses: each by bisection, halving the step round the most extreme pose so far in every
round. Every value found is a measured pose, so a refined figure never exceeds the true one.
Angles in radians, lengths in mm, e in micrometres.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from wheelstep_cli.gears.meshing.figures import Track, pitch_windows


@dataclass(frozen=True)
class PeakPoses:
    """Poses measured between the equal steps: pinion angles ``theta`` (rad), the law's
    wheel angles ``phi_law`` and the contacts ``phi_drive`` / ``phi_coast`` (rad; NaN where
    the teeth overlap or no contact was found), the wheel's pitch radius (mm) and the arc
    along the wheel pitch curve from the period's first pose (mm, within the period)."""

    theta: np.ndarray
    phi_law: np.ndarray
    phi_drive: np.ndarray
    phi_coast: np.ndarray
    pitch_radius: np.ndarray
    arc: np.ndarray


def error_um(te: np.ndarray, pitch_radius: np.ndarray, mean: float) -> np.ndarray:
    """e = r_H (TE - mean TE) in um (SPEC §10), ``te`` rad, ``pitch_radius`` mm."""
    return 1000.0 * pitch_radius * (te - mean)


def _slack(e: np.ndarray) -> np.ndarray:
    """Per pose, how far the curve may pass its value between its neighbouring poses (um),
    were it two straight branches meeting in a kink there: a kink after pose k, at a fraction
    t of the step, lies a t down the branch through poses k-1, k and (1 - t) down the one
    through k+1, k+2, so at most s1 s2 / (s1 + s2) past e[k] (s1, s2 their steps); likewise
    a kink before it. The larger of the two."""
    def meet(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(a + b > 0.0, a * b / (a + b), 0.0)

    step = np.abs(np.diff(np.append(e, e[:1])))         # step[k]: pose k to pose k+1
    after = meet(np.roll(step, 1), np.roll(step, -1))     # branches k-1..k and k+1..k+2
    before = meet(np.roll(step, 2), step)                 # branches k-2..k-1 and k..k+1
    return np.maximum(after, before)


def candidates(e: np.ndarray, track: Track) -> tuple[np.ndarray, np.ndarray]:
    """(highs, lows): the poses whose value, passed between poses by its slack, could
    raise F'i or f'i: within a window one tooth pitch long whose peak-to-peak so passed
    could exceed the figure read off the poses, the poses that could pass its highest
    (highs) or lowest (lows) value; the whole period likewise for F'i."""
    slack = _slack(e)
    up, down = e + slack, e - slack
    index, inside = pitch_windows(track.arc, track.arc_total, track.pitch)
    twice = np.concatenate([e, e])
    top = np.where(inside, twice[index], -np.inf).max(axis=1)
    bottom = np.where(inside, twice[index], np.inf).min(axis=1)
    ups, downs = np.concatenate([up, up])[index], np.concatenate([down, down])[index]
    could = np.where(inside, ups, -np.inf).max(axis=1) - np.where(inside, downs, np.inf).min(axis=1)
    open_window = could > float(np.max(top - bottom))
    n = len(e)
    high = inside & open_window[:, None] & (ups >= top[:, None])
    low = inside & open_window[:, None] & (downs <= bottom[:, None])
    highs = np.unique(np.concatenate([index[high] % n, np.flatnonzero(up >= e.max())]))
    lows = np.unique(np.concatenate([index[low] % n, np.flatnonzero(down <= e.min())]))
    return highs, lows


def refine_peaks(theta: np.ndarray, errors: dict[str, np.ndarray], track: Track, rounds: int,
                 measure: Callable[[np.ndarray], dict[str, np.ndarray]]) -> tuple[np.ndarray, dict]:
    """Bisection round the candidate extremes of each flank's e (um per equal-step pose
    ``theta`` rad, by flank name in ``errors``): ``rounds`` rounds, each measuring the two
    poses half the previous step either side of every search's most extreme pose so far
    (``measure(theta)`` gives e per flank name at any pinion angles, NaN where none).
    Returns (every pinion angle measured, e per flank at them)."""
    step = float(theta[1] - theta[0]) if len(theta) > 1 else 0.0
    searches = []                       # (flank, +1 highest / -1 lowest, theta, e)
    for flank, e in errors.items():
        if not np.all(np.isfinite(e)):
            continue
        highs, lows = candidates(e, track)
        searches += [(flank, 1.0, theta[k], e[k]) for k in highs]
        searches += [(flank, -1.0, theta[k], e[k]) for k in lows]
    measured, values = [], {flank: [] for flank in errors}
    for level in range(1, rounds + 1):
        if not searches:
            break
        at = np.array([s[2] for s in searches])
        poses = np.concatenate([at - step / 2 ** level, at + step / 2 ** level])
        found = measure(poses)
        measured.append(poses)
        for flank in errors:
            values[flank].append(found[flank])
        half = len(searches)
        moved = []
        for j, (flank, sign, best_at, best) in enumerate(searches):
            for q in (j, j + half):
                value = found[flank][q]
                if np.isfinite(value) and sign * value > sign * best:
                    best_at, best = poses[q], value
            moved.append((flank, sign, best_at, best))
        searches = moved
    if not measured:
        return np.zeros(0), {flank: np.zeros(0) for flank in errors}
    return np.concatenate(measured), {flank: np.concatenate(v) for flank, v in values.items()}
