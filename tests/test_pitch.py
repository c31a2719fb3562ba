"""Pitch curves (SPEC §3): reference values and properties over the design space."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tests.helpers.strategies import crank_laws
from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.pitch import (CrankLaw, carrier_angle, pinion_angle, pinion_radius, ratio,
                                       wheel_radius)

REF = CrankLaw(60, 100, 360, 143.5, 2)




def test_reference_u_and_handover_radii():
    assert REF.u == pytest.approx(1.25248, abs=5e-6)
    assert pinion_radius(REF, np.pi / 4) == pytest.approx(63.71, abs=0.005)
    assert wheel_radius(REF, np.pi / 4) == pytest.approx(79.79, abs=0.005)


@settings(max_examples=60, deadline=None)
@given(crank_laws())
def test_closure_sum_symmetry_and_inverse(law):
    phi = np.linspace(-np.pi / 4, np.pi / 4, 201)
    # r + r_H = L and the rolling condition r dtheta = r_H dphi
    np.testing.assert_allclose(pinion_radius(law, phi) + wheel_radius(law, phi), law.center_distance)
    dtheta = np.gradient(pinion_angle(law, phi), phi)
    np.testing.assert_allclose(dtheta[1:-1], ratio(law, phi)[1:-1], rtol=1e-3)
    # closure: the pinion turns n*pi/4 per half shoe cycle, n*pi per carrier half turn
    assert pinion_angle(law, np.pi / 4) == pytest.approx(law.turns * np.pi / 4)
    assert pinion_angle(law, np.pi) == pytest.approx(law.turns * np.pi)
    # mirror symmetry and quarter periodicity
    np.testing.assert_allclose(pinion_radius(law, phi), pinion_radius(law, -phi))
    np.testing.assert_allclose(pinion_radius(law, phi + np.pi / 2), pinion_radius(law, phi), atol=1e-9)
    np.testing.assert_allclose(pinion_angle(law, -phi), -pinion_angle(law, phi), atol=1e-12)
    assert np.all(pinion_radius(law, phi) > 0) and np.all(wheel_radius(law, phi) > 0)
    wide = np.linspace(-7, 7, 301)
    np.testing.assert_allclose(carrier_angle(law, pinion_angle(law, wide)), wide, atol=1e-10)


@pytest.mark.parametrize("kwargs, param", [
    (dict(a=-1, b=100, c=360, center_distance=143.5), "a"),
    (dict(a=60, b=120, c=360, center_distance=143.5), "b"),
    (dict(a=60, b=100, c=360, center_distance=0), "center-distance"),
    (dict(a=60, b=100, c=360, center_distance=143.5, turns=3), "turns"),
])
def test_invalid_laws_name_the_parameter(kwargs, param):
    with pytest.raises(DesignError) as err:
        CrankLaw(**kwargs)
    assert err.value.param == param
