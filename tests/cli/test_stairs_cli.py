"""`wheelstep stairs` (SPEC §6): JSON and plot, design check, sweep, bad input."""

import json
import math

import pytest

from tests.helpers.clicheck import error_line


def test_cli_json_and_plot(cli, tmp_path):
    png = tmp_path / "stairs.png"
    res = cli("stairs", "--run", "300", "--rise", "150", "--sole-radius", "70", "--json", "--plot", png)
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert data["b_mm"] == pytest.approx(20.0, abs=0.05) and data["y1_mm"] == pytest.approx(150.0, abs=0.05)
    assert data["a_mm"] == pytest.approx(2 * data["b_mm"])
    for key in ("climb", "descent"):
        rows = data[key]
        assert set(rows[0]) == {"phi", "X01", "dX01", "d2X01", "Y01", "dY01", "d2Y01"}
        assert rows[-1]["phi"] - rows[0]["phi"] == pytest.approx(90.0)
        assert rows[-1]["X01"] - rows[0]["X01"] == pytest.approx(300.0, abs=1e-6)
    assert data["climb"][0]["phi"] == -90.0 and data["descent"][0]["phi"] == 0.0
    assert data["climb"][-1]["Y01"] - data["climb"][0]["Y01"] == pytest.approx(150.0, abs=1e-6)
    assert data["descent"][-1]["Y01"] - data["descent"][0]["Y01"] == pytest.approx(-150.0, abs=1e-6)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_check_old_prototype(cli):
    res = cli("stairs", "--run", "300", "--rise", "150", "--a", "100", "--b", "50", "--y1", "130", "--y2", "192")
    assert res.exit_code == 1
    assert "CANNOT CLIMB" in res.stdout and "advances 494.6 mm" in res.stdout


def test_a_miss_finer_than_a_tenth_is_shown_to_the_tolerance(cli):
    """Within 0.01 mm the stair is missed by 0.015-0.04 mm: the lengths are shown finer than
    the tolerance (at 0.1 mm they read as the stair's own 300 x 150, a contradiction)."""
    res = cli("stairs", "--a", "40", "--b", "20", "--y1", "150", "--y2", "70", "--tol", "0.01")
    assert res.exit_code == 1
    assert "(within 0.01 mm)" in res.stdout and "closest: landing -90.0 deg advances 299.985 mm" in res.stdout
    assert "landing -0.0 deg" not in res.stdout


def test_cli_sweep_never_prints_meaningless_numbers(cli):
    res = cli("stairs", "--sweep", "--sweep-angles", "-120:-30:15", "--sweep-radii", "70")
    assert res.exit_code == 0
    lines = {line.split()[0]: line for line in res.stdout.splitlines() if line.strip()[:1] in "-0123456789"}
    assert "singular" in lines["-45.0"] and "singular" in lines["-105.0"]
    assert "n/a (negative b)" in lines["-60.0"]
    assert "20.0 / 150.0" in lines["-90.0"]


@pytest.mark.parametrize("args, param", [
    (("--landing-angle", "-45"), "landing-angle"),
    (("--landing-angle", "-60"), "landing-angle"),
    (("--run", "-3"), "run"),
    (("--a", "100", "--b", "50"), "y1"),
])
def test_cli_bad_input_one_line_exit_2(cli, tmp_path, args, param):
    png = tmp_path / "x.png"
    res = cli("stairs", *args, "--plot", png)
    assert error_line(res).startswith(f"wheelstep: error: --{param} =")
    assert not png.exists()


@pytest.mark.parametrize("args, line", [
    # an empty list printed an empty table, exit 0
    (("--sweep", "--sweep-angles", ",,,"), "--sweep-angles = ,,,: has an empty value between commas"),
    (("--sweep", "--sweep-angles", "-90,,-45"), "--sweep-angles = -90,,-45: has an empty value"),
    (("--sweep", "--sweep-radii", ","), "--sweep-radii = ,: has an empty value between commas"),
    # each list within its 10000 values, but 100 million cells: refused, not a memory error
    (("--sweep", "--sweep-radii", "1:10000:1", "--sweep-angles", "-179.982:0:0.018"),
     "--sweep-radii = 1:10000:1: gives 10000 radii, 100000000 cells with the 10000 landing angles; "
     "at most 100000 cells"),
    # -q prints no table: the step would shape nothing
    (("--step", "7", "-q"), "--step = 7: shapes the printed tables, which -q does not print (--json does)"),
    # a step that does not divide 90 deg was spread to one that does (7 printed every 6.92 deg)
    (("--step", "7"), "--step = 7: must divide the cycle's 90 deg into whole steps: 6.923076923 or 7.5"),
])
def test_options_that_would_do_nothing_are_refused(cli, args, line):
    assert error_line(cli("stairs", *args)).startswith(f"wheelstep: error: {line}")


def test_no_negative_zero_in_the_tables(cli):
    """The climb table's derivatives at phi = 0 printed as -0.00 (and -0.0 in --json)."""
    text = cli("stairs").stdout
    assert "-0.00 " not in text and not any(line.endswith("-0.00") for line in text.splitlines())
    numbers = []

    def walk(value):
        if isinstance(value, float):
            numbers.append(value)
        elif isinstance(value, dict):
            [walk(v) for v in value.values()]
        elif isinstance(value, list):
            [walk(v) for v in value]

    walk(json.loads(cli("stairs", "--json").stdout))
    zeros = [v for v in numbers if v == 0.0]
    assert zeros and all(math.copysign(1.0, v) > 0 for v in zeros)


def test_a_step_named_by_the_refusal_prints_at_that_step(cli):
    """The step the refusal of 7 offers, as printed, is taken and the tables run at it."""
    result = cli("stairs", "--step", "6.923076923", "--json")
    assert result.exit_code == 0, result.stderr
    import json

    angles = [row["phi"] for row in json.loads(result.stdout)["climb"]]
    assert len(angles) == 14 and abs(angles[1] - angles[0] - 90 / 13) < 1e-6


def test_angles_worked_out_from_a_landing_given_past_its_last_digit_read_as_numbers(cli):
    """-90.0000000000001 left -90 + 90 = -9.9476e-14 in the per-cycle line and the descent's
    landing; worked-out angles are said to the nanodegree."""
    text = cli("stairs", "--landing-angle=-90.0000000000001").stdout
    assert "per cycle (landing -90 -> 0 deg)" in text and "landing beta = -90 - alpha = 0 deg" in text, text
    assert "e-1" not in text
