"""The meshing check over a law's whole cycle (gears.cycle.WholeCycle): outlines that do not
repeat every period (a printed pair) are seen whole, whichever period their check starts in;
outlines that do repeat give the figures of one period."""

import numpy as np
import pytest

from tests.gears.meshing.test_meshing import involute_gear
from tests.helpers.outlines import mesh_figures, turned
from wheelstep_cli.gears.cycle import WholeCycle
from wheelstep_cli.gears.laws import CrankLaw, law_from_samples
from wheelstep_cli.gears.meshing import MeshingSettings, check_meshing
from wheelstep_cli.mechanism.crank import CrankMechanism

# a crank law without crank (b = 0): a constant ratio of 2, the pinion's period half a turn
# (2 a turn), the wheel's a quarter (4): spur gears of 24 and 48 teeth, module 2, follow it
LAW = CrankLaw(CrankMechanism(60.0, 0.0, 360.0), 2)
Z1, Z2, M, J = 24, 48, 2.0, 0.2
DISTANCE = M * (Z1 + Z2) / 2.0
PER_PERIOD = 96     # poses per law period: 8 per tooth pitch


@pytest.fixture(scope="module")
def spur():
    pinion = involute_gear(Z1, M, J / 2.0, space_at_zero=False, flank_points=120)
    wheel = involute_gear(Z2, M, J / 2.0, space_at_zero=True, flank_points=120)
    return pinion, wheel


@pytest.fixture(scope="module")
def printed(spur):
    """The spur pair with two teeth off their places, as a print's teeth are: pinion tooth at
    body angle 90 deg (met at theta 90 and 450 deg) turned 0.3 mrad (7 um), wheel tooth at
    161.25 deg (met at theta 397.5 deg, in the law's third period) 0.3 mrad (14 um)."""
    pinion, wheel = spur
    return (turned(pinion, 3e-4, np.radians(90.0), np.radians(12.0)),
            turned(wheel, 3e-4, np.radians(161.25), np.radians(6.0)))


def test_the_whole_cycle_of_a_crank_law_is_one_wheel_turn():
    cycle = WholeCycle(CrankLaw(CrankMechanism(60, 100, 360), 2))
    assert (cycle.periods, cycle.pinion_turns, cycle.wheel_turns) == (4, 2, 1)
    assert cycle.theta_period == pytest.approx(4 * np.pi) and cycle.phi_period == pytest.approx(2 * np.pi)
    # the handover corner of every period; the angles themselves are the law's
    np.testing.assert_allclose(cycle.corners, np.pi / 4 + np.pi / 2 * np.arange(4))
    theta = np.linspace(-1.0, 15.0, 50)
    np.testing.assert_array_equal(cycle.carrier_angle(theta), cycle.law.carrier_angle(theta))
    assert WholeCycle(CrankLaw(CrankMechanism(60, 100, 360), 4)).pinion_turns == 4


def test_a_law_whose_periods_do_not_divide_takes_their_least_common_multiple():
    # 3 periods a pinion turn, 2 a wheel turn: both back after 6 periods (2 and 3 turns)
    law = law_from_samples(np.linspace(0.0, 120.0, 25), np.linspace(0.0, 180.0, 25))
    cycle = WholeCycle(law)
    assert (cycle.periods, cycle.pinion_turns, cycle.wheel_turns) == (6, 2, 3)
    assert cycle.theta_period == pytest.approx(4 * np.pi)


def test_outlines_that_repeat_every_period_give_the_figures_of_one_period(spur):
    """The designed pair's check of one period stands for its whole cycle: the cycle's band
    of 3 tooth harmonics, derivative and windows are the period's, repeated."""
    one = check_meshing(*spur, LAW, DISTANCE, MeshingSettings(samples=PER_PERIOD))
    whole = check_meshing(*spur, WholeCycle(LAW), DISTANCE, MeshingSettings(samples=4 * PER_PERIOD))
    assert whole.period == pytest.approx(4 * np.pi) and len(whole.theta) == 4 * PER_PERIOD  # 720 deg
    assert whole.track.harmonics == 4 * one.track.harmonics
    assert whole.track.pitch == pytest.approx(one.track.pitch, rel=1e-9)
    np.testing.assert_allclose(mesh_figures(whole), mesh_figures(one), rtol=1e-6, atol=1e-6)


def test_a_printed_pair_turned_by_a_period_gives_the_same_figures_over_its_whole_cycle(printed):
    """Turning both gears by one law period (the pinion by half a turn, the wheel back by a
    quarter) is the same pair placed differently, so its check must not change; over one
    period it does: each check sees half of the pinion's and a quarter of the wheel's teeth,
    and neither the wheel tooth met in the law's third period."""
    pinion, wheel = printed
    moved = (turned(pinion, LAW.theta_period), turned(wheel, -LAW.phi_period))
    settings = MeshingSettings(samples=4 * PER_PERIOD)
    whole = [check_meshing(p, w, WholeCycle(LAW), DISTANCE, settings) for p, w in (printed, moved)]
    np.testing.assert_allclose(mesh_figures(whole[1]), mesh_figures(whole[0]), rtol=1e-6, atol=1e-6)
    one = [check_meshing(p, w, LAW, DISTANCE, MeshingSettings(samples=PER_PERIOD))
           for p, w in (printed, moved)]
    # the pinion tooth (7 um) is in the first period's view only
    assert one[0].drive.total_um > one[1].drive.total_um + 3.0
    # the wheel tooth (14 um) only in the whole cycle's: its F'i is the largest
    assert whole[0].drive.total_um > max(r.drive.total_um for r in one) + 3.0
