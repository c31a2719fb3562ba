"""The rigid fit that lays a printed outline back into its gear's frame (SPEC §11)."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.geometry.planar import offset_outline
from wheelstep_cli.geometry.registration import register


def _gear_like(teeth: int = 30) -> np.ndarray:
    """A toothed, non-circular, non-symmetric closed outline (mm)."""
    t = np.linspace(0.0, 2 * np.pi, 4000, endpoint=False)
    r = 20.0 + 0.8 * np.cos(teeth * t) + 3.0 * np.cos(2 * t) + 1.0 * np.sin(t)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def _moved(points: np.ndarray, angle: float, shift) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return points @ np.array([[c, s], [-s, c]]) + np.asarray(shift)


def test_a_moved_and_turned_outline_is_laid_back_exactly():
    design = _gear_like()
    printed = _moved(design, 2.345, [117.0, 63.5])
    fit = register(printed, design)
    assert np.abs(fit.apply(printed) - design).max() < 1e-6
    assert fit.rms < 1e-6 and abs(fit.offset) < 1e-6


def test_a_grown_print_is_fitted_in_place_and_its_growth_measured():
    design = _gear_like()
    grown = offset_outline(design, 0.08)
    fit = register(_moved(grown, -0.7, [40.0, -12.0]), design)
    assert abs(fit.offset - 0.08) < 0.002          # along the normals, as the printer grew it
    back = fit.apply(_moved(grown, -0.7, [40.0, -12.0]))
    # in place: the same centroid and orientation as the growth about the design
    assert np.abs(back.mean(axis=0) - grown.mean(axis=0)).max() < 0.002


def test_another_outline_does_not_fit():
    fit = register(_gear_like(28), _gear_like(30))
    assert fit.largest > 0.5
