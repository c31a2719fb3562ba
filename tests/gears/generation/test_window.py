"""The carving window follows the geometry (issue 13): small pitches carve far enough off."""

import json

import pytest


@pytest.mark.parametrize("z", [60])
def test_small_pitch_pair_is_carved_wide_enough_to_mesh_within_the_bounds(cli, tmp_path, z):
    # carved within 1.8 pitches, z = 60 kept 39 um of F'i and 3.8 % ripple on the drive flank
    result = cli("gears", "--z", str(z), "--format", "stl", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    meshing = json.loads((tmp_path / "gears.json").read_text())["meshing"]
    assert meshing["interference"] is False
    for side in ("drive", "coast"):
        assert meshing[side]["F_i_total_um"] <= 15.0 and meshing[side]["f_i_tooth_um"] <= 10.0
    assert meshing["drive"]["hub_speed_ripple_pct"] <= 1.0
