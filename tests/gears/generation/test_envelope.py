"""Polar envelopes: skipping segments that cannot come nearer never changes a ray."""

import numpy as np
import pytest

from wheelstep_cli.gears.generation.envelope import PolarGrid, _range_max, polyline_envelope


def _cutter_poses(rng, poses: int, points: int) -> np.ndarray:
    """A wavy closed-ish curve of radius ~50 mm, rotated and pushed in and out per pose (mm)."""
    t = np.linspace(0.0, 1.2, points)
    base = 50.0 + 3.0 * np.sin(40.0 * t)
    angle = rng.uniform(-np.pi, np.pi, poses)[:, None] + t[None, :]
    radius = base[None, :] + rng.uniform(-4.0, 4.0, poses)[:, None]
    return np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)


def _one_by_one(grid, polylines, out, reach=np.inf):
    """The envelope folded one polyline at a time (nothing to skip against)."""
    for polyline in polylines:
        polyline_envelope(grid, polyline[None], out=out, reach=reach)
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_nearest_envelope_is_bit_identical_to_folding_one_by_one(seed):
    rng = np.random.default_rng(seed)
    grid = PolarGrid(-np.pi, 2.0 * np.pi, 5000)
    polylines = _cutter_poses(rng, 120, 300)
    fast = polyline_envelope(grid, polylines)
    slow = _one_by_one(grid, polylines, np.full(grid.count, np.inf))
    assert np.isfinite(fast).sum() > 4000
    assert fast.tobytes() == slow.tobytes()


def test_folding_into_given_radii_with_a_reach_matches_too():
    rng = np.random.default_rng(7)
    grid = PolarGrid(0.3, np.pi, 3000)
    start = np.where(rng.random(grid.count) < 0.2, np.inf, rng.uniform(46.0, 56.0, grid.count))
    polylines = _cutter_poses(rng, 90, 200)
    fast = polyline_envelope(grid, polylines, out=start.copy(), reach=53.0)
    slow = _one_by_one(grid, polylines, start.copy(), reach=53.0)
    assert (fast < start).sum() > 100   # the cutter did lower some rays
    assert fast.tobytes() == slow.tobytes()


def test_range_bound_holds_round_the_period():
    rng = np.random.default_rng(3)
    values = rng.normal(size=100)
    values[5] = np.inf
    lo = rng.integers(-250, 250, 2000)
    counts = rng.integers(0, 40, 2000)
    got = _range_max(values, lo, counts, block=16)
    for g, start, count in zip(got, lo, counts):
        expected = values[np.mod(start + np.arange(count), 100)].max() if count else -np.inf
        assert g >= expected
    assert np.isfinite(got[(counts > 0) & (counts <= 16)]).mean() > 0.6   # it does bound
    # a range inside one block is bounded by that block's largest value
    assert _range_max(values, np.array([33, 133]), np.array([3, 3]), block=16).tolist() == \
        [values[32:48].max()] * 2
