"""`wheelstep kinematics`: reference ripple, the plot, bad input."""

import json

import pytest

from tests.helpers.clicheck import error_line

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
    (["--rmin", "-1"], "rmin ="),
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
