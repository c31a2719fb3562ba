"""Configuration models: every problem of a file reported at once with its line; one
snake_case name per parameter, the flag derived from it; --profile and batch share the rules."""

from __future__ import annotations

import json
import re
import pytest

from tests.helpers.clicheck import error_line
from tests.helpers.files import line_of, write


SEVERAL_BAD = """\
parts:
  - name: pair
    kind: gear-pair
    design: desk-demo
    printer: fdm-0.4-pla
    overrides:
      thickness: -2
      z: 24.5
      blend: 40
      teeth: wooden
  - name: shoe
    kind: shoe
    design: desk-demo
    printer: fdm-0.4-pla
    quantity: 500
    overrides:
      width: 0
      rim: thin
"""


def test_batch_reports_every_bad_value_of_an_entry_with_its_line(cli, tmp_path):
    batch = write(tmp_path / "bad.yaml", SEVERAL_BAD)
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    expected = {
        "thickness: -2": "parts[0].overrides.thickness = -2: must be >= 0.5 mm, and at least twice the mark depth "
                         "(1 mm with the default 0.5 mm marks)",
        "z: 24.5": "parts[0].overrides.z = 24.5: must be a whole number",
        "blend: 40": "parts[0].overrides.blend = 40: must be 0..20 deg",
        "teeth: wooden": "parts[0].overrides.teeth = 'wooden': must be one of: generated, paper",
        "quantity: 500": "parts[1].quantity = 500: must be between 1 and 200",
        "width: 0": "parts[1].overrides.width = 0: must be > 0 mm",
        "rim: thin": "parts[1].overrides.rim = 'thin': must be a number",
    }
    assert len(lines) == len(expected), result.stderr
    for needle, message in expected.items():
        assert f"wheelstep: error: {batch}:{line_of(batch, needle)}: {message}" in lines, result.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("command", ["batch", "sweep"])
@pytest.mark.parametrize("text, where, message", [
    ("- a\n", 1, "must be a mapping of keys"),
    ("just words\n", 1, "must be a mapping of keys"),
])
def test_a_file_that_is_not_a_mapping_is_one_line(cli, tmp_path, command, text, where, message):
    path = write(tmp_path / "top.yaml", text)
    line = error_line(cli(command, path, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {path}:{where}: {message}"
    assert not (tmp_path / "out").exists()


def test_a_batch_entry_that_is_not_a_mapping_is_named_at_its_line(cli, tmp_path):
    path = write(tmp_path / "entry.yaml", "parts:\n  - 3\n")
    line = error_line(cli("batch", path, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {path}:2: parts[0]: must be a mapping of keys"


def test_a_generator_setting_on_paper_teeth_is_refused_at_its_line(cli, tmp_path):
    """The rack cutter's settings do not shape the paper teeth: a batch entry that gives one
    with them is refused where it is written, not built with it ignored."""
    batch = write(tmp_path / "paper.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                  "    design: desk-demo\n    printer: fdm-0.4-pla\n    overrides:\n      teeth: paper\n"
                  "      tilt: 0.3\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    line = error_line(result)
    assert line.startswith(f"wheelstep: error: {batch}:{line_of(batch, 'tilt: 0.3')}: "
                           "parts[0].overrides.tilt = 0.3: shapes generated teeth only"), line
    assert not (tmp_path / "out").exists()


def test_design_profile_reports_every_bad_value_with_its_line(cli, tmp_path):
    design = write(tmp_path / "mine.yaml", "mechanism:\n  a: thirty\n  b: 50\ngears:\n  z: 24\n"
                   "  bore: -1\nshoe:\n  width: -4\n  colour: red\n")
    result = cli("gears", "--profile", design, "--out", tmp_path / "out")
    assert result.exit_code == 2
    lines = [re.sub(r"^wheelstep: error: ", "", ln) for ln in result.stderr.strip().splitlines()]
    assert lines == [
        f"{design}:2: mechanism.a = 'thirty': must be a number",
        f"{design}:6: gears.bore = -1: must be >= 0 mm",
        f"{design}:8: shoe.width = -4: must be > 0 mm",
        f"{design}:9: shoe.colour: unknown key; allowed: a, b, c, r_min, width, strut_diameter, "
        "socket_depth, rim",
    ]


def test_a_design_profile_breaking_several_rules_is_told_all_of_them_at_once(cli, tmp_path):
    """A rule stops at the first value it finds at fault: the profile is resolved again
    without the keys found so far, so the user mends the file in one go (it took four runs)."""
    text = ("gears:\n  z: 42\n  thickness: 1\n  chamfer: 2\n  mark_depth: 0.8\n  key_width: 2\n"
            "  hub_length: 3\n")
    design = write(tmp_path / "rules.yaml", text)
    result = cli("gears", "--profile", design, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert [re.sub(r"^wheelstep: error: ", "", ln) for ln in result.stderr.strip().splitlines()] == [
        f"{design}:4: gears.chamfer = 2: must be < half the thickness 0.5 mm",
        f"{design}:5: gears.mark_depth = 0.8: must be <= half the thickness, 0.5 mm",
        f"{design}:6: gears.key_width = 2: needs bore_shape keyway",
        f"{design}:7: gears.hub_length = 3: needs hub_d",
    ]
    assert not (tmp_path / "out").exists()
    # mended as the lines say, the profile is read (and the pair is sized) without a problem
    mended = write(tmp_path / "mended.yaml", "gears:\n  thickness: 2\n  chamfer: 0.5\n"
                   "  mark_depth: 0.8\n  bore_shape: keyway\n  key_width: 2\n  hub_d: 16\n  hub_length: 3\n")
    assert cli("gears", "--profile", mended, "--dry-run", "--out", tmp_path / "out").exit_code == 0
    # a rule the defaults standing in for a key found at fault take part in is not blamed on
    # the others: the key width's limit is the bore's, so no second line for the keyway
    tied = write(tmp_path / "tied.yaml", "gears:\n  bore_shape: keyway\n  bore: 1\n  key_depth: 3\n")
    lines = cli("gears", "--profile", tied, "--out", tmp_path / "out").stderr.strip().splitlines()
    assert lines == [f"wheelstep: error: {tied}:3: gears.bore = 1: must be > the key width 2 mm"], lines
    # a D-flat's depth against the default bore standing in for a bore of 0 ("must be < half
    # the bore 4 mm") is not said: the flat is sized by the bore the file gives
    flat = write(tmp_path / "flat.yaml", "gears:\n  bore_shape: d-flat\n  bore: 0\n  flat_depth: 5\n")
    lines = cli("gears", "--profile", flat, "--out", tmp_path / "out").stderr.strip().splitlines()
    assert lines == [f"wheelstep: error: {flat}:3: gears.bore = 0: must be > 0 mm for a D-flat"], lines


def test_a_problem_of_a_stand_in_default_does_not_end_the_profiles_search(cli, tmp_path):
    """The dedendum found at fault, the default one standing in is below the file's addendum:
    that rule is not said (it is the default's), and the search goes on past it to the faces'
    rules and the mechanism, checked once the spec builds (they came in later runs)."""
    design = write(tmp_path / "p.yaml", "mechanism:\n  a: 30\n  b: 50\n  c: 160\ngears:\n  thickness: 1\n"
                   "  chamfer: 0.8\n  addendum: 1.3\n  dedendum: 1.1\n")
    result = cli("gears", "--profile", design, "--out", tmp_path / "out")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    lines = [re.sub(r"^wheelstep: error: ", "", ln) for ln in result.stderr.strip().splitlines()]
    assert [ln.split(" = ")[0] for ln in lines] == [f"{design}:4: mechanism.c", f"{design}:7: gears.chamfer",
                                                     f"{design}:9: gears.dedendum"], lines


@pytest.mark.parametrize("command", ["gears", "shoe"])
def test_profile_with_a_wrong_typed_value_is_one_line_naming_the_key(cli, tmp_path, command):
    design = write(tmp_path / "typo.yaml", "mechanism:\n  a: 30\n  b: fifty\n")
    result = cli(command, "--profile", design, "--out", tmp_path / "out")
    line = error_line(result)
    assert line == f"wheelstep: error: {design}:3: mechanism.b = 'fifty': must be a number"
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("command, text, key, expect", [
    # a rule of the mechanism the profile gives: said at its line, by its key, not as a flag
    ("gears", "mechanism:\n  a: 60\n  b: 110\n  c: 360\ngears:\n  z: 48\n", "c: 360",
     "mechanism.c = 360: must be >= 4b - a + 0.001 = 380.001 mm"),
    ("shoe", "mechanism:\n  a: 60\n  b: -5\n", "b: -5", "mechanism.b = -5: must be >= 0 mm"),
    ("pitch", "mechanism:\n  a: 60\n  b: 110\n  c: 360\n", "c: 360", "mechanism.c = 360: must be >"),
    # rules met while the pair is built: too tall for the printer, undercut teeth
    ("gears", "gears:\n  thickness: 300\n", "thickness: 300",
     "gears.thickness = 300: makes part 'pinion' 300.0 mm tall"),
    # ... and the command's own flags in its words stay flags (a design profile has no printer key)
    ("gears", "gears:\n  thickness: 300\n", "thickness: 300",
     "gears.thickness = 300: makes part 'pinion' 300.0 mm tall, more than the 250 mm printer "
     "'fdm-0.4-pla' prints (the default printer; --printer chooses another, --format stl writes no plate)"),
    ("gears", "gears:\n  z: 12\n", "z: 12", "gears.z = 12: the rack undercuts the pinion"),
])
def test_a_rule_a_profiles_value_breaks_is_said_at_its_line(cli, tmp_path, command, text, key, expect):
    design = write(tmp_path / "mech.yaml", text)
    out = ["--out", tmp_path / "out"] if command != "pitch" else []
    line = error_line(cli(command, "--profile", design, *out))
    assert line.startswith(f"wheelstep: error: {design}:{line_of(design, key)}: {expect}"), line
    assert not (tmp_path / "out").exists()
    # the same value given on the command line is named by its flag
    flag = "--" + key.split(":")[0]
    value = key.split(": ")[1]
    assert error_line(cli(command, "--profile", design, flag, value, *out)).startswith(
        f"wheelstep: error: {flag} = {value}: ")


def test_profile_and_batch_share_the_rules(tmp_path):
    """The same profile value is refused by --profile and by a batch entry, in the same words."""
    from wheelstep_cli.batch import load_batch
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.config.schema import InvalidInput

    design = write(tmp_path / "d.yaml", "gears:\n  tilt: 3\n")
    batch = write(tmp_path / "b.yaml", f"parts:\n  - kind: gear-pair\n    design: {design}\n"
                  "    printer: fdm-0.4-pla\n")
    with pytest.raises(InvalidInput) as by_profile:
        gear_pair_spec(str(design))
    with pytest.raises(InvalidInput) as by_batch:
        load_batch(batch)
    assert by_profile.value.lines()[0].split(": ", 1)[1] == by_batch.value.lines()[0].split(": ", 1)[1] \
        == "gears.tilt = 3: must be 0..1.5"


def test_flag_is_derived_from_the_snake_case_name():
    from wheelstep_cli.config.names import flag_name, yaml_message
    from wheelstep_cli.errors import DesignError

    assert flag_name("install_distance") == "--install-distance"
    assert flag_name("r_min") == "--r-min"
    err = DesignError("install_distance", 140.0, "must be >= the centre distance 143.5 mm")
    assert yaml_message(err) == "install_distance = 140: must be >= the centre distance 143.5 mm"
    # a part's flags said as a file's keys; a command's own flags and a quoted command line kept
    err = DesignError("flat_depth", 1.0, "needs --bore-shape d-flat; give --force; `wheelstep gears --printer P`")
    assert yaml_message(err) == ("flat_depth = 1: needs bore_shape d-flat; give --force; "
                                 "`wheelstep gears --printer P`")


def test_specs_refuse_unknown_and_wrong_typed_values_naming_the_parameter():
    from wheelstep_cli.config.resolve import gear_pair_spec, shoe_spec
    from wheelstep_cli.errors import DesignError

    with pytest.raises(DesignError) as info:
        gear_pair_spec(None, teeth="paper", center_distance=143.5, install_distance=140.0)
    assert info.value.param == "install_distance"
    with pytest.raises(DesignError) as info:
        shoe_spec(None, strut_diameter=-1.0)
    assert (info.value.param, info.value.limit) == ("strut_diameter", "must be >= 1 mm")
    assert gear_pair_spec(None, a=80).a == 80 and isinstance(gear_pair_spec(None, a=80).a, int)
    assert isinstance(shoe_spec(None, a=80).a, float)


def test_a_printer_chamfer_too_small_to_replace_its_foot_is_refused_at_its_line(cli, tmp_path):
    """printer.chamfer must be 0 or at least elephant_foot_inset + elephant_foot_height."""
    from pathlib import Path

    from wheelstep_cli.config.profiles import shipped_profiles

    text = (Path(shipped_profiles()) / "fdm-0.4-pla.yaml").read_text()
    assert "\n  chamfer: 0.4\n" in text
    printer = write(tmp_path / "p.yaml", text.replace("\n  chamfer: 0.4\n", "\n  chamfer: 0.3\n"))
    line_no = printer.read_text().splitlines().index("  chamfer: 0.3") + 1
    result = cli("gears", "--printer", printer, "--out", tmp_path / "out")
    assert error_line(result).startswith(f"wheelstep: error: {printer}:{line_no}: printer.chamfer = 0.3: "
                                         "must be 0 or >= 0.4 mm")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("bed, expect", [
    ("[256]", "printer.bed = [256]: must be [X, Y] in mm, each > 0 and <= 2000"),
    ("[8, 300]", "printer.bed = [8, 300]: must be > 10 mm each (twice the 5 mm a part keeps from each edge"),
])
def test_a_printer_bed_of_one_size_or_inside_its_margins_is_refused_at_its_line(cli, tmp_path, bed, expect):
    """A bed list of the wrong length says the bed's own limit; a bed no part fits inside its
    margins is refused with the profile, not part by part with remedies of negative size."""
    from pathlib import Path

    from wheelstep_cli.config.profiles import shipped_profiles

    text = (Path(shipped_profiles()) / "fdm-0.4-pla.yaml").read_text()
    assert "\n  bed: [256, 256] " in text
    printer = write(tmp_path / "p.yaml", text.replace("\n  bed: [256, 256] ", f"\n  bed: {bed}\n "))
    line_no = printer.read_text().splitlines().index(f"  bed: {bed}") + 1
    for command in ("shoe", "gears"):
        line = error_line(cli(command, "--printer", printer, "--out", tmp_path / "out"))
        assert line.startswith(f"wheelstep: error: {printer}:{line_no}: {expect}"), line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("text, z", [("48", 48), ("48.0", 48), ("48.", 48)])
def test_a_whole_number_written_with_a_point_is_that_number_as_on_the_command_line(tmp_path, text, z):
    """YAML reads `z: 48.0` as a float; like `--z 48.0` it is the whole number 48, stored
    as an int (a profile and the command line take the same values)."""
    from wheelstep_cli.config.resolve import gear_pair_spec

    spec = gear_pair_spec(str(write(tmp_path / "p.yaml", f"gears:\n  z: {text}\n  turns: 2.0\n")))
    assert spec.z == z and type(spec.z) is int and spec.turns == 2 and type(spec.turns) is int


@pytest.mark.parametrize("text", ["48.5", "'48'", "true", ".inf"])
def test_what_is_no_whole_number_stays_refused_at_its_line(cli, tmp_path, text):
    profile = write(tmp_path / "p.yaml", f"gears:\n  z: {text}\n")
    line = error_line(cli("gears", "--profile", profile, "--out", tmp_path / "out"))
    assert line.startswith(f"wheelstep: error: {profile}:2: gears.z = ") and line.endswith(
        ": must be a whole number"), line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("text, expect", [
    ("  bore_shape: 0x10\n", "gears.bore_shape = '0x10': must be one of: round, d-flat, keyway, hex"),
    ("  dedendum: -1\n", "gears.dedendum = -1: must be above the addendum and <= 2.5 x module"),
])
def test_a_choice_is_not_told_to_be_digits_and_a_dedendum_states_both_ends(cli, tmp_path, text, expect):
    profile = write(tmp_path / "p.yaml", "gears:\n" + text)
    line = error_line(cli("gears", "--profile", profile, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {profile}:2: {expect}", line


@pytest.mark.parametrize("args", [
    ("gears", "--turns", "2", "--dry-run"), ("gears", "--dry-run"), ("shoe", "--dry-run"),
    ("kinematics", "--turns", "4"), ("pitch",),
])
def test_a_profiles_turns_is_checked_with_the_rest_at_its_line_whatever_overrides_it(cli, tmp_path, args):
    """The law takes 2 or 4 turns: a profile's other value is refused at its line, overridden
    or not, and by every command that reads the profile (the shoe's too)."""
    profile = write(tmp_path / "p.yaml", "mechanism:\n  a: 30\n  b: 50\n  c: 180\ngears:\n  z: 42\n"
                    "  turns: 3\nshoe:\n  width: 20\n")
    line = error_line(cli(args[0], "--profile", profile, *args[1:], *(
        ["--out", tmp_path / "out"] if "--dry-run" in args else [])))
    assert line == (f"wheelstep: error: {profile}:{line_of(profile, 'turns: 3')}: gears.turns = 3: "
                    "must be 2 (balanced pinion) or 4 (one pinion turn per shoe)"), line


def test_kinematics_takes_a_profiles_turns_as_the_model_reads_them(cli, tmp_path):
    """`turns: 4.0` is the whole number 4 in a profile as on the command line."""
    profile = write(tmp_path / "p.yaml", "gears:\n  turns: 4.0\n")
    result = cli("kinematics", "--profile", profile)
    assert result.exit_code == 0, result.stderr
    assert "4 pinion turns per carrier turn" in result.stdout


ADDENDUM_RULE = ("must be < the dedendum (1.25 x module; the difference is the tip clearance) "
                 "and >= 0.3 x module")


@pytest.mark.parametrize("args, expect", [
    (["--addendum", "1.5"], f"--addendum = 1.5: {ADDENDUM_RULE}"),
    (["--dedendum", "0.9"], "--dedendum = 0.9: must be > the addendum (1 x module; the difference is the tip "
                               "clearance) and <= 2.5 x module"),
    (["--addendum", "1.5", "--dedendum", "1.4"],
     "--dedendum = 1.4: must be > the addendum (1.5 x module; the difference is the tip clearance) "
     "and <= 2.5 x module"),
])
def test_the_dedendum_above_the_addendum_is_said_of_the_one_given(cli, tmp_path, args, expect):
    """Of the two tied values the refusal names the option the user typed, not the default."""
    line = error_line(cli("gears", "--profile", "desk-demo", *args, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {expect}"
    assert not (tmp_path / "out").exists()


def test_an_addendum_above_the_dedendum_is_said_at_its_line_in_a_profile_and_a_batch(cli, tmp_path):
    """Not at the profile's first key that sizes the pair (it said `gears.z = 42: with it,
    dedendum = 1.25 fails`)."""
    profile = write(tmp_path / "p.yaml", "gears:\n  z: 42\n  addendum: 1.5\n")
    line = error_line(cli("gears", "--profile", profile, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {profile}:3: gears.addendum = 1.5: {ADDENDUM_RULE}"
    batch = write(tmp_path / "b.yaml", "parts:\n  - kind: gear-pair\n    design: desk-demo\n"
                  "    printer: fdm-0.4-pla\n    overrides:\n      addendum: 1.5\n")
    line = error_line(cli("batch", batch, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {batch}:6: parts[0].overrides.addendum = 1.5: {ADDENDUM_RULE}"
    assert not (tmp_path / "out").exists()


def test_a_long_value_in_an_error_line_is_said_by_what_it_is(cli, tmp_path):
    """A JSON report given as a batch file: its nested 'parts' mapping is named by its keys,
    not dumped whole into the line."""
    assert cli("gears", "--format", "stl", "-q", "--out", tmp_path / "o").exit_code == 0
    result = cli("batch", tmp_path / "o" / "gears.json", "--dry-run")
    assert result.exit_code == 2
    line = next(line for line in result.stderr.splitlines() if ": parts = " in line)
    assert line.endswith(": parts = {a mapping of 2 keys: pinion, wheel}: must be a list of at least one part"), line


def test_a_choice_is_read_in_any_case_in_a_profile_as_on_the_command_line(cli, tmp_path):
    """`--corner Tooth` was taken and `corner: Tooth` in a profile refused: both are taken, as
    the name the choice has (what is stored and written), and a wrong name is still refused."""
    from wheelstep_cli.config.resolve import gear_pair_spec

    profile = write(tmp_path / "p.yaml", "gears:\n  corner: Tooth\n  bore_shape: HEX\n  teeth: Generated\n")
    spec = gear_pair_spec(str(profile))
    assert (spec.corner, spec.bore_shape, spec.teeth) == ("tooth", "hex", "generated")
    wrong = write(tmp_path / "q.yaml", "gears:\n  corner: Tooht\n")
    line = error_line(cli("gears", "--profile", wrong, "--dry-run", "--out", tmp_path / "out"))
    assert "corner = 'Tooht': must be one of: space, tooth" in line, line


@pytest.mark.parametrize("given", [{"a": 50}, {"b": 90}, {"a": 45, "b": 110}])
def test_a_gear_pair_and_a_shoe_of_the_same_a_and_b_follow_one_mechanism(given):
    """Without a strut both take R_min = 20 mm (c = R_min - a + 4b), as the help says."""
    from wheelstep_cli.config.specs import GearPairSpec, ShoeSpec

    pair, shoe = GearPairSpec(**given), ShoeSpec(**given).design()
    assert pair.c == pytest.approx(shoe.c) == pytest.approx(20 - shoe.a + 4 * shoe.b)
    assert pair.mechanism().r_min == pytest.approx(20)
    assert GearPairSpec(**given, c=300).c == 300


def test_a_gear_pair_whose_a_and_b_leave_no_strut_is_said_of_them(cli, tmp_path):
    line = error_line(cli("gears", "--a", "500", "--b", "10", "--out", tmp_path / "out"))
    assert line.startswith("wheelstep: error: --b = 10: must be > (a - R_min)/4 = 120 mm"), line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("command", ["gears", "shoe", "kinematics"])
def test_a_parts_section_that_changes_the_profiles_mechanism_is_refused_at_its_lines(cli, tmp_path, command):
    """The gears and the shoe of a profile share its mechanism: a part section giving other
    lengths is said at each of its lines, whatever the command; the same lengths pass."""
    profile = write(tmp_path / "p.yaml", "mechanism:\n  a: 60\n  b: 100\n  r_min: 20\n"
                                         "gears:\n  a: 50\n  c: 360\nshoe:\n  c: 360\n")
    out = ["--out", tmp_path / "out"] if command != "kinematics" else []
    result = cli(command, "--profile", profile, *out)
    assert result.exit_code == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    # the key that differs, not its section's other keys, which agree
    assert [line.split(": ", 3)[3].split(" =")[0] for line in lines] == ["gears.a"], lines
    assert f"{profile}:{line_of(profile, 'a: 50')}" in lines[0]
    assert "a = 50, b = 100, c = 360 mm" in lines[0] and "a = 60, b = 100, c = 360 mm" in lines[0]
    assert not (tmp_path / "out").exists()
    write(profile, "mechanism:\n  a: 60\n  b: 100\n  r_min: 20\ngears:\n  a: 60\n  c: 360\nshoe:\n  c: 360\n")
    assert cli(command, "--profile", profile, *out).exit_code == 0


def test_a_profile_with_a_bad_value_and_a_mechanism_conflict_gets_both_at_once(cli, tmp_path):
    """Every problem of a profile at once, in its lines' order: a value out of range and a
    part section's other mechanism; a mechanism section with a bad value has no lengths to
    compare (nothing more said of the parts' lengths)."""
    profile = write(tmp_path / "p.yaml", "mechanism:\n  a: 30\ngears:\n  z: 3\n  a: 31\n"
                                         "shoe:\n  width: -1\n  b: 40\n")
    result = cli("gears", "--profile", profile, "--dry-run")
    assert result.exit_code == 2
    said = [line.split(": ", 3)[2:] for line in result.stderr.strip().splitlines()]
    assert [what.split(" =")[0] for _, what in said] == ["gears.z", "gears.a", "shoe.width", "shoe.b"], said
    assert [where.rsplit(":", 1)[1] for where, _ in said] == ["4", "5", "7", "8"], said
    write(profile, "mechanism:\n  a: x\ngears:\n  a: 31\n  z: 3\n")
    lines = cli("gears", "--profile", profile, "--dry-run").stderr.strip().splitlines()
    assert [line.split(": ", 3)[3].split(" =")[0] for line in lines] == ["mechanism.a", "gears.z"], lines
    # a mechanism section's other problem leaves its lengths to compare; an empty value is one
    # problem among the others
    write(profile, "mechanism:\n  a: 30\n  d: 5\ngears:\n  z:\n  a: 31\nshoe:\n  width: -1\n")
    lines = cli("gears", "--profile", profile, "--dry-run").stderr.strip().splitlines()
    assert [line.split(": ", 3)[3].split(":")[0].split(" =")[0] for line in lines] == [
        "mechanism.d", "gears.z", "gears.a", "shoe.width"], lines
    # a strut given both ways and disagreeing, in the mechanism or a part's section, is one of
    # them too (it was found only once the others were fixed)
    write(profile, "mechanism:\n  a: 30\n  b: 50\n  c: 180\n  r_min: 20\nshoe:\n  width: -1\n"
                   "  c: 180\n  r_min: 15\n")
    lines = cli("shoe", "--profile", profile, "--dry-run").stderr.strip().splitlines()
    assert [line.split(": ", 3)[3] for line in lines if "r_min" in line] == [
        "mechanism.r_min = 20: contradicts c = 180 mm (a - 4b + c = 10 mm); give only one of c and R_min",
        "shoe.r_min = 15: contradicts c = 180 mm (a - 4b + c = 10 mm); give only one of c and R_min"], lines
    assert any("shoe.width = -1" in line for line in lines), lines


def test_a_yaml_word_read_as_a_switch_by_yaml_1_1_is_said_as_written(cli, tmp_path):
    """`quantity: yes` is YAML 1.1's true (it was said as `quantity = true`, with why): read
    as YAML 1.2 reads it, the text written, it is said as written."""
    batch = write(tmp_path / "b.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n    design: desk-demo\n"
                                       "    printer: fdm-0.4-pla\n    quantity: yes\n")
    line = error_line(cli("batch", batch, "--out", tmp_path / "out"))
    assert line.endswith(f"{batch}:6: parts[0].quantity = 'yes': must be a whole number"), line


def test_a_batch_law_csv_is_said_as_the_file_writes_it(cli, tmp_path, monkeypatch):
    """An entry's law CSV is found beside the batch file; a refusal at its line shows the path
    as written there, not as found from the working folder."""
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    write(tmp_path / "short.csv", "driving_deg,driven_deg\n0,0\n10,5\n")
    batch = write(jobs / "b.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n    design: desk-demo\n"
                                   "    printer: fdm-0.4-pla\n    overrides:\n      law_csv: ../short.csv\n")
    monkeypatch.chdir(tmp_path)
    line = error_line(cli("batch", batch.relative_to(tmp_path), "--out", "out"))
    assert "parts[0].overrides.law_csv = '../short.csv': needs at least" in line, line


@pytest.mark.parametrize("text, key", [
    ("gears:\n  a: 50\n", "gears.a"),           # no mechanism section: the source design's is shared
    ("shoe:\n  r_min: 25\n", "shoe.r_min"),
    ("gears:\n  law_csv: law.csv\n  turns: 4\n", "gears.turns"),   # a law CSV has no crank law
    ("gears:\n  law_csv: law.csv\n  b: 90\n", "gears.b"),
])
def test_a_part_section_cannot_set_its_own_crank_law(cli, tmp_path, text, key):
    import numpy as np

    phi = np.linspace(0.0, 90.0, 91)
    write(tmp_path / "law.csv", "driving_deg,driven_deg\n" + "\n".join(f"{2 * p:g},{p:g}" for p in phi))
    profile = write(tmp_path / "p.yaml", text)
    for command in (["gears", "--dry-run"], ["kinematics"]):
        line = error_line(cli(*command, "--profile", profile))
        assert f"{profile}:{line_of(profile, key.split('.')[1] + ':')}: {key} = " in line, line


def test_an_empty_value_in_a_profile_is_refused_at_its_line(cli, tmp_path):
    """`law_csv:` with nothing after it is YAML's null: the default would stand while the file
    seems to set it."""
    profile = write(tmp_path / "p.yaml", "gears:\n  law_csv:\n  z: 48\nmechanism:\n  a:\n")
    result = cli("gears", "--profile", profile, "--out", tmp_path / "out")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert result.stderr.strip().splitlines() == [
        f"wheelstep: error: {profile}:2: gears.law_csv = null: give a value, or leave the key out for the default",
        f"wheelstep: error: {profile}:5: mechanism.a = null: give a value, or leave the key out for the default"]


@pytest.mark.parametrize("text", ["1.0e2", "1e2"])
def test_a_number_whose_exponent_has_no_sign_is_told_how_yaml_reads_it(cli, tmp_path, text):
    """YAML 1.1 reads 1.0e2 as text (its exponent needs a sign): said with the forms it reads."""
    profile = write(tmp_path / "p.yaml", f"mechanism:\n  b: {text}\n")
    line = error_line(cli("gears", "--profile", profile, "--out", tmp_path / "out"))
    assert line.endswith(f"mechanism.b = '{text}': must be a number written with the exponent's sign (1.0e+2) "
                         "or as plain decimal digits (100)"), line
    write(profile, "mechanism:\n  b: 1.0e+2\n")
    assert cli("gears", "--profile", profile, "--dry-run", "--out", tmp_path / "out").exit_code == 0


@pytest.mark.parametrize("command, report", [("shoe", "shoe.json"), ("gears", "gears.json")])
def test_a_profile_in_the_working_folder_that_replaces_a_preset_is_warned_of_and_recorded(
        cli, tmp_path, monkeypatch, command, report):
    """A profiles/ folder in the working folder comes before the shipped presets: a file there
    named as a preset is said to be read instead of it, and the report records the file read
    (its SHA-256), as it does for the preset itself."""
    import hashlib
    import json
    from pathlib import Path

    from wheelstep_cli.config.profiles import shipped_profiles

    preset = (Path(shipped_profiles()) / "desk-demo.yaml").read_bytes()
    monkeypatch.chdir(tmp_path)
    shipped = cli(command, "--profile", "desk-demo", "--out", "a", "--dry-run", "--json", "-q")
    assert shipped.exit_code == 0 and "warning" not in shipped.stderr, shipped.stderr
    assert json.loads(shipped.stdout)["design_profile"] == {
        "given": "desk-demo", "file": "desk-demo.yaml", "sha256": hashlib.sha256(preset).hexdigest(), "shipped": True}
    local = preset.replace(b"  width: 20", b"  width: 21")
    assert local != preset
    (tmp_path / "profiles").mkdir()
    write(tmp_path / "profiles" / "desk-demo.yaml", local.decode())
    result = cli(command, "--profile", "desk-demo", "--out", "b")
    assert result.exit_code == 0, result.stderr
    assert ("wheelstep: warning: --profile desk-demo is read from profiles/desk-demo.yaml, a profiles/ folder in "
            "the working folder, not the shipped preset of that name") in result.stderr
    assert json.loads((tmp_path / "b" / report).read_text())["design_profile"] == {
        "given": "desk-demo", "file": "desk-demo.yaml", "sha256": hashlib.sha256(local).hexdigest(), "shipped": False}
    # a path given is recorded by its file's name: no folder of the user's in a report
    by_path = cli(command, "--profile", tmp_path / "profiles" / "desk-demo.yaml", "--out", "c", "--dry-run",
                  "--json", "-q")
    assert json.loads(by_path.stdout)["design_profile"]["given"] == "desk-demo.yaml"


@pytest.mark.parametrize("command", ["gears", "shoe"])
def test_a_strut_given_both_ways_keeps_c_when_the_command_line_resizes_the_cranks(cli, tmp_path, command):
    """A profile's agreeing c and R_min, with --a given: c is kept (as a c given alone is), not
    refused as contradicting by arithmetic made with the command line's a."""
    from wheelstep_cli.config.resolve import gear_pair_spec, shoe_spec

    profile = str(write(tmp_path / "p.yaml", "mechanism:\n  a: 60\n  b: 100\n  c: 360\n  r_min: 20\n"))
    resolve = gear_pair_spec if command == "gears" else shoe_spec
    spec = resolve(profile, a=50.0)
    assert spec.c == 360 and getattr(spec, "r_min", None) is None
    assert resolve(profile).c == 360


def _said(result) -> list[str]:
    return [re.sub(r"^wheelstep: error: ", "", ln) for ln in result.stderr.strip().splitlines()]


def test_the_command_lines_problems_and_the_profiles_are_told_together(cli, tmp_path):
    """Bad options are said all at once, as a profile's keys are, and neither hides the
    other: a run found one option at a time (``--flat-depth 1 --mark-depth 6`` took two)."""
    out = tmp_path / "out"
    result = cli("gears", "--flat-depth", "1", "--mark-depth", "6", "--z", "3", "--out", out)
    assert result.exit_code == 2 and not out.exists()
    assert sorted(ln.split(" = ")[0] for ln in _said(result)) == ["--flat-depth", "--mark-depth", "--z"], _said(result)
    tables = cli("pitch", "--z", "3", "--turns", "9")
    assert tables.exit_code == 2 and [ln.split(" = ")[0] for ln in _said(tables)] == ["--z", "--turns"]
    # the profile's rules and the command line's, in one run
    design = write(tmp_path / "p.yaml", "mechanism:\n  a: 9999\ngears:\n  thickness: 1\n  chamfer: 2\n")
    result = cli("gears", "--profile", design, "--pressure-angle", "50", "--out", out)
    lines = _said(result)
    assert result.exit_code == 2 and not out.exists()
    assert sorted(ln.split(" = ")[0] for ln in lines) == sorted(
        [f"{design}:2: mechanism.a", f"{design}:5: gears.chamfer", "--pressure-angle"]), lines
    # the file's lines together, in its order (they were split round the option's)
    in_file = [ln.startswith(str(design)) for ln in lines]
    assert in_file in ([True, True, False], [False, True, True]) and lines.index(
        next(ln for ln in lines if ":2: " in ln)) < lines.index(next(ln for ln in lines if ":5: " in ln)), lines
    # in --json: each problem, an option's with no file line
    record = json.loads(cli("gears", "--profile", design, "--pressure-angle", "50", "--json",
                            "--out", out).stdout)["error"]
    keys = [(p["where"], p["key"]) for p in record["problems"]]
    assert (None, "--pressure-angle") in keys and (f"{design}:2", "mechanism.a") in keys, keys
    assert record["message"].splitlines() == [f"wheelstep: error: {ln}" for ln in lines]
    # mended as the lines say, it runs
    mended = write(tmp_path / "m.yaml", "mechanism:\n  a: 60\ngears:\n  thickness: 5\n  chamfer: 2\n")
    assert cli("gears", "--profile", mended, "--pressure-angle", "20", "--dry-run", "--out", out).exit_code == 0


def test_a_profile_that_cannot_be_read_does_not_hide_the_options_own_problems(cli, tmp_path):
    """A value out of its own bounds stops the file being read; the options' own rules are
    still said, but not one the profile's values could mend (--a 400 against a b it gives)."""
    design = write(tmp_path / "p.yaml", "mechanism:\n  b: 120\ngears:\n  z: 3\n")
    out = tmp_path / "out"
    result = cli("shoe", "--profile", design, "--width", "-3", "--a", "400", "--out", out)
    assert result.exit_code == 2 and not out.exists()
    assert _said(result) == [f"{design}:4: gears.z = 3: must be 6..240 (pinion teeth)",
                             "--width = -3: must be > 0 mm"]
    missing = cli("gears", "--profile", tmp_path / "none.yaml", "--z", "3", "--out", out)
    assert [ln.split(" = ")[0] for ln in _said(missing)] == ["--profile", "--z"], _said(missing)


def test_a_profiles_values_out_of_bounds_do_not_hide_its_rules_between_values(cli, tmp_path):
    """A value out of its own bound stopped the file being read, and the rules between its
    other values came in the next run: the file is read again without the keys at fault, and
    its rules are said with its bounds, in its lines' order, the options' after them; a rule
    tied to a key at fault is not (its default stands in)."""
    design = write(tmp_path / "p.yaml", "mechanism:\n  a: 9999\ngears:\n  z: 3\n  thickness: 1\n"
                   "  chamfer: 2\n  key_width: 2\n  pressure_angle: 50\n")
    out = tmp_path / "out"
    result = cli("gears", "--profile", design, "--mark-depth", "9", "--out", out)
    assert result.exit_code == 2 and not out.exists()
    assert [ln.split(" = ")[0].split(": ")[0] for ln in _said(result)] == [
        f"{design}:2", f"{design}:4", f"{design}:6", f"{design}:7", f"{design}:8", "--mark-depth"], _said(result)
    assert "gears.chamfer = 2: must be < half the thickness 0.5 mm" in _said(result)[2]
    tied = write(tmp_path / "tied.yaml", "gears:\n  thickness: 0.3\n  chamfer: 0.4\n")
    assert [ln.split(": ")[1] for ln in _said(cli("gears", "--profile", tied, "--out", out))] == ["gears.thickness = 0.3"]


def test_mesh_checks_distance_is_named_as_typed_among_the_other_problems(cli, tmp_path):
    """mesh-check's --distance is the design's installed distance: renamed for the line, it
    dropped the run's other problems, and one found after another kept its inner name."""
    for other, flag in ((["--blend", "-3"], "--blend"), (["--turns", "3"], "--turns")):
        result = cli("mesh-check", tmp_path / "p.stl", tmp_path / "w.stl", "--distance", "-5", *other)
        assert result.exit_code == 2
        assert sorted(ln.split(" = ")[0] for ln in _said(result)) == sorted(["--distance", flag]), _said(result)
