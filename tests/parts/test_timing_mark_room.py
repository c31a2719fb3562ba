"""A gear whose web has no room for its timing mark is refused (the pair is set in phase by
its marks), naming the option that took the room and the remedy; without marks it is built."""

from __future__ import annotations

from tests.helpers.clicheck import error_line


def test_a_hub_that_leaves_the_pinion_no_room_for_its_mark_is_refused(cli, tmp_path):
    out = tmp_path / "out"
    args = ("gears", "--profile", "desk-demo", "--hub-d", "34", "--format", "stl", "--out", out, "-q")
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --hub-d = 34: with it, mark-depth = 0.5 fails: leaves "
                           "the pinion no room for its timing mark"), line
    assert "--mark-depth 0 for no marks" in line and not out.exists()
    # the remedy, applied: no marks asked for, none missing
    result = cli(*args, "--mark-depth", "0")
    assert result.exit_code == 0, result.stderr
    assert (out / "pinion.stl").exists()
