"""`wheelstep trajectory` (SPEC §8): the files it writes and its bad input."""

import json
from pathlib import Path

import numpy as np
import pytest

from tests.helpers.clicheck import error_line


def test_cli_files(cli, tmp_path):
    import ezdxf

    f = {k: tmp_path / f"path.{k}" for k in ("csv", "dxf", "png")}
    res = cli("trajectory", "-H", "300", "--r1", "20", "--r2", "45", "--h-max", "120", "--json",
              "--csv", f["csv"], "--dxf", f["dxf"], "--plot", f["png"])
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert data["case"] == "general" and data["h_max_mm"] == pytest.approx(120.0)
    rows = np.loadtxt(f["csv"], delimiter=",", skiprows=1)
    assert rows[:, 1].max() == pytest.approx(120.0, abs=1e-3) and rows[:, 1].min() == pytest.approx(0.0)
    # the piece each sample lies on, as the JSON's pieces count them: whole numbers
    pieces = [line.rsplit(",", 1)[1] for line in f["csv"].read_text().splitlines()[1:]]
    assert all(piece.isdigit() for piece in pieces)
    assert sorted({int(piece) for piece in pieces}) == list(range(len(data["pieces"])))
    doc = ezdxf.readfile(f["dxf"])
    ents = list(doc.modelspace())
    assert [e.dxftype() for e in ents] == ["LINE", "ARC", "ARC", "ARC"]
    top = ents[2]
    assert top.dxf.radius == pytest.approx(data["r3_mm"]) and top.dxf.center.y + top.dxf.radius == pytest.approx(120.0)
    assert f["png"].read_bytes()[:4] == b"\x89PNG"
    again = tmp_path / "again.dxf"
    cli("trajectory", "-H", "300", "--r1", "20", "--r2", "45", "--h-max", "120", "--dxf", again)
    assert again.read_bytes() == f["dxf"].read_bytes()


def test_cli_polyline_dxf(cli, tmp_path):
    import ezdxf

    out = tmp_path / "p.dxf"
    assert cli("trajectory", "--dxf", out, "--dxf-polyline").exit_code == 0
    (poly,) = list(ezdxf.readfile(out).modelspace())
    assert poly.dxftype() == "POLYLINE" and poly.is_closed and len(poly.vertices) == 4


def test_cli_bad_input_one_line_exit_2(cli, tmp_path):
    out = tmp_path / "x.dxf"
    res = cli("trajectory", "--r1", "30", "--h-max", "40", "--dxf", out)
    assert error_line(res).startswith("wheelstep: error: --h-max = 40") and not out.exists()
    res = cli("trajectory", "--r3", "400", "--h-max", "100")
    assert res.exit_code == 2 and "either --r3 or --h-max" in res.stderr


def test_dxf_run_prints_no_library_log_line(tmp_path):
    import subprocess
    import sys

    run = subprocess.run([sys.executable, "-m", "wheelstep_cli", "trajectory", "--dxf", "p.dxf", "-q"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stderr == "" and (tmp_path / "p.dxf").is_file()


@pytest.mark.parametrize("option", ["--r1", "--r2"])
def test_an_arc_below_the_least_radius_is_refused_by_its_own_limit(cli, option):
    """A 1e-9 mm arc lost its tangent points' digits and was refused as 'turning 360.0 deg
    instead of 360'; it is refused by the radius's own limit, which 0.01 mm meets."""
    assert error_line(cli("trajectory", option, "1e-9")) == f"wheelstep: error: {option} = 1e-9: must be >= 0.01 mm"
    assert cli("trajectory", option, "0.01", "-q").exit_code == 0


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc, where no file can be made")
def test_a_file_that_cannot_be_made_is_named_by_its_option_not_by_a_hidden_temporary(cli):
    """The atomic writer's hidden `.x.csv.NNN.part` was named, with no option."""
    assert error_line(cli("trajectory", "--csv", "/proc/x.csv")) == (
        "wheelstep: error: --csv = /proc/x.csv: cannot be written (No such file or directory)")


def test_the_clearance_rule_names_the_arc_given_not_the_support_length(cli):
    """h_max > 2 max(r1, r2) does not involve H, yet `--r1 1e6 -H 300` was blamed on -H; of two
    arcs given, the larger is the one at fault (`--r1 40` alone passes). h-max not given is its
    default (100 without --r3), and said so."""
    assert error_line(cli("trajectory", "--r1", "1e6", "-H", "300")) == (
        "wheelstep: error: --r1 = 1e6: with it, h-max = 100 (the default) fails: must be > 2 max(r1, r2) = "
        "2e+06 mm for the top arc to touch both arcs from outside")
    assert error_line(cli("trajectory", "--r1", "40", "--r2", "70")) == (
        "wheelstep: error: --r2 = 70: with it, h-max = 100 (the default) fails: must be > 2 max(r1, r2) = "
        "140 mm for the top arc to touch both arcs from outside")
    assert cli("trajectory", "--r1", "40", "-q").exit_code == 0


def test_a_path_hundreds_of_metres_long_is_not_refused_for_the_rounding_of_its_sweeps(cli):
    """The arcs' sweeps of a 1 km path add up to 360 deg within 7e-9 rad; that was refused as
    'they turn 360.0 deg instead of 360'. The sampling's limit is what remains, said of a size
    the user gave (the spacing was not given) with the spacing that serves, which passes."""
    result = cli("trajectory", "-H", "1e6", "--r1", "0.01", "--h-max", "1e6")
    assert error_line(result) == ("wheelstep: error: -H = 1e6: with it, spacing = 1 (the default) fails: gives over "
                                  "a million points along the 3.768e+06 mm path; must be >= 3.77 mm")
    assert cli("trajectory", "-H", "1e6", "--r1", "0.01", "--h-max", "1e6", "--spacing", "3.77",
               "-q").exit_code == 0
    assert error_line(cli("trajectory", "--h-max", "1e6")).startswith(
        "wheelstep: error: --h-max = 1e6: with it, spacing = 1 (the default) fails: gives over a million points")
    # the least spacing to three digits, rounded up: it passes (0.01 was said for 0.000803)
    assert error_line(cli("trajectory", "--spacing", "0.0001")) == (
        "wheelstep: error: --spacing = 0.0001: gives over a million points along the 802.5 mm path; "
        "must be >= 0.000803 mm")
    assert cli("trajectory", "--spacing", "0.000803", "-q").exit_code == 0
