"""Tip clearance in the wheel (issue 13): the spaces are deepened below the pinion's tips."""

import json

import numpy as np
import pytest

from tests.helpers.clicheck import error_line
from wheelstep_cli.gears.generation.wheel import deepened_spaces


def test_space_bottoms_drop_by_the_clearance_and_the_flanks_stay():
    teeth, rays = 8, 800
    j = np.arange(rays)
    # trapezoid teeth: bottom 90 mm, tips 95 mm, straight flanks between
    phase = np.mod(j, rays // teeth) / (rays // teeth)
    radii = 90.0 + 5.0 * np.clip(4.0 * np.minimum(phase, 1.0 - phase) * 2.0 - 1.0, 0.0, 1.0)
    out = deepened_spaces(radii, teeth, 0.5, 0.25)
    bottom = radii == radii.min()
    assert np.allclose(out[bottom], 89.5)
    assert np.array_equal(out[radii > 90.25], radii[radii > 90.25])   # above the band: as carved
    assert np.all(out <= radii) and np.all(np.diff(out[: rays // teeth // 2]) >= -1e-12)
    assert np.array_equal(deepened_spaces(radii, teeth, 0.0, 0.25), radii)


def test_clearance_option_deepens_the_written_wheel_and_is_reported(cli, tmp_path):
    from wheelstep_cli.formats.mesh_read import read_outline

    roots = {}
    for clearance in ("0", "0.25"):
        out = tmp_path / clearance
        result = cli("gears", "--clearance", clearance, "--format", "stl", "--out", out)
        assert result.exit_code == 0, result.stderr
        report = json.loads((out / "gears.json").read_text())
        gen = report["generated"]
        assert gen["tip_clearance"]["wheel_spaces_mm"] == pytest.approx(
            float(clearance) * gen["module_mm"])
        assert report["meshing"]["interference"] is False
        wheel = read_outline(str(out / "wheel.stl"), "wheel", default_name="wheel")
        roots[clearance] = float(np.hypot(*wheel.T).min())
        module = gen["module_mm"]
    assert roots["0"] - roots["0.25"] == pytest.approx(0.25 * module, abs=0.01)


def test_clearance_out_of_bounds_is_refused(cli, tmp_path):
    result = cli("gears", "--clearance", "2", "--out", tmp_path / "out")
    assert result.exit_code == 2 and "clearance" in result.stderr
    assert not (tmp_path / "out").exists()


def test_module_solves_the_centre_distance_and_changes_the_teeth(cli, tmp_path):
    # SPEC §9: the pitch-curve perimeter grows with the distance; a module picks the distance
    # at z = 48 the module's pair meshes outside the bounds: refused with more teeth as the
    # remedy, which is applied as given
    refused = cli("gears", "--module", "2.5", "--format", "stl", "--out", tmp_path)
    remedy = error_line(refused).rsplit("; use ", 1)[1].split()
    assert remedy[0] == "--z"
    result = cli("gears", "--module", "2.5", *remedy, "--format", "stl", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    report = json.loads((tmp_path / "gears.json").read_text())
    gen, meshing = report["generated"], report["meshing"]
    assert gen["module_mm"] == pytest.approx(2.5, rel=1e-6)
    # the default's 144 mm carries module 2.1082: the distance scales with the module
    # (and with the number of teeth: the perimeter is z x the pitch)
    z = int(remedy[1])
    assert gen["rolling_center_distance_mm"] == pytest.approx(144.0 * 2.5 / 2.1082 * z / 48, rel=1e-3)
    assert gen["center_distance_chosen_by"].startswith("the module")
    assert meshing["distance_mm"] == pytest.approx(gen["rolling_center_distance_mm"])
    assert meshing["interference"] is False
    assert f"rolling at {gen['rolling_center_distance_mm']:g} mm (the centre distance module 2.5" \
        in result.stdout
