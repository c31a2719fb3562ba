"""Every option acts or is refused: an option given where it would change nothing is one
line naming it (as the user wrote it), exit 2, nothing written."""

from __future__ import annotations

import json

import pytest

from tests.helpers.clicheck import error_line


@pytest.mark.parametrize("args, line", [
    # stairs: a sweep sizes over its own landing angles and sole radii, draws no tables
    (["stairs", "--sweep", "--sole-radius", "50"], "--sole-radius = 50: is not used: such options do nothing with --sweep"),
    (["stairs", "--sweep", "--landing-angle=-30"], "--landing-angle = -30: is not used"),
    (["stairs", "--sweep", "--step", "2"], "--step = 2: is not used"),
    (["stairs", "--sweep", "--tol", "3"], "--tol = 3: is not used"),
    # the allowed miss is the design check's, the sole radius the sizing's
    (["stairs", "--tol", "5"], "--tol = 5: is the design check's allowed miss: give the design"),
    (["stairs", "--a", "100", "--b", "50", "--y1", "130", "--y2", "192", "--sole-radius", "60"],
     "--sole-radius = 60: sizes a design for the stair; the design checked has its own"),
    (["trajectory", "--o3-root", "upper"], "--o3-root = upper: shapes --r3: give --r3 too"),
    (["trajectory", "--dxf-polyline"], "--dxf-polyline = on: shapes --dxf: give --dxf too"),
    (["linkage", "--gif-frames", "10"], "--gif-frames = 10: shapes --gif: give --gif too"),
    (["linkage", "-q", "--step", "30"], "--step = 30: shapes the printed table, which -q does not print"),
    (["kinematics", "--json", "--rows", "3"], "--rows = 3: shapes the printed table"),
    (["kinematics", "-q", "--rows", "3"], "--rows = 3: shapes the printed table"),
    (["stairs", "-q", "-v"], "-v = on: cannot be combined with -q/--quiet"),
    (["stairs", "--quiet", "--verbose"], "--verbose = on: cannot be combined with -q/--quiet"),
])
def test_an_option_that_would_do_nothing_is_refused(cli, tmp_path, args, line):
    out = tmp_path / "out.png"
    # a picture asked for too: nothing of it is written when the run is refused
    result = cli(*args, *([] if "--sweep" in args else ["--plot", out]))
    assert error_line(result).startswith(f"wheelstep: error: {line}"), result.stderr
    assert not out.exists()


@pytest.mark.parametrize("option", [["--a", "50"], ["--b", "90"], ["--c", "400"], ["--turns", "4"]])
@pytest.mark.parametrize("command", ["gears", "mesh-check"])
def test_the_crank_law_options_are_refused_with_a_law_csv(cli, tmp_path, command, option):
    """A law CSV replaces the crank law: what sizes that law would do nothing."""
    csv = tmp_path / "law.csv"
    csv.write_text("driving_deg,driven_deg\n0,0\n180,90\n360,180\n")
    meshes = [tmp_path / "p.stl", tmp_path / "w.stl"] if command == "mesh-check" else []
    out = tmp_path / "out"
    line = error_line(cli(command, *meshes, "--law-csv", csv, *option, "--out" if command == "gears"
                          else "--plot", out if command == "gears" else out / "m.png"))
    assert line.startswith(f"wheelstep: error: {option[0]} = {option[1]}: sets the crank law, "
                           "which --law-csv replaces"), line
    assert not out.exists()


@pytest.mark.parametrize("installed, source", [(["--distance", "144"], "--distance"),
                                               (["--profile", "desk-demo"], "the profile's install_distance")])
def test_mesh_check_refuses_a_center_distance_an_installed_distance_overrides(cli, tmp_path, installed, source):
    line = error_line(cli("mesh-check", tmp_path / "p.stl", tmp_path / "w.stl", *installed,
                          "--center-distance", "140"))
    assert line == ("wheelstep: error: --center-distance = 140: gives the distance checked at when "
                    f"none is installed; {source} sets it here"), line


def test_a_batch_entry_with_a_law_csv_refuses_its_crank_override_at_its_line(cli, tmp_path):
    from tests.helpers.files import line_of, write

    csv = tmp_path / "law.csv"
    csv.write_text("driving_deg,driven_deg\n" + "".join(f"{d},{d / 2:g}\n" for d in range(0, 361, 45)))
    batch = write(tmp_path / "b.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                  "    printer: fdm-0.4-pla\n    overrides:\n      law_csv: " + str(csv) + "\n"
                  "      b: 90\n")
    line = error_line(cli("batch", batch, "--out", tmp_path / "out"))
    assert line.startswith(f"wheelstep: error: {batch}:{line_of(batch, 'b: 90')}: "
                           "parts[0].overrides.b = 90: sets the crank law, which the entry's law_csv replaces"), line
    assert not (tmp_path / "out").exists()


def test_a_crank_option_over_a_profiles_law_csv_names_the_profile_as_its_source(cli, tmp_path):
    """The CSV came from the profile, not from --law-csv: the refusal says so (a batch entry
    whose design holds it likewise names the design's)."""
    from tests.helpers.files import write

    csv = tmp_path / "law.csv"
    csv.write_text("driving_deg,driven_deg\n" + "".join(f"{d},{d / 2:g}\n" for d in range(0, 361, 45)))
    profile = write(tmp_path / "p.yaml", f"gears:\n  law_csv: {csv}\n")
    line = error_line(cli("gears", "--profile", profile, "--a", "50", "--out", tmp_path / "out"))
    assert line == ("wheelstep: error: --a = 50: sets the crank law, which the profile's gears.law_csv "
                    "replaces (the pair follows the law read from the CSV)"), line
    batch = write(tmp_path / "b.yaml", f"parts:\n  - kind: gear-pair\n    design: {profile}\n"
                  "    printer: fdm-0.4-pla\n    overrides:\n      a: 50\n")
    line = error_line(cli("batch", batch, "--out", tmp_path / "out"))
    assert "parts[0].overrides.a = 50: sets the crank law, which the design's gears.law_csv replaces" in line, line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("args, line", [
    (["gears", "--z", "4_8"], "--z = 4_8: must be a whole number, 6..240 (pinion teeth), written without "
                              "underscores"),
    (["gears", "-vn4_8"], "-n = 4_8: must be a whole number"),     # bundled after a switch
    (["gears", "--backlash=0_1"], "--backlash = 0_1: must be a number"),
    (["gears", "-n2_0"], "-n = 2_0: must be a whole number"),
    (["kinematics", "--b", "1_00"], "--b = 1_00: must be a number"),
    (["teeth", "-m0_5"], "-m = 0_5: must be a number"),
    (["teeth", "-qm", "0_5"], "-m = 0_5: must be a number"),
    (["stairs", "--sweep", "--sweep-angles", "1_0,20"], "--sweep-angles = 1_0,20: must be numbers 'a,b,c' or "
                                                        "'start:stop:step', written without underscores"),
])
def test_a_number_with_an_underscore_is_refused_not_read_as_digits(cli, tmp_path, args, line):
    """Python reads 4_8 as 48: a slip, not a number a person means."""
    out = tmp_path / "out"
    result = cli(*args, *(["--out", out] if args[0] == "gears" else []))
    assert result.exit_code == 2 and error_line(result).startswith(f"wheelstep: error: {line}"), result.stderr
    assert not out.exists()
    assert cli(*args, "--help").exit_code == 0          # asking for help is not refused


@pytest.mark.parametrize("args, line", [
    (["gears", "--z", "40", "--z", "48"], "--z = 48: given twice (--z = 40 before it); give it once"),
    (["gears", "--z=40", "-n", "2", "--turns", "4"], "--turns = 4: given twice (-n = 2 before it)"),
    (["trajectory", "--csv", "p.csv", "--csv", "q.csv"], "--csv = q.csv: given twice (--csv = p.csv "
                                                         "before it)"),
    (["linkage", "--preset", "chebyshev", "--branch", "C=1", "--branch", "C=-1"],
     "--branch = C=-1: gives joint C again (C=1 before it); give each joint once"),
    (["batch", "x.yaml", "--tolerance", "--no-tolerance"],
     "--no-tolerance = on: contradicts --tolerance, given too; give one of them"),
])
def test_an_option_given_twice_is_refused_not_read_as_its_last_value(cli, tmp_path, monkeypatch, args, line):
    """The parser kept the last of two values and dropped the other unsaid (`--csv p.csv --csv
    q.csv` wrote only q.csv). Switches (-v -v) and options that collect values (--branch of
    different joints, --gcode) stay repeatable."""
    monkeypatch.chdir(tmp_path)
    result = cli(*args)
    assert result.exit_code == 2 and error_line(result).startswith(f"wheelstep: error: {line}"), result.stderr
    assert list(tmp_path.iterdir()) == []
    both = cli("linkage", "--preset", "jansen", "--branch", "F=+1", "--branch", "K=-1", "--json")
    assert both.exit_code == 0, both.stderr
    branches = json.loads(both.stdout)["branches"]
    assert (branches["F"], branches["K"]) == (1, -1)
    twice = cli("pitch", "-v", "-v")
    assert twice.exit_code == 0 and "a = 60" in twice.stderr


@pytest.mark.parametrize("args, files", [
    (["kinematics", "--dry-run"], "--plot"),
    (["kinematics", "--force", "-q"], "--plot"),
    (["stairs", "--force", "-q"], "--plot"),
    (["linkage", "--dry-run"], "--csv or --plot or --gif"),
    (["trajectory", "--dry-run"], "--csv or --dxf or --plot"),
])
def test_dry_run_or_force_without_a_file_to_write_is_refused(cli, tmp_path, monkeypatch, args, files):
    """These commands write only the files their options name: without one, --dry-run and
    --force did nothing and exited 0 silently. With a file named, they act."""
    monkeypatch.chdir(tmp_path)
    flag = "--dry-run" if "--dry-run" in args else "--force"
    assert error_line(cli(*args)) == (f"wheelstep: error: {flag} = on: acts on the files the command "
                                      f"writes, and without {files} it writes none")
    plot = cli(*args, "--plot", "p.png")
    assert plot.exit_code == 0, plot.stderr
    if flag == "--dry-run":
        assert "would write p.png" in plot.stdout and not (tmp_path / "p.png").exists()
    else:
        assert (tmp_path / "p.png").is_file()


@pytest.mark.parametrize("flag", ["--dry-run", "--force"])
def test_dry_run_or_force_with_a_stairs_sweep_is_refused_as_the_plot_is(cli, flag):
    """A sweep prints a table and writes no file; the remedy of the flag above (--plot) is
    itself refused with --sweep, so the flag is refused as such options are."""
    assert error_line(cli("stairs", "--sweep", flag)) == (
        f"wheelstep: error: {flag} = on: is not used: such options do nothing with --sweep")


@pytest.mark.parametrize("text", ["4_8", "1:30", "060", "0x30", "0b110000", "0o60", "-010"])
def test_a_yaml_number_yaml_1_1_would_misread_is_text(cli, tmp_path, text):
    """YAML 1.1 reads 4_8 as 48, 1:30 as 90 (base 60), 060 as 48 (octal: a thickness of 010
    printed 8 mm), 0x30 and 0b110000 as 48; read as text, a number field refuses it with the
    file's other problems, saying how to write the number (0o60, YAML 1.2's octal, is text to
    YAML 1.1 too), and a text field keeps it."""
    profile = tmp_path / "p.yaml"
    profile.write_text(f"gears:\n  z: {text}\n  thickness: -1\n")
    lines = cli("gears", "--profile", profile, "--out", tmp_path / "out").stderr.splitlines()
    how = "" if text == "0o60" else " written as plain decimal digits (no leading zero, underscore, base prefix or colon)"
    assert lines[0] == f"wheelstep: error: {profile}:2: gears.z = '{text}': must be a whole number{how}", lines
    assert lines[1].startswith(f"wheelstep: error: {profile}:3: gears.thickness = -1"), lines
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("text", ["yes", "No", "on", "OFF"])
def test_a_yaml_1_1_truth_word_is_text_refused_by_a_flag_field(cli, tmp_path, text):
    """YAML 1.1 reads yes / no / on / off as true / false (`lighten: yes` built lightened
    gears), YAML 1.2 as text, as it reads 010 or 1:30: kept as the text written, a true/false
    field refuses it at its line; true and false themselves are read as ever."""
    from wheelstep_cli.config.located_yaml import parse_located_yaml

    profile = tmp_path / "p.yaml"
    profile.write_text(f"gears:\n  teeth: paper\n  lighten: {text}\n")
    line = error_line(cli("gears", "--profile", profile, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {profile}:3: gears.lighten = '{text}': must be true or false", line
    assert not (tmp_path / "out").exists()
    assert parse_located_yaml(f"a: {text}\nb: true\nc: False\n{text}: 1\n", "t.yaml").data == {
        "a": text, "b": True, "c": False, text: 1}     # as a key too (it was the key True)


def test_a_yaml_name_with_an_underscore_stays_the_text_written():
    from wheelstep_cli.config.located_yaml import parse_located_yaml

    assert parse_located_yaml("name: 2024_01\nat: 12:30\nz: 48\n", "t.yaml").data == {
        "name": "2024_01", "at": "12:30", "z": 48}
    assert parse_located_yaml("id: 007\nz: -48\nn: +2\nzero: 0\nt: 10.0\n", "t.yaml").data == {
        "id": "007", "z": -48, "n": 2, "zero": 0, "t": 10.0}


@pytest.mark.parametrize("args, line", [
    (["shoe", "--out", ""], "--out = '': must not be empty"),
    (["shoe", "-o", "  "], "-o = '  ': must not be only spaces"),
    (["shoe", "--out="], "--out = '': must not be empty"),
    (["shoe", "--profile", ""], "--profile = '': must not be empty"),
    (["trajectory", "--csv", ""], "--csv = '': must not be empty"),
])
def test_an_empty_value_is_refused_not_read_as_the_current_folder(cli, tmp_path, monkeypatch, args, line):
    """A path option reads '' as '.': the files would land in the current folder."""
    monkeypatch.chdir(tmp_path)
    assert error_line(cli(*args)) == f"wheelstep: error: {line}"
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("args, line", [
    (["kinematics", "--plot", "speed.jpg"], "--plot = speed.jpg: must end in .png"),
    (["stairs", "--plot", "stairs.svg"], "--plot = stairs.svg: must end in .png"),
    (["trajectory", "--dxf", "path.txt"], "--dxf = path.txt: must end in .dxf"),
    (["trajectory", "--csv", "path.png"], "--csv = path.png: must end in .csv"),
    (["linkage", "--gif", "walk.png"], "--gif = walk.png: must end in .gif"),
    (["linkage", "--plot", "walk.gif"], "--plot = walk.gif: must end in .png"),
])
def test_a_file_named_for_another_format_is_refused(cli, tmp_path, monkeypatch, args, line):
    """These files are written in one format whatever their name: a .svg holding PNG bytes,
    or two options at one path overwriting each other, would mislead."""
    monkeypatch.chdir(tmp_path)
    assert error_line(cli(*args)) == f"wheelstep: error: {line} (the extension sets the format)"
    assert not any(tmp_path.iterdir())


def test_the_extension_is_read_in_any_case(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli("trajectory", "--plot", "path.PNG", "--csv", "path.CSV").exit_code == 0
    assert (tmp_path / "path.PNG").read_bytes().startswith(b"\x89PNG")
    assert (tmp_path / "path.CSV").read_text().splitlines()[0].startswith("x")


@pytest.mark.parametrize("command", ["pitch", "teeth"])
def test_the_paper_tables_refuse_a_law_csv_profile_and_say_they_leave_its_blend_out(cli, tmp_path, command):
    """pitch and teeth tabulate the paper's sectors of the crank law: a profile whose gears
    follow a law CSV is refused at its line (the crank law's table was printed, the key
    unread); a profile's blend, which smooths only the generated teeth's law, is said to be
    left out (the table is the same as without it)."""
    (tmp_path / "law.csv").write_text("driving_deg,driven_deg\n" + "".join(
        f"{d},{d / 2}\n" for d in range(0, 361, 10)))
    profile = tmp_path / "p.yaml"
    profile.write_text("gears:\n  law_csv: law.csv\n")
    line = error_line(cli(command, "--profile", profile))
    assert line.startswith(f"wheelstep: error: {profile}:2: gears.law_csv = "), line
    assert "replaces the crank law: the paper tables (pitch, teeth) are the crank law's sectors" in line
    profile.write_text("gears:\n  blend: 10\n")
    blended = cli(command, "--profile", profile)
    assert blended.exit_code == 0 and blended.stdout == cli(command).stdout
    assert "the profile's gears.blend = 10 deg smooths the law that generated teeth follow" in blended.stderr
