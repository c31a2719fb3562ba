"""Exact polygon offsets of outlines (SPEC §11)."""

import numpy as np
import pytest

from wheelstep_cli.errors import DesignError
from wheelstep_cli.geometry.planar import offset_outline


def _circle(radius: float, n: int = 4000) -> np.ndarray:
    t = 2 * np.pi * np.arange(n) / n
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)])


@pytest.mark.parametrize("distance", [0.1, -0.1, 0.05, -0.25])
@pytest.mark.parametrize("thin", [None, "band"])
def test_offset_of_a_circle_has_the_offset_radius_to_1_um(distance, thin):
    """At its vertices and between them (the band's cases thin their offsets further)."""
    from wheelstep_cli.parts.tolerance import OFFSET_THIN

    grown = (offset_outline(_circle(10.0), distance) if thin is None
             else offset_outline(_circle(10.0), distance, thin=OFFSET_THIN))
    middles = 0.5 * (grown + np.roll(grown, -1, axis=0))
    for points in (grown, middles):
        radius = np.hypot(points[:, 0], points[:, 1])
        assert np.abs(radius - (10.0 + distance)).max() < 1e-3


def test_offset_of_a_square_keeps_its_edges_at_the_distance_and_rounds_its_corners():
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    grown = offset_outline(square, 0.2)
    assert grown[:, 0].min() == pytest.approx(-0.2) and grown[:, 1].max() == pytest.approx(10.2)
    corner = np.hypot(grown[:, 0] - 10, grown[:, 1] - 10)
    assert corner[(grown[:, 0] > 10) & (grown[:, 1] > 10)] == pytest.approx(0.2)
    shrunk = offset_outline(square, -0.2)
    assert shrunk[:, 0].min() == pytest.approx(0.2) and shrunk[:, 0].max() == pytest.approx(9.8)


def test_an_offset_that_empties_the_outline_is_refused():
    with pytest.raises(DesignError, match="offset"):
        offset_outline(_circle(1.0, 200), -2.0, "pinion")
