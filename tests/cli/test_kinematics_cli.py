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
    # the table's U column is said (a reader met an unexplained U); at phi = 0 it is SPEC §3's u (k + 3b) / k
    assert "\nU = omega / omega_H = r_H / r: pinion speed per carrier speed" in text
    k, mid = data["a_mm"] - data["b_mm"] + data["c_mm"], curve["phi_deg"].index(0)
    assert curve["ratio_u"][mid] == pytest.approx(1.25248 * (k + 3 * data["b_mm"]) / k, rel=1e-5)


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


def _speed_check(data: dict, ratio_of, rtol: float = 1e-8) -> None:
    """The geared curve is the hub speed of gears following ``ratio_of(phi rad)``: omega / U(phi)
    times the speed analogue k + 3b cos 2phi (SPEC §3), and its ripple is peak-to-peak over the
    time mean (each equal carrier step lasting U dphi / omega). ``rtol``: of the ratio (the report
    keeps 10 digits; a law read from a CSV is a fit to its samples)."""
    import numpy as np

    curve = data["curve"]
    phi = np.radians(curve["phi_deg"])
    u = ratio_of(phi)
    assert np.allclose(curve["ratio_u"], u, rtol=rtol, atol=0)
    k, b = data["a_mm"] - data["b_mm"] + data["c_mm"], data["b_mm"]
    omega = data["motor_rpm"] * 2 * np.pi / 60
    speed = omega / u * (k + 3 * b * np.cos(2 * phi)) / 1000
    assert np.allclose(curve["with_m_s"], speed, rtol=rtol, atol=0)
    time = np.concatenate([[0.0], np.cumsum(0.5 * (u[1:] + u[:-1]) * np.diff(phi))])
    mean = np.trapezoid(speed, time) / time[-1]
    assert data["with_gears"]["ripple_pct"] == pytest.approx(100 * np.ptp(speed) / mean, rel=1e-3)


def test_profile_blend_is_the_law_the_gears_follow(cli, tmp_path):
    """A design profile's gears.blend smooths the law the gears are cut for: the hub speed
    ripples as much as the blended law departs from the crank law (not 0)."""
    import numpy as np

    from wheelstep_cli.gears.laws import CrankLaw, blended_law
    from wheelstep_cli.mechanism.crank import CrankMechanism

    profile = tmp_path / "blend.yaml"
    profile.write_text("gears:\n  blend: 10\n")
    result = cli("kinematics", "--profile", profile, "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    law = blended_law(CrankLaw(CrankMechanism(60, 100, 360), 2), np.radians(10))
    _speed_check(data, law.ratio)
    assert data["with_gears"]["ripple_pct"] > 1 and "blended over 10 deg" in data["with_gears"]["law"]
    plain = json.loads(cli("kinematics", "--json").stdout)
    assert plain["without_gears"] == data["without_gears"]


def test_profile_law_csv_is_the_law_the_gears_follow(cli, tmp_path):
    """A profile's law CSV repeating within the shoe cycle drives the hub; its mean ratio is
    the pinion turns; --turns with it is refused; one of another period is refused."""
    import numpy as np

    phi = np.linspace(0.0, 90.0, 181)
    theta = 4 * phi + np.degrees(0.1 * np.sin(np.radians(4 * phi)))
    law = tmp_path / "law.csv"
    law.write_text("driving_deg,driven_deg\n" + "\n".join(f"{t:.12f},{p:.12f}" for t, p in zip(theta, phi)))
    profile = tmp_path / "p.yaml"
    profile.write_text(f"gears:\n  law_csv: {law}\n")
    result = cli("kinematics", "--profile", profile, "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["turns"] == 4 and data["cycle_time_s"] == pytest.approx(1.0)
    _speed_check(data, lambda p: 4 + 0.4 * np.cos(4 * p), rtol=1e-4)
    assert str(law) in data["with_gears"]["law"]
    assert "-n = 4" in error_line(cli("kinematics", "--profile", profile, "-n", "4"))
    half = tmp_path / "half.csv"
    half.write_text("driving_deg,driven_deg\n" + "\n".join(f"{3 * p:.12f},{p:.12f}" for p in np.linspace(0, 120, 121)))
    profile.write_text(f"gears:\n  law_csv: {half}\n")
    line = error_line(cli("kinematics", "--profile", profile))
    assert "law_csv" in line and "must divide 90 deg" in line, line


def test_a_profiles_gears_that_cannot_be_made_are_refused_as_gears_refuses_them(cli, tmp_path):
    profile = tmp_path / "p.yaml"
    profile.write_text("gears:\n  teeth: paper\n  blend: 10\n")
    line = error_line(cli("kinematics", "--profile", profile))
    assert line == error_line(cli("gears", "--profile", profile, "--out", tmp_path / "out"))
    assert f"{profile}:3: gears.blend = 10:" in line


def test_a_profiles_turns_are_the_turns_of_its_blended_law(cli, tmp_path):
    """`turns: 4` with a blend: the blended law is the 4-turn crank law's (it was built on 2)."""
    import numpy as np

    from wheelstep_cli.gears.laws import CrankLaw, blended_law
    from wheelstep_cli.mechanism.crank import CrankMechanism

    profile = tmp_path / "p.yaml"
    profile.write_text("gears:\n  turns: 4\n  blend: 10\n")
    result = cli("kinematics", "--profile", profile, "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["turns"] == 4
    _speed_check(data, blended_law(CrankLaw(CrankMechanism(60, 100, 360), 4), np.radians(10)).ratio)


def test_the_summary_is_the_cycles_not_the_samples_shown(cli):
    """--points shapes the table and the curve only: 4 points miss mid-stance (phi = 0), where
    the speed without the gears peaks, yet the ripple and the speeds' range are the cycle's."""
    import json

    few, many = (json.loads(cli("kinematics", "--points", n, "--json").stdout) for n in ("4", "361"))
    for side in ("without_gears", "with_gears"):
        for key in ("min_m_s", "max_m_s", "ripple_pct"):
            assert few[side][key] == pytest.approx(many[side][key], rel=1e-9, abs=1e-12), (side, key)
    assert max(few["curve"]["without_m_s"]) < few["without_gears"]["max_m_s"] - 0.1


def test_more_table_rows_than_samples_are_refused_and_a_fast_motors_cycle_is_not_zero(cli):
    """--rows 1000 over the default 361 samples printed 361 rows unsaid: refused naming the
    samples; with as many samples it prints them. A 1e6 rpm motor's cycle (30 us) was
    printed as 0.000 s."""
    line = error_line(cli("kinematics", "--rows", "1000"))
    assert line.startswith("wheelstep: error: --rows = 1000: must be <= --points = 361"), line
    table = cli("kinematics", "--rows", "1000", "--points", "1000").stdout.splitlines()
    assert sum(1 for row in table if row.split() and row.split()[0].replace(".", "").lstrip("-").isdigit()) == 1000
    for rpm in ("1e6", "60"):
        first = cli("kinematics", "--motor-rpm", rpm).stdout.splitlines()[0]
        seconds = json.loads(cli("kinematics", "--motor-rpm", rpm, "--json").stdout)["cycle_time_s"]
        printed = float(first.split("one shoe cycle ")[1].split(" s,")[0])
        # the printed time is the cycle's to 3 significant digits (or the millisecond), never 0
        assert printed > 0 and abs(printed - seconds) <= max(5e-4, 5e-3 * seconds), (first, seconds)
