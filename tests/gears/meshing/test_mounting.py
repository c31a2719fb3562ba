"""How much closer than designed a pair may be mounted (issue 13): the report's figure is
the outlines' least separation, and the written files mesh that much closer."""

import json

import numpy as np
import pytest

from wheelstep_cli.gears.meshing.mounting import THIN, least_separation
from tests.helpers.laws import FunctionLaw


#: phi = theta / 2 over a quarter turn of the pinion (two discs rolling 1:2)
HALF = FunctionLaw(lambda theta: 0.5 * np.asarray(theta, dtype=float), np.pi / 2)


def _circle(radius: float, points: int = 720) -> np.ndarray:
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def test_least_separation_of_two_discs_is_the_gap_between_them():
    # discs of 40 and 80 mm at 120.5 mm: 0.5 mm apart at every pose (vertices on the circles,
    # so the nearest points, on the line of centres, are vertices); reported less the 4 um
    # the outlines' thinning may hide
    gap, _ = least_separation(_circle(40.0), _circle(80.0), HALF, 120.5, samples=16)
    assert gap == pytest.approx(0.5 - 2 * THIN, abs=1e-6)
    gap, _ = least_separation(_circle(40.0), _circle(80.0), HALF, 119.9, samples=16)
    assert gap == 0.0


@pytest.fixture(scope="module")
def default_pair(tmp_path_factory):
    from wheelstep_cli.cli import run

    out = tmp_path_factory.mktemp("default")
    assert run(["gears", "--z", "48", "--format", "stl", "--out", str(out)]) == 0
    return out, json.loads((out / "gears.json").read_text())


def _mesh_check(cli, out, distance):
    result = cli("mesh-check", out / "pinion.stl", out / "wheel.stl", "--distance", f"{distance:.4f}",
                 "--samples", "768", "--json")
    return result, json.loads(result.stdout)


def test_the_default_pair_meshes_as_much_closer_as_its_report_says(cli, default_pair):
    out, report = default_pair
    meshing = report["meshing"]
    mounting = meshing["mounting"]
    assert meshing["interference"] is False
    # the tip clearance is cut (0.25 module) and no ridge stands in a space bottom: the pair
    # takes several hundredths of a millimetre
    assert report["generated"]["tip_clearance"]["wheel_spaces_mm"] == pytest.approx(
        0.25 * report["generated"]["module_mm"])
    assert mounting["closer_mm"] >= 0.04
    closer = meshing["distance_mm"] - 0.95 * mounting["closer_mm"]
    result, checked = _mesh_check(cli, out, closer)
    assert result.exit_code == 0, result.stderr
    assert checked["interference"] is False and checked["interfering_poses"] == 0


def test_the_default_pair_mounted_half_a_tenth_closer_neither_interferes_nor_jams(cli, default_pair):
    # a ridge left standing in a space bottom would meet the pinion's tips head-on here
    out, report = default_pair
    result, checked = _mesh_check(cli, out, report["meshing"]["distance_mm"] - 0.05)
    assert result.exit_code == 0, result.stderr
    assert checked["interference"] is False and checked["interfering_poses"] == 0
    assert checked["backlash_min_mm"] > 0


@pytest.mark.xfail(strict=True, reason="issue 13: at the pitch-curve corners the pinion's corner "
                   "space, cut by the rack pivoting about the corner point, meets the wheel's notch "
                   "tooth with no radial clearance; mounted 0.1 mm closer they overlap. Cutting that "
                   "space shallower costs f'i (9.9 um at 0.05 mm, 15 um at 0.1) and still jams "
                   "(benchmarks/results.md, the corner socket)")
def test_the_default_pair_mounted_a_tenth_closer_does_not_interfere(cli, default_pair):
    out, report = default_pair
    result, checked = _mesh_check(cli, out, report["meshing"]["distance_mm"] - 0.1)
    assert checked["interference"] is False


def test_the_mounting_line_does_not_call_touching_outlines_clear():
    from wheelstep_cli.parts.mesh_check import mounting_line

    assert "clear when mounted up to 0.047 mm closer" in mounting_line(
        {"closer_mm": 0.0467, "at_pinion_deg": 90.8})
    line = mounting_line({"closer_mm": 0.0, "at_pinion_deg": 45.0})
    assert "not known to be clear mounted any closer" in line and "up to 0.000" not in line
    assert "within 0.004 mm" in line
