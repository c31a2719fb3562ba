"""The crank mechanism (SPEC §2): one model, one rule for an impossible design."""

import numpy as np
import pytest
from hypothesis import given, settings

from tests.helpers.strategies import mechanisms
from wheelstep_cli.errors import DesignError
from wheelstep_cli.mechanism.crank import CrankMechanism


def test_reference_design_from_r_min():
    m = CrankMechanism.from_r_min(60, 100, 20)
    assert m.c == pytest.approx(360.0)
    assert m.k == m.hub_height == pytest.approx(320.0)
    assert m.x_walk == pytest.approx(600.0)
    assert m.x_roll == pytest.approx(202.7, abs=0.05)
    assert m.x_cycle == pytest.approx(802.7, abs=0.05)
    assert 100 * m.roll_share == pytest.approx(25.25, abs=0.005)


@pytest.mark.parametrize("kwargs, param", [
    (dict(a=-1, b=100, c=360), "a"),
    (dict(a=60, b=-1, c=360), "b"),
    (dict(a=60, b=100, c=float("nan")), "c"),
    (dict(a=60, b=120, c=360), "c"),        # R_min = -60: the strut is too short for the crank
])
def test_impossible_designs_name_one_parameter(kwargs, param):
    with pytest.raises(DesignError) as err:
        CrankMechanism(**kwargs)
    assert err.value.param == param


@pytest.mark.parametrize("r_min", [0.0, -5.0, 1e-300, float("inf")])
def test_r_min_must_be_positive_and_finite(r_min):
    with pytest.raises(DesignError) as err:
        CrankMechanism.from_r_min(60, 100, r_min)
    assert err.value.param == "r_min"


@settings(max_examples=60, deadline=None)
@given(mechanisms())
def test_speed_analogue_is_periodic_with_its_minimum_at_the_handover(m):
    phi = np.linspace(-np.pi / 4, np.pi / 4, 201)[:-1]
    v = m.speed_analogue(phi)
    np.testing.assert_allclose(m.speed_analogue(phi + np.pi / 2), v, rtol=1e-12, atol=1e-9)
    assert v.min() == pytest.approx(m.k, abs=1e-9) and v[0] == pytest.approx(m.k, abs=1e-9)
    assert v.max() == pytest.approx(m.k + 3 * m.b, rel=1e-12)
    # the mean over a shoe cycle is X01 / (pi/2)
    dense = np.linspace(-np.pi / 4, np.pi / 4, 20001)
    assert np.trapezoid(m.speed_analogue(dense), dense) / (np.pi / 2) == pytest.approx(m.mean_speed_analogue, rel=1e-9)


@pytest.mark.parametrize("given, param, limit", [
    ({"b"}, "b", "must be <= (a + c - 0.001)/4 = 104.9997 mm"),
    ({"a", "z"}, "a", "must be >= 4b - c + 0.001 = 120.001 mm"),
    ({"c"}, "c", "must be >= 4b - a + 0.001 = 420.001 mm"),
    (set(), "c", "must be >= 4b - a + 0.001 = 420.001 mm"),
])
def test_the_r_min_rule_names_the_parameter_the_user_gave(given, param, limit):
    with pytest.raises(DesignError) as err:
        CrankMechanism(60, 120, 360)
    named = err.value.for_given(given)
    assert named.param == param and named.limit.startswith(limit)
    assert "R_min = a - 4b + c = -60 mm" in named.limit


@pytest.mark.parametrize("given, param, limit", [
    ({"c"}, "c", "must be >= 4b - a + 0.001 = 340.001 mm"),
    ({"b"}, "b", "must be <= (a + c - 0.001)/4 = 99.9998 mm"),
    ({"a"}, "a", "must be >= 4b - c + 0.001 = 60.001 mm"),
])
def test_a_strut_leaving_the_sole_tighter_than_the_least_r_min_is_refused_as_r_min_is(given, param, limit):
    """c = 340.0005 leaves R_min = 0.0005 mm, which --rmin refuses (in effect a cusp): the
    strut, or the input given, is refused with the limit of the least R_min, printed so that
    the value copied from it passes; the least R_min itself passes."""
    with pytest.raises(DesignError) as err:
        CrankMechanism(60, 100, 340.0005)
    named = err.value.for_given(given)
    assert named.param == param and named.limit.startswith(limit), named.limit
    assert "R_min = a - 4b + c = 0.0005 mm must be >= 0.001 mm" in named.limit
    copied = float(limit.rsplit("= ", 1)[1].split()[0])
    lengths = {"a": 60.0, "b": 100.0, "c": 340.0005, param: copied}
    assert CrankMechanism(lengths["a"], lengths["b"], lengths["c"]).r_min >= 0.001 - 1e-9
    assert CrankMechanism.from_r_min(60, 100, 0.001).r_min == pytest.approx(0.001)
