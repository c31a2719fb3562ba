"""`gears` and `shoe --printer NAME`: the part drawn for a printer as batch draws it; design and
printer profiles are kept apart, the wrong kind named with the option it belongs to."""

from __future__ import annotations

import json

import numpy as np
import pytest
import trimesh

from tests.helpers.clicheck import error_line
from tests.helpers.files import write


@pytest.mark.parametrize("command", ["gears", "shoe"])
@pytest.mark.parametrize("option, name, expect", [
    ("--profile", "fdm-0.4-pla", "--profile = fdm-0.4-pla: is a printer profile, not a design "
                                 "profile (a printer profile goes in --printer)"),
    ("--printer", "desk-demo", "--printer = desk-demo: is a design profile, not a printer "
                               "profile (a design profile goes in --profile)"),
    ("--printer", "fdm-0.6-abs", "--printer = fdm-0.6-abs: not found; known printer profiles: fdm-0.4-petg, "
                                 "fdm-0.4-pla, resin-0.05-standard"),
    ("--profile", "bntu", "--profile = bntu: not found; known design profiles: bntu-2024, desk-demo"),
])
def test_the_wrong_kind_of_profile_is_refused_naming_the_right_option(cli, tmp_path, command, option,
                                                                    name, expect):
    result = cli(command, option, name, "--out", tmp_path / "out")
    assert expect in error_line(result)
    assert not (tmp_path / "out").exists()


KINDS = {
    "batch": "defaults:\n  printer: fdm-0.4-pla\nparts:\n  - kind: shoe\n    design: desk-demo\n",
    "sweep": "command: gears\ndesign: desk-demo\ngrid:\n  backlash: [0.03, 0.1]\n",
    "empty": "{}\n",
    "described": "description: a printer, some day\n",
}
PRINTERS = "printer profiles: fdm-0.4-petg, fdm-0.4-pla, resin-0.05-standard"


@pytest.mark.parametrize("option, kind, expect", [
    ("--printer", "batch", "is a batch file, not a printer profile (`wheelstep batch {file}` takes it); "
                           + PRINTERS),
    ("--printer", "sweep", "is a sweep file, not a printer profile (`wheelstep sweep {file}` takes it); "
                           + PRINTERS),
    # no section tells what it is: not called a design profile
    ("--printer", "empty", "is not a printer profile (no printer keys: a printer profile has a printer: "
                           "section); " + PRINTERS),
    ("--printer", "described", "is not a printer profile (no printer keys: a printer profile has a "
                               "printer: section); " + PRINTERS),
    ("--profile", "batch", "is a batch file, not a design profile (`wheelstep batch {file}` takes it); "
                           "design profiles: bntu-2024, desk-demo"),
    ("--profile", "sweep", "is a sweep file, not a design profile (`wheelstep sweep {file}` takes it); "
                           "design profiles: bntu-2024, desk-demo"),
])
def test_a_file_of_another_kind_is_said_to_be_what_it_is(cli, tmp_path, option, kind, expect):
    """A batch or sweep file given as a profile is named as one with the command that takes
    it (not called a design profile, then refused as one for its unknown keys); a file whose
    sections do not tell is said to be no printer profile."""
    file = write(tmp_path / f"{kind}.yaml", KINDS[kind])
    assert error_line(cli("shoe", option, file, "--out", tmp_path / "out")) == (
        f"wheelstep: error: {option} = {file}: " + expect.format(file=file))
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("option", ["--profile", "--printer"])
@pytest.mark.parametrize("text, why", [("", "is empty"), ("- a\n- b\n", "holds a list"),
                                       ("3\n", "holds a single value"), (None, "folder")])
def test_a_profile_file_that_is_no_mapping_is_told_so_not_called_the_other_kind(cli, tmp_path, option,
                                                                                 text, why):
    given = tmp_path / "p.yaml" if text is not None else tmp_path / "folder"
    if text is None:
        given.mkdir()
        expect = f"{option} = {given}: is a folder, not a profile file"
    else:
        write(given, text)
        expect = f"{option} = {given}: must be a mapping of sections; the file {why}"
    assert error_line(cli("shoe", option, given, "--out", tmp_path / "out")) == f"wheelstep: error: {expect}"
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("option", ["--profile", "--printer"])
def test_a_profile_file_not_named_yaml_is_told_so_not_called_missing(cli, tmp_path, option):
    given = write(tmp_path / "p1.txt", "gears:\n  z: 48\n")
    assert error_line(cli("shoe", option, given, "--out", tmp_path / "out")) == (
        f"wheelstep: error: {option} = {given}: is not a profile file: a profile is a YAML file "
        "named *.yaml or *.yml")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("option", ["--profile", "--printer"])
def test_a_profile_file_that_is_not_text_is_said_of_the_option_that_named_it(cli, tmp_path, monkeypatch,
                                                                             option):
    """Found by its name in ./profiles or given as a path, an unreadable profile is named by the
    option the user gave, the file's path added when a name found it."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "profiles").mkdir()
    (tmp_path / "profiles" / "bin.yaml").write_bytes(b"\xff\xfe\x00binary")
    by_name = error_line(cli("shoe", option, "bin", "--out", tmp_path / "out"))
    assert by_name == f"wheelstep: error: {option} = bin: profiles/bin.yaml is not UTF-8 text (byte 0)"
    by_path = error_line(cli("shoe", option, "profiles/bin.yaml", "--out", tmp_path / "out"))
    assert by_path == f"wheelstep: error: {option} = profiles/bin.yaml: is not UTF-8 text (byte 0)"
    assert not (tmp_path / "out").exists()


def test_shoe_for_a_printer_has_the_bore_enlarged_the_foot_inset_and_says_so(cli, tmp_path):
    assert cli("shoe", "--out", tmp_path / "plain", "-q").exit_code == 0
    assert cli("shoe", "--printer", "fdm-0.4-pla", "--out", tmp_path / "pla", "-q").exit_code == 0
    report = json.loads((tmp_path / "pla" / "shoe.json").read_text())
    assert report["printer_profile"] == "fdm-0.4-pla"
    assert report["parameters"]["strut_diameter"] == 12.0
    assert report["printed_parameters"]["strut_diameter"] == pytest.approx(12.2)
    assert report["printer_geometry"]["elephant_foot_inset"] == 0.2
    assert "printer_profile" not in json.loads((tmp_path / "plain" / "shoe.json").read_text())
    plain = trimesh.load(tmp_path / "plain" / "shoe.stl")
    pla = trimesh.load(tmp_path / "pla" / "shoe.stl")
    assert pla.volume < plain.volume  # (one closed body: the elephant-foot rework of issue 11.5)
    bottom = pla.vertices[np.isclose(pla.vertices[:, 2], 0.0)]
    # the bed-side face is drawn 0.2 mm smaller all round (elephant foot)
    assert bottom[:, 0].min() == pytest.approx(plain.bounds[0, 0] + 0.2, abs=1e-4)  # float32 STL
    assert pla.bounds[0, 2] == pytest.approx(0.0, abs=1e-9)


def test_gears_for_a_printer_match_the_batch_entry_figures(cli, tmp_path):
    """Same compensation and the same meshing check as a batch entry for that printer."""
    result = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--out", tmp_path / "g",
                 "--json", "-q")
    assert result.exit_code == 0
    gears = json.loads(result.stdout)
    assert gears == {**json.loads((tmp_path / "g" / "gears.json").read_text()), "written": gears["written"],
                     "removed": []}
    assert gears["printed_parameters"]["backlash"] == pytest.approx(gears["parameters"]["backlash"] + 0.15)
    assert gears["printed_parameters"]["bore"] == pytest.approx(gears["parameters"]["bore"] + 0.2)
    batch = write(tmp_path / "pair.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                                          "    design: desk-demo\n    printer: fdm-0.4-pla\n")
    assert cli("batch", batch, "--out", tmp_path / "b", "--jobs", "1").exit_code == 0
    entry = json.loads((tmp_path / "b" / "reports" / "pair.json").read_text())
    assert entry["meshing"] == gears["meshing"]
    assert entry["printed_parameters"] == gears["printed_parameters"]
    # the printer's chamfer (profile key printer.chamfer) when the design gives none, in both
    assert gears["printed_parameters"]["chamfer"] == 0.4 and gears["parameters"]["chamfer"] is None
    assert entry["design_report"]["chamfer"] == gears["chamfer"] == {
        "mm": 0.4, "from": "printer profile fdm-0.4-pla", "elephant_foot_inset": gears["chamfer"][
            "elephant_foot_inset"]}
    for name, part in gears["parts"].items():
        assert part["volume_mm3"] == pytest.approx(entry["printed_parts"][name]["volume_mm3"], rel=1e-12)


@pytest.mark.parametrize("args, mm, source, foot", [
    (["--chamfer", "0"], 0.0, "--chamfer", "applied: the lowest 0.2 mm drawn 0.2 mm smaller"),
    (["--chamfer", "0.6"], 0.6, "--chamfer", "replaced by the chamfer"),
    ([], 0.4, "printer profile fdm-0.4-pla", "replaced by the chamfer"),
])
def test_an_explicit_chamfer_overrides_the_printers_and_the_foot_follows(cli, tmp_path, args, mm,
                                                                         source, foot):
    out = tmp_path / "g"
    result = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", *args, "--format", "stl",
                 "--out", out, "-q")
    assert result.exit_code == 0, result.stderr
    report = json.loads((out / "gears.json").read_text())
    assert report["chamfer"]["mm"] == mm and report["printed_parameters"]["chamfer"] == mm
    assert report["chamfer"]["from"].startswith(source)
    assert report["chamfer"]["elephant_foot_inset"].startswith(foot)
    mesh = trimesh.load(out / "wheel.stl")
    bottom = np.hypot(*mesh.vertices[np.isclose(mesh.vertices[:, 2], 0.0, atol=1e-6)][:, :2].T).max()
    tips = np.hypot(*mesh.vertices[:, :2].T).max()
    # the bed-side edge is drawn in by the chamfer, else by the elephant-foot inset (0.2 mm)
    assert tips - bottom == pytest.approx(mm or 0.2, abs=0.03)


def test_a_chamfer_a_design_profile_gives_is_said_to_come_from_it(cli, tmp_path):
    from wheelstep_cli.config.profiles import find_profile

    text = find_profile("desk-demo").read_text()
    assert "\ngears:\n" in text
    profile = write(tmp_path / "chamfered.yaml", text.replace("\ngears:\n", "\ngears:\n  chamfer: 0.6\n"))
    for args, source in (([], "design profile chamfered.yaml, gears.chamfer"), (["--chamfer", "0.7"], "--chamfer")):
        result = cli("gears", "--profile", profile, *args, "--dry-run", "--json", "-q")
        assert result.exit_code == 0, result.stderr
        assert json.loads(result.stdout)["chamfer"]["from"] == source


def test_no_printer_no_chamfer_says_so(cli, tmp_path):
    result = cli("gears", "--profile", "desk-demo", "--dry-run", "--json", "-q")
    assert result.exit_code == 0, result.stderr
    assert json.loads(result.stdout)["chamfer"] == {
        "mm": 0.0, "from": "none given (no --chamfer, no --printer)", "elephant_foot_inset": "none (no printer)"}


@pytest.mark.parametrize("command", [["gears", "--printer", "fdm-0.4-pla"], ["gears", "--printer", "resin-0.05-standard"]])
def test_a_chamfer_too_small_to_replace_the_foot_is_refused(cli, tmp_path, command):
    out = tmp_path / "out"
    line = error_line(cli(*command, "--chamfer", "0.2", "--out", out))
    least = "0.4" if "fdm" in command[2] else "0.35"
    assert line.startswith(f"wheelstep: error: --chamfer = 0.2: must be 0 or >= {least} mm on printer {command[2]}")
    assert not out.exists()


def test_the_backlash_line_says_how_the_printers_clearance_makes_it_up(cli):
    """A backlash the design sets gets the printer's tooth clearance on top; a default one (the
    most play the ripple bound allows) holds it, and the line says what play is left printed."""
    import re

    # 0.05 designed + 0.15 printed ripples 1.06 % on the coast flank: the bound's own remedy
    result = cli("gears", "--profile", "desk-demo", "--backlash", "0.012", "--printer", "fdm-0.4-pla",
                 "--dry-run")
    assert result.exit_code == 0, result.stderr
    found = re.search(r"backlash j_n = ([0-9.]+) mm \(([0-9.]+) designed \+ 0\.15 tooth clearance of "
                      r"printer 'fdm-0.4-pla'\)", result.stdout)
    assert found, result.stdout
    assert float(found[1]) == pytest.approx(0.162, abs=1e-4) and float(found[2]) == pytest.approx(0.012)
    default = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--dry-run")
    found = re.search(r"backlash j_n = ([0-9.]+) mm \(the design's default, which holds the 0\.15 mm tooth "
                      r"clearance of printer 'fdm-0.4-pla': ([0-9.]+) mm of play once printed\)", default.stdout)
    assert found, default.stdout
    assert float(found[1]) >= 0.15 and float(found[2]) == pytest.approx(float(found[1]) - 0.15, abs=1e-4)
    plain = cli("gears", "--profile", "desk-demo", "--dry-run")
    assert "designed +" not in plain.stdout and "holds the" not in plain.stdout
    assert "backlash j_n = " in plain.stdout


def test_a_name_not_found_lists_only_readable_profiles_whatever_lies_in_profiles(cli, tmp_path, monkeypatch):
    """The list of known names reads ./profiles/*.yaml: a binary file, a folder or an empty
    file there must not break the one-line message, nor be offered as a profile."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "profiles" / "folder.yaml").mkdir(parents=True)
    (tmp_path / "profiles" / "binary.yaml").write_bytes(b"\xff\xfe\x00")
    (tmp_path / "profiles" / "empty.yaml").write_text("")
    line = error_line(cli("shoe", "--profile", "nosuch"))
    assert line == "wheelstep: error: --profile = nosuch: not found; known design profiles: bntu-2024, desk-demo"


def test_a_limit_on_a_value_the_printer_changes_is_said_for_the_value_as_given(cli, tmp_path):
    """The bore is drawn larger by the printer's hole compensation: the refusal gives the limit
    for the bore as typed (the printed one beside it), and that value, applied, passes it; batch
    says the same of the entry's value (it showed only the printed 40.2)."""
    import re


    # (without timing marks: with them, the room they need is the bore's limit, said the same way)
    line = error_line(cli("gears", "--profile", "desk-demo", "--bore", "40", "--mark-depth", "0", "--printer",
                          "fdm-0.4-pla", "--out", tmp_path / "out"))
    found = re.search(r"--bore = 40 \(([0-9.]+) as printed\): must be < ([0-9.]+) mm \(< ([0-9.]+) mm as "
                      r"printed\)", line)
    assert found, line
    shift = float(found[1]) - 40.0
    assert shift > 0 and float(found[2]) == pytest.approx(float(found[3]) - shift, abs=0.011)
    passed = cli("gears", "--profile", "desk-demo", "--bore", found[2], "--mark-depth", "0", "--printer",
                 "fdm-0.4-pla", "--dry-run", "--out", tmp_path / "out")
    assert passed.exit_code == 0, passed.stderr
    batch = write(tmp_path / "b.yaml", "parts:\n  - name: g\n    kind: gear-pair\n    design: desk-demo\n"
                  "    printer: fdm-0.4-pla\n    overrides:\n      bore: 40\n      mark_depth: 0\n")
    result = cli("batch", batch, "--out", tmp_path / "batch")
    assert result.exit_code == 1
    assert f"bore = 40 ({found[1]} as printed): must be < {found[2]} mm (< {found[3]} mm as printed)" \
        in result.stderr, result.stderr


@pytest.mark.parametrize("args, said", [
    (["mesh-check", "{d}", "{d}"], "pinion = {d}"),
    (["mesh-check", "{d}"], "pinion = {d}"),
    (["mesh-check", "--gcode", "{d}"], "--gcode = {d}"),
    (["gears", "--law-csv", "{d}", "--out", "{o}"], "--law-csv = {d}"),
    (["batch", "{d}", "--out", "{o}"], "file = {d}"),
])
def test_a_folder_given_for_a_file_is_said_to_be_a_folder(cli, tmp_path, args, said):
    folder, out = tmp_path / "folder", tmp_path / "out"
    folder.mkdir()
    line = error_line(cli(*(a.format(d=folder, o=out) for a in args)))
    assert line == f"wheelstep: error: {said.format(d=folder)}: is a folder, not a file", line
    assert not out.exists()


@pytest.mark.parametrize("args, said", [(["mesh-check", "{l}", "{l}"], "pinion = {l}"),
                                        (["mesh-check", "--gcode", "{l}"], "--gcode = {l}")])
def test_a_broken_link_given_for_a_file_names_where_it_points(cli, tmp_path, args, said):
    link = tmp_path / "gone.stl"
    link.symlink_to(tmp_path / "moved" / "pinion.stl")
    line = error_line(cli(*(a.format(l=link) for a in args)))
    assert line == (f"wheelstep: error: {said.format(l=link)}: is a link to {tmp_path / 'moved' / 'pinion.stl'}, "
                    "which does not exist"), line


def _small_bed_printer(tmp_path, side: float, other: float | None = None) -> str:
    """The PLA preset on a ``side`` x ``other`` (default ``side``) mm bed, as a printer profile file."""
    from wheelstep_cli.config.profiles import find_profile

    bed = f"bed: [{side}, {other or side}]"
    text = find_profile("fdm-0.4-pla", printer=True).read_text().replace("bed: [256, 256]", bed)
    assert bed in text
    return str(write(tmp_path / f"bed{side}.yaml", text))


@pytest.mark.parametrize("side, given", [(100, []), (60, ["--c", "360"])])
def test_a_shoe_too_large_for_the_bed_is_offered_its_mechanism_drawn_smaller_which_prints(cli, tmp_path,
                                                                                           side, given):
    """The remedy scales a, b and the strut as given (the socket and rim keep their size);
    applied, the shoe is written on that printer's plate."""
    from tests.helpers.clicheck import remedy_in, with_remedy

    printer = _small_bed_printer(tmp_path, side)
    args = ["shoe", "--printer", printer, *given, "--out", tmp_path / "out"]
    line = error_line(cli(*args))
    assert f"does not fit the bed of printer '{printer}'" in line and "(the mechanism drawn at" in line, line
    remedy = remedy_in(line)
    assert remedy[0::2] == ["--a", "--b", "--c" if given else "--r-min"], remedy
    assert not (tmp_path / "out").exists()
    applied = cli(*with_remedy(args, remedy), "-q")
    assert applied.exit_code == 0, applied.stderr
    report = json.loads((tmp_path / "out" / "shoe.json").read_text())
    assert report["parameters"]["a"] == float(remedy[1]) and report["parameters"]["b"] == float(remedy[3])
    assert (tmp_path / "out" / "shoe.3mf").exists()


def test_a_batch_shoe_too_large_for_the_bed_is_offered_overrides_that_print(cli, tmp_path):
    import re

    entry = f"parts:\n  - kind: shoe\n    name: big\n    printer: {_small_bed_printer(tmp_path, 100)}\n"
    result = cli("batch", write(tmp_path / "big.yaml", entry), "--out", tmp_path / "out")
    assert result.exit_code == 1 and not (tmp_path / "out").exists(), result.stderr
    found = re.search(r"; not built; use overrides (\{a: [0-9.]+, b: [0-9.]+, c: [0-9.]+\}) \(the mechanism drawn",
                      result.stderr)
    assert found, result.stderr
    fixed = write(tmp_path / "fixed.yaml", entry + f"    overrides: {found.group(1)}\n")
    applied = cli("batch", fixed, "--out", tmp_path / "fixed")
    assert applied.exit_code == 0, applied.stderr
    assert [p.name for p in (tmp_path / "fixed").glob("plate-*.3mf")] == ["plate-1.3mf"]


def test_a_shoe_no_smaller_shoe_fits_names_the_option_that_stops_the_smaller_one(cli, tmp_path):
    """On a 40 mm bed the shoe small enough has no room for the 25 mm socket: the line says so
    of --socket-depth (not given: its default), and offers no remedy."""
    line = error_line(cli("shoe", "--printer", _small_bed_printer(tmp_path, 40), "--out", tmp_path / "out"))
    assert "; no remedy found (--a " in line and "is refused: --socket-depth = 25: must be <= " in line, line
    assert line.endswith(": a printer with a larger bed (--printer)"), line


def test_a_shoe_on_a_bed_barely_wider_than_its_margins_is_offered_no_mechanism_of_no_size(cli, tmp_path):
    line = error_line(cli("shoe", "--printer", _small_bed_printer(tmp_path, 10.2, 300), "--out", tmp_path / "o"))
    assert line.endswith("; no remedy found (the mechanism drawn at 0.3 % of its size rounds r_min to 0 mm): "
                         "a printer with a larger bed (--printer)"), line


def test_a_shoe_too_large_for_the_default_printers_plate_is_offered_the_smaller_shoe(cli, tmp_path):
    """No --printer, a 3MF plate: the default printer's bed, said so, with the smaller shoe as the
    remedy (as a gear pair gets it there); applied, written; with no plate (STL) no bed applies."""
    from tests.helpers.clicheck import remedy_in, with_remedy

    args = ["shoe", "--rmin", "400", "--out", tmp_path / "out"]
    line = error_line(cli(*args))
    assert "(the default printer; --printer chooses another, --format stl writes no plate); nothing written; " \
           "use --a " in line and "(the mechanism drawn at" in line, line
    assert cli(*with_remedy(args, remedy_in(line)), "-q").exit_code == 0
    assert (tmp_path / "out" / "shoe.3mf").exists()
    assert cli("shoe", "--rmin", "400", "--format", "stl", "--out", tmp_path / "stl", "-q").exit_code == 0


def test_a_shoe_whose_socket_and_rim_keep_its_height_is_offered_the_largest_smaller_shoe(cli, tmp_path):
    """On a 60 x 200 mm bed the shoe's height (the socket and rim do not scale) binds: the
    search steps past the proportional scale and halves back, so the remedy fits and the
    mechanism 0.1 mm larger (each length) does not."""
    from tests.helpers.clicheck import remedy_in, with_remedy

    args = ["shoe", "--printer", _small_bed_printer(tmp_path, 60, 200), "--out", tmp_path / "out"]
    remedy = remedy_in(error_line(cli(*args)))
    larger = [word if word.startswith("--") else f"{float(word) + 0.1:.1f}" for word in remedy]
    line = error_line(cli(*with_remedy(args, larger)))
    assert cli(*with_remedy(args, remedy), "-q").exit_code == 0
    assert "does not fit the bed" in line, line


def test_a_part_just_taller_than_the_printer_does_not_read_as_its_limit(cli, tmp_path):
    """250.01 mm on a 250 mm printer was said `250.0 mm tall, more than the 250 mm printer
    prints`: the height is said to as many decimals as it takes to differ."""
    result = cli("shoe", "--width", "250.01", "--printer", "resin-0.05-standard", "--out", tmp_path / "s")
    assert result.exit_code == 2 and not (tmp_path / "s").exists()
    assert "makes part 'shoe' 250.01 mm tall, more than the 250 mm printer" in result.stderr, result.stderr
