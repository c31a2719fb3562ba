"""Ring simplification (geometry.planar.simplify_ring): the fast path keeps what the
topology-preserving simplifier keeps."""

import numpy as np
import pytest
import shapely

from wheelstep_cli.geometry.planar import simplify_ring


def _gear_like(teeth: int, points: int, start: float) -> np.ndarray:
    """A dense wavy ring (mm) like a ray-map gear outline, starting at body angle ``start``."""
    angle = start + np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    radius = 50.0 + 2.0 * np.clip(3.0 * np.sin(teeth * angle), -1.0, 1.0)
    return np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])


@pytest.mark.parametrize("start", [0.0, 0.013, 0.5])      # first point on a flat, a flank, a kink
@pytest.mark.parametrize("tolerance", [1e-4, 5e-4, 1e-2])
def test_simplified_ring_equals_the_topology_preserving_one(start, tolerance):
    ring = _gear_like(24, 20000, start)
    ring += np.random.default_rng(3).normal(0.0, 2e-5, ring.shape)      # micron noise to thin
    expected = np.asarray(shapely.simplify(shapely.LinearRing(ring), tolerance,
                                           preserve_topology=True).coords)[:-1]
    got = simplify_ring(ring, tolerance)
    assert len(got) < len(ring) / 4
    assert np.array_equal(got, expected)


def test_a_ring_plain_simplification_would_tangle_goes_the_slow_way():
    # a star-shaped ring whose plain Douglas-Peucker simplification at 2.27 mm crosses itself
    ring = np.array([[1.628, 5.288], [1.539, 8.891], [-1.985, 8.57], [-1.807, 6.686],
                     [-7.523, -0.72], [-8.885, -1.056], [-9.533, -2.985], [-5.237, -2.208],
                     [-3.143, -5.011], [-1.268, -5.244], [-2.156, -9.3], [-0.831, -8.775]])
    tolerance = 2.2707
    assert not shapely.simplify(shapely.LinearRing(ring), tolerance, preserve_topology=False).is_simple
    expected = np.asarray(shapely.simplify(shapely.LinearRing(ring), tolerance,
                                           preserve_topology=True).coords)[:-1]
    got = simplify_ring(ring, tolerance)
    assert shapely.LinearRing(got).is_simple
    assert np.array_equal(got, expected)
