"""Polylines fitted as B-spline edges (geometry.spline_fit): within the tolerance both ways,
closed, joined exactly at the ring's own points, corners kept."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st
from scipy.interpolate import splev

from wheelstep_cli.geometry.spline_fit import BSpline, FitSettings, fit_pieces, fit_ring, joined


def hausdorff(edges, ring) -> float:
    """Distance (mm) between the edges, sampled densely, and the closed polyline, both ways."""
    curve = np.vstack([e.points(per_span=64) for e in edges])
    polyline = shapely.LineString(np.vstack([ring, ring[:1]]))
    fitted = shapely.LineString(np.vstack([curve, curve[:1]]))
    return max(shapely.distance(shapely.points(curve), polyline).max(),
               shapely.distance(shapely.points(ring), fitted).max())


@st.composite
def rough_rings(draw):
    """Star-shaped closed rings (mm) like gear outlines: teeth with sharp corners, steps and
    micrometre noise, 40 to 4000 points."""
    n = draw(st.integers(40, 4000))
    teeth = draw(st.integers(3, 60))
    radius = draw(st.floats(5.0, 120.0))
    height = draw(st.floats(0.0, 0.2)) * radius
    noise = draw(st.floats(0.0, 0.004))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    theta = np.sort(rng.uniform(0.0, 2 * np.pi, n))
    wave = np.clip(1.6 * np.sin(teeth * theta), -1.0, 1.0)          # flat tips and roots
    r = radius + height * wave + rng.normal(0.0, noise, n)
    ring = np.stack([r * np.cos(theta), r * np.sin(theta)], 1)
    return ring[np.linalg.norm(np.diff(ring, axis=0, append=ring[:1]), axis=1) > 1e-6]


@settings(max_examples=15, deadline=None, derandomize=True)
@given(rough_rings(), st.sampled_from([0.002, 0.005, 0.02]))
def test_a_fitted_ring_lies_within_the_tolerance_both_ways_and_closes_exactly(ring, tolerance):
    fit = FitSettings(tolerance=tolerance)
    edges = fit_ring(ring, fit)
    assert 1 <= len(edges) <= fit.max_edges
    assert hausdorff(edges, ring) <= tolerance
    for before, after in zip(edges, edges[1:] + edges[:1]):
        assert np.array_equal(before.poles[-1], after.poles[0])     # no gap for a CAD kernel
    starts = {tuple(e.poles[0]) for e in edges}
    assert starts <= {tuple(p) for p in ring}                      # edges end at ring points


def test_a_square_keeps_its_corners_and_straight_sides():
    side = np.linspace(0.0, 10.0, 50, endpoint=False)
    square = np.concatenate([np.stack([side, 0 * side], 1), np.stack([10 + 0 * side, side], 1),
                             np.stack([10 - side, 10 + 0 * side], 1), np.stack([0 * side, 10 - side], 1)])
    edges = fit_ring(square, FitSettings())
    assert len(edges) == 4
    assert sorted(tuple(e.poles[0]) for e in edges) == [(0, 0), (0, 10), (10, 0), (10, 10)]
    assert hausdorff(edges, square) < 1e-9


def test_a_joined_edge_runs_through_each_piece_over_one_unit_of_parameter():
    ring = np.stack([np.cos(t := np.linspace(0, 2 * np.pi, 300, endpoint=False)),
                     np.sin(t) * (1 + 0.3 * (np.cos(5 * t) > 0))], 1) * 20.0
    pieces = fit_pieces(ring, FitSettings())
    assert len(pieces) > 2
    edge = joined(pieces)
    u = np.linspace(0.0, 1.0, 7)
    for k, piece in enumerate(pieces):
        own = splev(piece.knots[0] + u * (piece.knots[-1] - piece.knots[0]),
                    (piece.knots, [piece.poles[:, 0], piece.poles[:, 1]], piece.degree))
        composite = splev(k + u, (edge.knots, [edge.poles[:, 0], edge.poles[:, 1]], edge.degree))
        assert np.allclose(own, composite, atol=1e-9)


def test_a_line_piece_is_the_segment():
    edges = fit_ring(np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0]]), FitSettings())
    assert isinstance(edges[0], BSpline)
    assert hausdorff(edges, np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0]])) == pytest.approx(0, abs=1e-12)


def test_a_repeated_corner_point_keeps_the_corner():
    square = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0], [0.0, 10.0]])
    edges = fit_ring(square, FitSettings())
    assert sorted(tuple(e.poles[0]) for e in edges) == [(0, 0), (0, 10), (10, 0), (10, 10)]
    with pytest.raises(ValueError):
        fit_ring(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]), FitSettings())


@pytest.mark.parametrize("lobes, most_poles", [(0, 40), (7, 120)])
def test_a_smooth_ring_is_a_few_cubic_poles_not_its_points(lobes, most_poles):
    """The fit does fit: a smooth 4000-point ring becomes one closed cubic edge with a few
    dozen poles (a fit that failed everywhere would fall back to the polyline, 4000 poles,
    and still pass the distance tests above)."""
    t = np.linspace(0.0, 2 * np.pi, 4000, endpoint=False)
    ring = (50.0 * (1.0 + 0.05 * np.cos(lobes * t)))[:, None] * np.stack([np.cos(t), np.sin(t)], 1)
    edges = fit_ring(ring, FitSettings())
    assert len(edges) == 1 and edges[0].degree == 3
    assert len(edges[0].poles) <= most_poles
    assert hausdorff(edges, ring) <= FitSettings().tolerance
