"""Sector-involute teeth (SPEC §5): reference points and closed outlines."""

import json
import re

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.paper_teeth import (ToothForm, check_tooth_form, involute_polar_angle,
                                             pinion_outline, wheel_outline)
from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.gears.pitch_curves import pinion_radius, wheel_radius
from wheelstep_cli.mechanism.crank import CrankMechanism
from wheelstep_cli.gears.sectors import sector_partition
from tests.helpers.clicheck import error_line


def test_reference_points(cli):
    result = cli("teeth", "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["parameters"]["z"] == 48 and data["parameters"]["module"] > 0
    p1 = data["pinion"][0]["points"]
    assert [round(p["theta_deg"], 2) for p in p1] == [-88.76, -88.64, -88.43, -88.16, -87.84]
    assert [round(p["theta_s_deg"], 2) for p in p1] == [-85.44, -85.55, -85.77, -86.04, -86.36]
    assert [round(p["r_mm"], 2) for p in p1] == [59.30, 60.30, 61.30, 62.30, 63.30]
    w1 = data["wheel"][0]["points"]
    assert [round(p["phi_deg"], 2) for p in w1] == [-43.80, -43.87, -44.01, -44.18, -44.39]
    assert [round(p["phi_s_deg"], 2) for p in w1] == [-41.87, -41.80, -41.66, -41.49, -41.28]
    assert len(data["pinion"]) == 24 and len(data["wheel"]) == 24


def test_teeth_takes_the_paper_rules_not_the_generators(cli):
    """`teeth` prints sector-involute teeth: a module and the distance their sectors roll at
    go together, as for `gears --teeth paper` (the generator's rule would refuse them)."""
    result = cli("teeth", "--module", "2", "--center-distance", "143.5", "--json", "-v")
    assert result.exit_code == 0, result.stderr
    assert "center_distance = 143.5" in result.stderr and "module = 2.0" in result.stderr
    assert len(json.loads(result.stdout)["pinion"]) == 24


@pytest.mark.parametrize("command", ["pitch", "teeth"])
@pytest.mark.parametrize("gears, args", [
    # a profile tuned for generated teeth: the generator's settings and the part's shape
    ("{z: 42, install_distance: 72.125, tilt: 0.8, blend: 10, thickness: 6, bore: 5}", []),
    ("{z: 42, install_distance: 72.125}", ["--center-distance", "80"]),   # mounted nowhere
    ("{z: 42, install_distance: 72.125}", ["--z", "120"]),
])
def test_the_tables_read_only_what_they_draw_from_a_profile(cli, tmp_path, command, gears, args):
    """pitch and teeth draw the paper method's sectors: a profile's generator settings, bore
    and installed distance do not refuse them (they are not mounted)."""
    profile = tmp_path / "tuned.yaml"
    profile.write_text(f"mechanism: {{a: 30, b: 50, c: 180}}\ngears: {gears}\n")
    extra = ["--module", "0.4"] if command == "teeth" else []
    result = cli(command, "--profile", profile, *args, *extra, "--json")
    assert result.exit_code == 0, result.stderr
    assert json.loads(result.stdout)


def test_a_backlash_no_module_can_carry_names_no_module(cli):
    line = error_line(cli("teeth", "--backlash", "6.1"))
    assert "teeth come to a point" in line and "--module" not in line.split("use ")[1], line


def test_a_module_too_large_names_one_that_works(cli):
    """The desk demo at half scale cannot carry the paper teeth's default module 2: the
    refusal names the largest module that can, and that module is accepted."""
    result = cli("teeth", "--profile", "desk-demo", "--json")
    line = error_line(result)
    found = re.search(r"use --module ([0-9.]+) or less", line)
    # the module the line names is the one a script reads
    assert json.loads(result.stdout)["error"]["remedies"] == [{"--module": float(found.group(1))}]
    # the module nobody gave is said to be the default
    assert line.startswith("wheelstep: error: --module = 2: the paper teeth's default module (none given): "
                           "too large for the tooth pitch") and found, line
    assert cli("teeth", "--profile", "desk-demo", "--module", found.group(1), "--json").exit_code == 0
    above = f"{float(found.group(1)) + 0.05:.2f}"
    assert cli("teeth", "--profile", "desk-demo", "--module", above, "--backlash", "0.5").exit_code == 2


def test_the_module_named_is_the_largest_with_its_own_default_backlash_whatever_was_given(cli):
    """With no --backlash the backlash follows the module (0.25 m): the largest module named
    is the same for every too-large module given (it kept the given module's backlash: 2.83
    for -m 3, 2.13 for -m 10), it is accepted, and 0.01 mm more is refused."""
    named = set()
    for module in ("3", "5", "10"):
        found = re.search(r"use --module ([0-9.]+) or less", error_line(cli("teeth", "-m", module)))
        named.add(found.group(1))
    assert len(named) == 1, named
    largest = float(named.pop())
    assert cli("teeth", "-m", f"{largest:g}", "-q").exit_code == 0
    assert cli("teeth", "-m", f"{largest + 0.01:.2f}", "-q").exit_code == 2


def test_involute_polar_angle_matches_definition():
    alpha = np.radians(20.0)
    assert involute_polar_angle(np.cos(alpha), 1.0) == pytest.approx(np.tan(alpha) - alpha)
    assert involute_polar_angle(10.0, 10.0) == 0.0


def count_teeth(outline: np.ndarray, pitch_radius, module: float) -> int:
    """Teeth = runs of outline points more than m/2 outside the exact pitch curve."""
    radius = np.hypot(outline[:, 0], outline[:, 1])
    angle = np.arctan2(outline[:, 1], outline[:, 0])
    outer = radius > pitch_radius(angle) + module / 2
    return int(np.count_nonzero(outer & ~np.roll(outer, 1)))


@pytest.mark.parametrize("z, n, wheel_teeth", [(48, 2, 96), (24, 4, 96), (40, 2, 80)])
def test_outlines_are_simple_and_have_the_tooth_count(z, n, wheel_teeth):
    law = CrankLaw(CrankMechanism(60, 100, 360), n)
    part = sector_partition(law, z * n // 4, 143.5)
    form = ToothForm(2.0 * 48 / max(z, wheel_teeth / 2) if n == 2 else 2.0, 0.5)
    check_tooth_form(part, form)
    pinion_pitch = lambda theta: pinion_radius(law, law.carrier_angle(theta), 143.5)
    wheel_pitch = lambda phi: wheel_radius(law, phi, 143.5)
    for outline, pitch, teeth in ((pinion_outline(part, form), pinion_pitch, z),
                                  (wheel_outline(part, form), wheel_pitch, wheel_teeth)):
        ring = shapely.LinearRing(outline)
        assert ring.is_simple
        assert shapely.Polygon(outline).area > 0
        assert count_teeth(outline, pitch, form.module) == teeth


def test_pointed_teeth_are_refused():
    part = sector_partition(CrankLaw(CrankMechanism(60, 100, 360), 2), 24, 143.5)
    with pytest.raises(DesignError) as err:
        check_tooth_form(part, ToothForm(3.0, 0.75))
    assert err.value.param == "module"


@settings(max_examples=25, deadline=None)
@given(st.floats(0, 104), st.sampled_from([32, 40, 48, 56]))
def test_outline_simple_over_designs(b, z):
    law = CrankLaw(CrankMechanism(60, b, 360), 2)
    part = sector_partition(law, z // 2, 143.5)
    form = ToothForm(0.3 * part.arc, 0.075 * part.arc)
    check_tooth_form(part, form)
    assert shapely.LinearRing(pinion_outline(part, form)).is_simple
    assert shapely.LinearRing(wheel_outline(part, form)).is_simple


def test_pitch_shows_only_the_parameters_its_partition_uses(cli):
    result = cli("pitch", "-v", "--json")
    assert result.exit_code == 0, result.stderr
    shown = [line.split("=")[0].strip() for line in result.stderr.splitlines() if " = " in line]
    assert shown == ["a", "b", "c", "z", "turns", "center_distance"]
    assert "center_distance = 143.5" in result.stderr        # the paper sectors' L_p
