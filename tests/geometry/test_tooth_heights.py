"""The height a tooth loses to a morphological opening of two extrusion lines' width
(geometry.planar.tooth_heights_lost), against its closed form on pointed teeth."""

import numpy as np
import pytest

from wheelstep_cli.geometry.planar import tooth_heights_lost


def _pointed_gear(teeth: int, root: float, height: float, base: float, arc_points: int = 60) -> np.ndarray:
    """A disc of radius ``root`` (mm) with ``teeth`` isosceles teeth ``height`` mm tall on a
    ``base`` mm wide chord, counter-clockwise."""
    pitch = 2.0 * np.pi / teeth
    half = np.arcsin(0.5 * base / root)
    ring = []
    for k in range(teeth):
        start = k * pitch
        for a in np.linspace(start + half, start + pitch - half, arc_points, endpoint=False):
            ring.append((root * np.cos(a), root * np.sin(a)))
        mid = start + pitch
        foot = root * np.cos(half)
        # the tooth: from its right foot to the apex and down to its left foot
        ring.append((root * np.cos(mid - half), root * np.sin(mid - half)))
        ring.append(((foot + height) * np.cos(mid), (foot + height) * np.sin(mid)))
        ring.append((root * np.cos(mid + half), root * np.sin(mid + half)))
    return np.array(ring)


@pytest.mark.parametrize("line_width", [0.4, 0.8])
def test_a_pointed_tooth_loses_what_the_largest_line_inside_its_tip_cannot_reach(line_width):
    # an apex of half-angle beta keeps up to the top of the disc of radius w/2 touching both
    # sides: rho / sin(beta) - rho below the apex
    height, base = 3.0, 3.0
    beta = np.arctan(0.5 * base / height)
    rho = line_width / 2
    lost = tooth_heights_lost(_pointed_gear(12, 20.0, height, base), module=2.0, line_width=line_width)
    assert len(lost) == 12
    # shapely's buffers draw the disc with 16 segments a quarter: well within 1 um of the arc
    assert lost == pytest.approx(rho * (1.0 / np.sin(beta) - 1.0), abs=1e-3)
