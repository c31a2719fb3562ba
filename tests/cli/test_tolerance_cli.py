"""`gears --tolerance / --fit`: a printer without a band is told to add one (SPEC §11)."""

from __future__ import annotations

import pytest

from tests.helpers.clicheck import error_line
from tests.helpers.files import printer_profile_without_band


def test_a_printer_without_a_band_is_refused_by_tolerance_and_fit(cli, tmp_path):
    printer = printer_profile_without_band(tmp_path)
    for option in (["--tolerance"], ["--fit", "auto"]):
        result = cli("gears", "--printer", str(printer), *option, "--out", tmp_path / "out")
        line = error_line(result)
        assert "has no dimensional band: add a `band:` section" in line
        assert not (tmp_path / "out").exists()


def test_an_unknown_fit_is_refused(cli, tmp_path):
    result = cli("gears", "--fit", "snug", "--out", tmp_path / "out")
    assert result.exit_code == 2 and "--fit" in result.stderr


def test_mesh_check_printer_without_tolerance_is_refused(cli, tmp_path):
    result = cli("mesh-check", "a.stl", "b.stl", "--printer", "fdm-0.4-pla")
    assert "--printer = fdm-0.4-pla: names the band --tolerance checks" in error_line(result)


def test_mesh_check_tolerance_on_plates_is_refused(cli, tmp_path):
    result = cli("mesh-check", "plate.3mf", "--tolerance")
    assert "checks two named meshes (PINION WHEEL), not plates" in error_line(result)


def test_gears_tolerance_reports_every_case_and_the_loose_corner_has_more_play(cli, tmp_path):
    import json

    result = cli("gears", "--profile", "desk-demo", "--tolerance", "--printer", "resin-0.05-standard",
                 "--json", "-q", "--out", tmp_path / "out")
    assert result.exit_code == 0, result.stderr
    meshing = json.loads((tmp_path / "out" / "gears.json").read_text())["meshing"]
    band = meshing["tolerance"]
    assert band["printer"] == "resin-0.05-standard" and band["band"]["outline_mm"] == 0.05
    cases = {case["case"]: case for case in band["cases"]}
    assert list(cases) == ["tight", "pinion grown, wheel shrunk", "pinion shrunk, wheel grown", "loose"]
    loose = cases["loose"]
    assert loose["distance_mm"] == pytest.approx(meshing["distance_mm"] + 0.03)
    assert not loose["jams"] and loose["backlash_min_mm"] > meshing["backlash_min_mm"]
    assert band["largest_backlash_mm"] == max(c["backlash_max_mm"] for c in band["cases"])
