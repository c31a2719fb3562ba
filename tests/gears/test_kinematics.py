"""Hub speed over one shoe cycle without and with the non-circular gears (`wheelstep kinematics`)."""

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelstep_cli.gears.kinematics import hub_kinematics
from wheelstep_cli.mechanism.crank import CrankMechanism

from tests.helpers.clicheck import error_line

# valid designs (a, b, R_min) with a strut c = R_min - a + 4b > 0
designs = st.tuples(st.floats(0.0, 250.0), st.floats(1.0, 300.0), st.floats(0.02, 0.98)).map(
    lambda t: (t[2] * (t[1] + 4 * t[0]), t[0], t[1]))


def test_reference_ripple_and_constant_speed(cli):
    result = cli("kinematics", "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    # SPEC §9: without the gears the hub speed varies by 59 % of its mean
    assert round(data["without_gears"]["ripple_pct"]) == 59
    assert data["with_gears"]["ripple_pct"] < 1e-9
    # k = 320, 3b = 300: speeds in the ratio 320 : 620 at the ends and the middle
    without = data["without_gears"]
    assert without["max_m_s"] / without["min_m_s"] == pytest.approx(620 / 320)
    # both make one 802.7 mm shoe cycle in the same time (60 rpm pinion, 2 turns per carrier turn)
    assert data["cycle_time_s"] == pytest.approx(0.5)
    assert data["mean_speed_m_s"] == pytest.approx(0.8026548 / 0.5, rel=1e-6)
    assert data["with_gears"]["min_m_s"] == pytest.approx(data["mean_speed_m_s"], rel=1e-9)
    curve = data["curve"]
    assert curve["phi_deg"][0] == -45 and curve["phi_deg"][-1] == 45
    text = cli("kinematics").stdout
    assert "without gears 58.7 %" in text and "with non-circular gears 0.0 %" in text


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


def test_plot_shows_both_curves_and_the_sole(cli, tmp_path):
    png = tmp_path / "kin.png"
    result = cli("kinematics", "--plot", png)
    assert result.exit_code == 0, result.stderr
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000
    from matplotlib.image import imread

    image = imread(png)
    assert image.shape[1] > image.shape[0] > 300


@pytest.mark.parametrize("args, param", [
    (["--rmin", "-1"], "r_min ="),
    (["--b", "-5"], "b ="),
    (["--motor-rpm", "0"], "motor-rpm ="),
    (["--turns", "3"], "turns ="),
    (["--points", "2"], "points ="),
])
def test_bad_input_one_line_exit_2_no_plot(cli, tmp_path, args, param):
    png = tmp_path / "kin.png"
    result = cli("kinematics", *args, "--plot", png)
    assert param in error_line(result), result.stderr
    assert not png.exists()
