"""Tip clearance in the wheel (issue 13): the spaces are deepened below the pinion's tips."""

import json

import numpy as np
import pytest

from tests.helpers.clicheck import error_line
from wheelstep_cli.gears.generation.envelope import PolarGrid
from wheelstep_cli.gears.generation.wheel import head_on_relief, level_space_ridges, notch_weight


def test_relief_lowers_head_on_tips_and_roots_where_asked_and_keeps_the_flanks():
    teeth, rays = 8, 8000
    grid = PolarGrid(0.0, 2 * np.pi, rays)
    j = np.arange(rays)
    # trapezoid teeth: bottom 90 mm, tips 95 mm, steep flanks between (5 mm over 42 rays:
    # their normals lean ~60 deg from the radius)
    phase = np.mod(j, rays // teeth) / (rays // teeth)
    radii = 90.0 + 5.0 * np.clip(24.0 * np.minimum(phase, 1.0 - phase) - 3.0, 0.0, 1.0)
    notch = grid.angles[rays // teeth // 2]             # the middle of the first tooth's tip
    region = notch_weight(grid, np.array([notch]), 2 * np.pi / teeth)
    out = head_on_relief(radii, grid, region, 0.5, np.radians(35))
    near = np.abs(grid.angles - notch) < 0.5 * np.pi / teeth
    before = np.abs(radii - np.roll(radii, 1)) > 1e-12
    after = np.abs(np.roll(radii, -1) - radii) > 1e-12
    flat, flank = ~before & ~after, before & after                    # rays off the edges
    assert np.allclose(out[near & flat], radii[near & flat] - 0.5)       # tip and roots lowered
    assert np.allclose(out[flank], radii[flank])                        # flanks as carved
    far = np.abs(np.mod(grid.angles - notch + np.pi, 2 * np.pi) - np.pi) > 2 * np.pi / teeth
    assert np.array_equal(out[far], radii[far])                         # away from the notch: as is
    assert np.all(out <= radii)


def test_ridges_in_the_spaces_are_cut_down_and_nothing_else_moves():
    rays, teeth = 6000, 6
    phase = np.mod(np.arange(rays), rays // teeth) / (rays // teeth)
    # spaces from 88 mm to the tips at 95 mm, pitch curve at 92 mm; V-shaped flanks
    radii = 88.0 + 7.0 * np.clip(np.abs(phase - 0.5) * 4.0 - 0.5, 0.0, 1.0)
    pitch = np.full(rays, 92.0)
    flat = radii.copy()
    # a ridge 1.5 mm high and a ragged step in the bottom of two spaces, one across the
    # period's end (the walk must start outside a space)
    ridge = np.abs(phase - 0.5) < 0.04
    radii[ridge & (np.arange(rays) < rays // teeth)] += 1.5
    step = (np.abs(phase - 0.5) < 0.1) & (phase > 0.5) & (np.arange(rays) >= rays - rays // teeth)
    radii[step] += 0.3
    rolled = np.roll(radii, rays // (2 * teeth))
    for given, expected in ((radii, flat), (rolled, np.roll(flat, rays // (2 * teeth)))):
        out = level_space_ridges(given, pitch)
        assert np.allclose(out, expected)          # bumps gone, the flanks and tips as they were
        assert np.all(out <= given)
    # a ray map without spaces (all above or all below) is left as it is
    assert np.array_equal(level_space_ridges(flat, np.full(rays, 80.0)), flat)
    assert np.array_equal(level_space_ridges(flat, np.full(rays, 99.0)), flat)


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
    remedy = error_line(refused).rsplit("; use ", 1)[1].split(" (")[0].split()
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
