"""Hub speed over one shoe cycle without and with the non-circular gears."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.helpers.strategies import r_min_designs

from wheelstep_cli.gears.kinematics import hub_kinematics
from wheelstep_cli.mechanism.crank import CrankMechanism


designs = r_min_designs()


@settings(max_examples=60, deadline=None)
@given(designs, st.sampled_from([2, 4]), st.floats(1.0, 3000.0))
def test_geared_speed_is_constant_and_plain_follows_dx01(design_args, turns, rpm):
    a, b, r_min = design_args
    design = CrankMechanism.from_r_min(a, b, r_min)
    omega = rpm * 2 * math.pi / 60
    kin = hub_kinematics(design, omega, turns, count=181)
    k = a - b + design.c
    phi = np.linspace(-math.pi / 4, math.pi / 4, 181)
    analogue = k + 3 * b * np.cos(2 * phi)
    # circular gears: the carrier turns at omega / turns
    assert np.allclose(kin.speed_plain, omega / turns * analogue, rtol=1e-12)
    # non-circular gears: constant, equal to the plain drive's time-mean (same advance per cycle)
    assert np.ptp(kin.speed_geared) <= 1e-9 * kin.speed_geared.mean()
    mean_plain = omega / turns * (k + 6 * b / math.pi)
    assert kin.speed_geared.mean() == pytest.approx(mean_plain, rel=1e-9)
    assert kin.speed_geared.mean() * kin.cycle_time == pytest.approx(design.x_cycle, rel=1e-9)
    # ripple without gears: 3b peak-to-peak over the mean (sampled time-mean, trapezoid)
    assert kin.ripple_plain == pytest.approx(3 * b / (k + 6 * b / math.pi), rel=1e-4, abs=1e-12)
