"""`wheelstep linkage` (SPEC §7): JSON, plot, GIF and CSV, scaling, impossible legs."""

import json

import numpy as np
import pytest

from tests.helpers.clicheck import error_line


def test_cli_json_plot_gif_csv(cli, tmp_path):
    out = {k: tmp_path / f"leg.{k}" for k in ("png", "gif", "csv")}
    res = cli("linkage", "--preset", "jansen", "--samples", "360", "--json",
              "--plot", out["png"], "--gif", out["gif"], "--gif-frames", "6", "--csv", out["csv"])
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert data["loop_residual_mm"] < 1e-9
    assert 0 < data["duty_factor"] < 1 and data["stride_mm"] > 0 and data["lift_mm"] > 0
    assert data["branches"] == {"U": -1, "W": 1, "R": 1, "K": -1, "F": -1}
    assert out["png"].read_bytes()[:4] == b"\x89PNG" and out["gif"].read_bytes()[:6] == b"GIF89a"
    assert len(out["csv"].read_text().splitlines()) == 361
    # the support column is a flag, 0 or 1 as the JSON's booleans are (it was 0.000000 / 1.000000)
    support = [line.rsplit(",", 1)[1] for line in out["csv"].read_text().splitlines()[1:]]
    assert set(support) == {"0", "1"}
    from PIL import Image

    assert Image.open(out["gif"]).n_frames == 6


def test_cli_chebyshev_scaled(cli):
    res = cli("linkage", "--preset", "chebyshev", "--scale", "0.02", "--step", "90", "--json")
    data = json.loads(res.stdout)
    pts = {round(r["crank_deg"]): (r["x_mm"], r["y_mm"]) for r in data["path"]}
    assert np.allclose([pts[90], pts[180], pts[270]], [[4, 4], [2, 4], [0, 4]], atol=1e-9)   # unit 50 x 0.02
    # the preset's description states its own numbers: the report says they are scaled
    assert data["scale"] == 0.02 and data["description"].endswith("; every length x 0.02 (--scale)")
    plain = json.loads(cli("linkage", "--preset", "chebyshev", "--step", "90", "--json").stdout)
    assert plain["scale"] == 1.0 and "--scale" not in plain["description"]


def test_cli_impossible_linkage_one_line_exit_2(cli, tmp_path):
    png = tmp_path / "x.png"
    res = cli("linkage", "--l3", "100", "--plot", png)
    line = error_line(res)
    # the solver stops at a crank angle, which nobody types: the line names the link given
    assert line.startswith("wheelstep: error: --l3 = 100: ")
    assert "cannot close" in line and "crank angle" in line and not png.exists()
    line = error_line(cli("linkage", "--l1", "500", "--o1=567,615"))
    assert line.startswith("wheelstep: error: --l1 = 500: ") and "crank angle 195.5 deg" in line
    for typed in ("Q=+1", "Q=1"):     # echoed as typed
        res = cli("linkage", "--preset", "jansen", "--branch", typed)
        assert res.exit_code == 2 and res.stderr.startswith(f"wheelstep: error: --branch = {typed}: not a dyad joint")
    # a four-bar link given with another preset is the option that would do nothing: named
    assert error_line(cli("linkage", "--preset", "jansen", "--o1", "3,4")) == (
        "wheelstep: error: --o1 = 3,4: shapes the four-bar only (--l1..--l4, --beta, --o1), not the "
        "jansen preset: drop it or use --preset four-bar")
    # the arm angle by its option, not the field it fills (it said `beta_deg = 10`)
    assert error_line(cli("linkage", "--preset", "jansen", "--beta", "10")).startswith(
        "wheelstep: error: --beta = 10: shapes the four-bar only")


def test_a_table_step_between_the_sampled_crank_angles_is_refused_with_the_ones_it_takes(cli):
    """The path table lists sampled angles: --step 10.3 printed every 10.5 deg."""
    line = error_line(cli("linkage", "--step", "10.3", "--json"))
    assert line == ("wheelstep: error: --step = 10.3: must be a whole multiple of the crank angles' spacing "
                    "0.5 deg (360 / --samples 720): 10 or 10.5")
    for step in (10.0, 10.5):       # the remedies, applied: the table steps by them
        rows = json.loads(cli("linkage", "--step", str(step), "--json").stdout)["path"]
        assert np.diff([r["crank_deg"] for r in rows]) == pytest.approx(step)
    assert error_line(cli("linkage", "--step", "0.3", "--json")).endswith("(360 / --samples 720): 0.5")
    assert error_line(cli("linkage", "--step", "7", "--samples", "100", "--json")).endswith(
        "spacing 3.6 deg (360 / --samples 100): 3.6 or 7.2")
    # a spacing that is no short decimal: the multiples printed to 10 digits are taken as given
    line = error_line(cli("linkage", "--samples", "700", "--step", "10", "--json"))
    above = line.rsplit(" or ", 1)[1]
    assert above == "10.28571429"
    assert cli("linkage", "--samples", "700", "--step", above, "--json").exit_code == 0


def test_the_default_table_step_is_the_sampled_multiple_nearest_15_deg_and_says_so(cli):
    """With no --step the table steps by 15 deg where the samples hold it, else by the multiple
    of their spacing nearest it, the larger of two as near (36 samples: 20 deg, 60: 18 deg, 100:
    14.4 deg), stated in the table's
    header and --json's table_step_deg; that step given is taken as it is."""
    for samples, step in (("720", 15.0), ("36", 20.0), ("100", 14.4), ("60", 18.0)):
        report = json.loads(cli("linkage", "--samples", samples, "--json").stdout)
        assert report["table_step_deg"] == pytest.approx(step)
        assert np.diff([r["crank_deg"] for r in report["path"]]) == pytest.approx(step)
        printed = cli("linkage", "--samples", samples)
        assert f"phase   (every {step:g} deg)" in printed.stdout, printed.stdout
        assert cli("linkage", "--samples", samples, "--step", f"{step:g}", "--json").exit_code == 0


def test_a_support_band_as_deep_as_the_lift_or_none_at_all_is_refused(cli, tmp_path):
    """--ground-tol is how near its lowest level the foot counts as on the ground: at the lift
    or beyond, every crank angle would be support (duty factor 1); at 0, hardly one. Both are
    refused naming the lift; just under the lift the support is most of the turn, not all."""
    lift = json.loads(cli("linkage", "--json").stdout)["lift_mm"]
    from wheelstep_cli.errors import rounded_down

    for value, limit in ((f"{lift + 1:g}", f"must be < the foot's lift {rounded_down(lift, 1)} mm"),
                         ("0", "must be > 0 mm")):
        line = error_line(cli("linkage", "--ground-tol", value, "--csv", tmp_path / "leg.csv"))
        assert line.startswith(f"wheelstep: error: --ground-tol = {value}: {limit}"), line
        assert not (tmp_path / "leg.csv").exists()
    near = json.loads(cli("linkage", "--ground-tol", f"{0.99 * lift:g}", "--json").stdout)
    assert 0.5 < near["duty_factor"] < 1


def test_the_papers_own_numbers_typed_are_the_papers_leg(cli):
    """--o1 567,615 (the paper's pivot) gave a 'four-bar leg' report without the source's
    name: the same numbers typed are the paper's leg, reported the same; one changed is not."""
    plain = json.loads(cli("linkage", "--json").stdout)
    typed = json.loads(cli("linkage", "--o1", "567,615", "--l1", "270", "--beta", "70.8", "--json").stdout)
    assert typed["description"] == plain["description"] and plain["description"].startswith("source paper")
    changed = json.loads(cli("linkage", "--beta", "70.9", "--json").stdout)
    assert not changed["description"].startswith("source paper") and "70.9 deg" in changed["description"]


def test_an_arm_angle_past_a_full_turn_is_refused(cli, tmp_path):
    """--beta 400 was taken as the leg of 40 deg (angles wrap), the report saying 400: a value
    past a full turn is refused; just inside a turn it is the leg of that angle."""
    for value in ("400", "-360"):
        line = error_line(cli("linkage", "--beta", value, "--csv", tmp_path / "leg.csv"))
        assert line == f"wheelstep: error: --beta = {value}: must be in (-360, 360) deg", line
        assert not (tmp_path / "leg.csv").exists()
    inside = json.loads(cli("linkage", "--beta", "359", "--json").stdout)
    assert "359 deg" in inside["description"]


def test_a_scale_beyond_a_thousand_either_way_is_refused(cli):
    """--scale 1e6 printed a foot speed of 1.5e6 m/s, 1e-9 only zeros: the range is said."""
    for value in ("1e6", "0.0001", "0"):
        assert error_line(cli("linkage", "--scale", value)) == f"wheelstep: error: --scale = {value}: must be in [0.001, 1000]"
    for value in ("0.001", "1000"):
        assert cli("linkage", "--scale", value, "--json").exit_code == 0
