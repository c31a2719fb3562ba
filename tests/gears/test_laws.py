"""Transmission laws and their pitch curves (SPEC §3): reference values and properties over
the design space."""

import numpy as np
import pytest
from hypothesis import given, settings

from tests.helpers.strategies import center_distances, crank_laws
from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.gears.pitch_curves import pinion_radius, wheel_radius
from wheelstep_cli.mechanism.crank import CrankMechanism

REF = CrankLaw(CrankMechanism(60, 100, 360), 2)
L_REF = 143.5


def test_reference_u_and_handover_radii():
    assert REF.u == pytest.approx(1.25248, abs=5e-6)
    assert pinion_radius(REF, np.pi / 4, L_REF) == pytest.approx(63.71, abs=0.005)
    assert wheel_radius(REF, np.pi / 4, L_REF) == pytest.approx(79.79, abs=0.005)


@settings(max_examples=60, deadline=None)
@given(crank_laws(), center_distances())
def test_closure_sum_symmetry_and_inverse(law, L):
    phi = np.linspace(-np.pi / 4, np.pi / 4, 201)
    # r + r_H = L and the rolling condition r dtheta = r_H dphi
    np.testing.assert_allclose(pinion_radius(law, phi, L) + wheel_radius(law, phi, L), L)
    dtheta = np.gradient(law.pinion_angle(phi), phi)
    np.testing.assert_allclose(dtheta[1:-1], law.ratio(phi)[1:-1], rtol=1e-3)
    # closure: the pinion turns n*pi/4 per half shoe cycle, n*pi per carrier half turn
    assert law.pinion_angle(np.pi / 4) == pytest.approx(law.turns * np.pi / 4)
    assert law.pinion_angle(np.pi) == pytest.approx(law.turns * np.pi)
    # mirror symmetry and quarter periodicity
    np.testing.assert_allclose(pinion_radius(law, phi, L), pinion_radius(law, -phi, L))
    np.testing.assert_allclose(pinion_radius(law, phi + np.pi / 2, L), pinion_radius(law, phi, L), atol=1e-9)
    np.testing.assert_allclose(law.pinion_angle(-phi), -law.pinion_angle(phi), atol=1e-12)
    assert np.all(pinion_radius(law, phi, L) > 0) and np.all(wheel_radius(law, phi, L) > 0)
    wide = np.linspace(-7, 7, 301)
    np.testing.assert_allclose(law.carrier_angle(law.pinion_angle(wide)), wide, atol=1e-10)


def test_invalid_turns_name_the_parameter():
    with pytest.raises(DesignError) as err:
        CrankLaw(CrankMechanism(60, 100, 360), turns=3)
    assert err.value.param == "turns"


def test_crank_law_hub_speed_factor_is_the_mechanism_speed_analogue():
    phi = np.linspace(-3.0, 3.0, 61)
    np.testing.assert_array_equal(REF.hub_speed_factor(phi), REF.mechanism.speed_analogue(phi))
    np.testing.assert_allclose(REF.ratio(phi) * REF.mechanism.k / REF.u, REF.hub_speed_factor(phi))
