"""A gear whose web has no room for its timing mark is refused (the pair is set in phase by
its marks), naming the option that took the room and the remedy; without marks it is built."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tests.helpers.clicheck import error_line, with_remedy


def test_a_hub_that_leaves_the_pinion_no_room_for_its_mark_is_refused(cli, tmp_path):
    out = tmp_path / "out"
    args = ("gears", "--profile", "desk-demo", "--hub-d", "34", "--format", "stl", "--out", out, "-q")
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --hub-d = 34: must be <= 27.91 mm: larger, it leaves "
                           "the pinion no room for its timing mark"), line
    assert line.endswith("; or --mark-depth 0 for no marks") and not out.exists()
    # the one value the line offers is the --json remedy (it was {}; the hub's is a limit)
    refused = json.loads(cli(*args, "--json").stdout)["error"]
    assert refused["remedy"] == {"--mark-depth": 0.0} and refused["remedies"] == [{"--mark-depth": 0.0}], refused
    # the remedy, applied: no marks asked for, none missing
    result = cli(*args, "--mark-depth", "0")
    assert result.exit_code == 0, result.stderr
    assert (out / "pinion.stl").exists()
    # and the assembly note does not send the user to marks that are not there
    phase = json.loads((out / "gears.json").read_text())["phase"]
    note = phase["shaft"]["note"]
    assert "carry no timing marks (mark depth 0)" in note and "marks face each other" not in note
    assert "no timing marks are engraved" in phase["carrier_zero"]["note"], phase["carrier_zero"]
    assert "the timing marks point" not in phase["carrier_zero"]["note"]


@pytest.mark.parametrize("args, flag", [
    (["--hub-d", "36.12"], "--hub-d"),          # within the hub's own wall rule, not the mark's
    (["--bore", "40"], "--bore"),
    (["--bore-shape", "keyway", "--key-depth", "4", "--bore", "22"], "--key-depth"),
    (["--bore-shape", "keyway", "--bore", "30"], "--bore"),
    (["--bore-shape", "hex", "--bore", "30"], "--bore"),
    (["--bore-shape", "d-flat", "--bore", "34"], "--bore"),
    (["--bore", "34", "--printer", "fdm-0.4-pla"], "--bore"),   # the printer draws the bore larger
])
def test_the_mark_room_refusal_names_the_largest_value_that_leaves_room(cli, tmp_path, args, flag):
    """The option the user gave that narrows the web is named with the largest value that
    leaves the mark its room; that value applied, the pair is made."""
    out = ["--dry-run", "--out", tmp_path / "out"]
    result = cli("gears", "--profile", "desk-demo", *args, *out, "--json")
    line = error_line(result)
    assert line.startswith(f"wheelstep: error: {flag} = ") and "no room for its timing mark" in line, line
    largest = line.split(": must be <= ", 1)[1].split(" mm", 1)[0]
    # --json: the number given (the line may show what the printer drew beside it)
    assert json.loads(result.stdout)["error"]["value"] == float(args[args.index(flag) + 1])
    fixed = list(args)
    fixed[fixed.index(flag) + 1] = largest
    result = cli("gears", "--profile", "desk-demo", *fixed, *out)
    assert result.exit_code == 0, result.stderr


def test_the_mark_depth_given_names_the_bore_as_given_to_a_printer_that_draws_it_larger(cli, tmp_path):
    """With --mark-depth given, the refusal is stated for it and names the largest bore that
    leaves room: said as the bore the user gives (the printer draws it larger, the printed
    bound beside it); applied, the pair is made (said as printed, it was refused again)."""
    args = ["gears", "--profile", "desk-demo", "--bore", "34", "--printer", "fdm-0.4-pla", "--mark-depth", "0.5",
            "--dry-run", "--out", tmp_path / "out"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --mark-depth = 0.5: leaves the pinion no room"), line
    largest, printed = line.split("--bore <= ", 1)[1].split(" mm (<= ", 1)
    assert float(largest) < float(printed.split(" mm as printed)")[0]) < 34
    result = cli(*with_remedy(args, ["--bore", largest]))
    assert result.exit_code == 0, result.stderr


def test_the_assembly_note_of_marked_gears_on_a_round_bore_says_to_face_the_marks():
    from types import SimpleNamespace

    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.gear_phase import shaft_record

    spec = gear_pair_spec(None)
    assert spec.mark_depth > 0 and spec.bore_shape == "round"
    law = SimpleNamespace(pinion_periods=2, wheel_periods=2)
    assert "turn each gear until the marks face each other" in shaft_record(spec, law)["note"]
    # a keyed bore sets the phase with or without marks
    keyed = spec.model_copy(update={"bore_shape": "keyway", "mark_depth": 0.0})
    assert "keyed shaft fits one way" in shaft_record(keyed, law)["note"]
    # a hex bore without marks: in phase every way only when the teeth repeat with the hex
    hexed = spec.model_copy(update={"bore_shape": "hex", "mark_depth": 0.0})
    assert "every one in phase" in shaft_record(hexed, SimpleNamespace(pinion_periods=6, wheel_periods=12))["note"]
    assert "carry no timing marks" in shaft_record(hexed, law)["note"]


def test_lighten_with_no_room_for_a_pocket_in_the_wheel_is_refused(cli, tmp_path):
    """A 1:1 law makes the wheel as small as the pinion: at 40 mm its web has no room for a
    pocket, so --lighten would cut nothing and is refused with the remedy; at 60 mm (the
    remedy: a larger centre distance) it cuts."""
    turns = np.linspace(0.0, 360.0, 73)
    law = tmp_path / "law.csv"
    law.write_text("driving_deg,driven_deg\n" + "".join(
        f"{a:.4f},{b:.6f}\n" for a, b in zip(turns, turns + 8.0 * np.sin(np.radians(2.0 * turns)))))
    out = tmp_path / "out"
    args = ("gears", "--law-csv", law, "--lighten", "--mark-depth", "0", "--format", "stl", "--out", out, "-q")
    line = error_line(cli(*args, "--center-distance", "40"))
    assert line.startswith("wheelstep: error: --lighten = on: leaves no room for pockets in the wheel ("), line
    assert "a larger --center-distance" in line and "or print without --lighten" in line
    assert not out.exists()
    # the remedy applied
    assert cli(*args, "--center-distance", "60", "--json").exit_code == 0
    assert json.loads((out / "gears.json").read_text())["lighten"]["wheel"]["pockets"] > 0


def test_no_marks_is_offered_only_where_the_gear_holds_without_them(cli, tmp_path):
    """A 200 mm hub on a 40-tooth pinion: --mark-depth 0 was offered, and applied, the hub was
    refused by its own wall rule; only the hub that leaves room is offered, and it passes."""
    args = ["gears", "--turns", "4", "--z", "40", "--hub-d", "200", "--dry-run", "--out", tmp_path / "out"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --hub-d = 200: must be <= ") and "mark-depth" not in line, line
    largest = line.split(": must be <= ", 1)[1].split(" mm", 1)[0]
    assert cli(*with_remedy(args, ["--hub-d", largest])).exit_code == 0
    assert cli(*args, "--mark-depth", "0").exit_code == 2


def test_a_hub_the_mark_leaves_no_size_for_names_the_bore_first(cli, tmp_path):
    """Bore 26 and hub 34 on the desk pinion: the largest hub that leaves the mark its web
    (27.91 mm) is below the least that walls a 26 mm bore (29 mm), so a hub_d limit would be
    refused in turn as too small. The bore is named first; each limit applied, the pair is made."""
    out = ["--dry-run", "--out", tmp_path / "out"]
    args = ["gears", "--profile", "desk-demo", "--bore", "26", "--hub-d", "34", *out]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --bore = 26: must be <= ") and "no room for its timing mark" in line, line
    args[args.index("--bore") + 1] = line.split(": must be <= ", 1)[1].split(" mm", 1)[0]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --hub-d = 34: must be <= "), line
    args[args.index("--hub-d") + 1] = line.split(": must be <= ", 1)[1].split(" mm", 1)[0]
    done = cli(*args)
    assert done.exit_code == 0, done.stderr
