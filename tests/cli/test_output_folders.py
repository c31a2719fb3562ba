"""Output folders: a rerun removes what the previous run of the same command wrote and this one
does not; a file the command did not write is never removed or overwritten (refused, exit 2,
unless --force); files follow the user's umask."""

from __future__ import annotations

import json
import os
import stat

import pytest

from tests.helpers.clicheck import error_line
from tests.helpers.files import write

SHOE = "parts:\n  - kind: shoe\n    design: desk-demo\n    printer: fdm-0.4-pla\n"


def listing(folder) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_gears_stl_after_both_leaves_no_gears_3mf(cli, tmp_path):
    out = tmp_path / "out"
    assert cli("gears", "--profile", "desk-demo", "--out", out, "-q").exit_code == 0
    assert (out / "gears.3mf").exists()
    assert cli("gears", "--profile", "desk-demo", "--format", "stl", "--out", out, "-q").exit_code == 0
    assert sorted(p.name for p in out.iterdir()) == [".wheelstep-gears.json", "gears.json", "pinion.stl",
                                                     "wheel.stl"]


def test_a_rerun_keeps_another_commands_files_and_files_changed_since(cli, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    assert cli("shoe", "--out", out, "-q").exit_code == 0
    (out / "shoe.3mf").write_bytes(b"edited by the user")
    rerun = cli("shoe", "--format", "stl", "--out", out)
    assert rerun.exit_code == 0, rerun.stderr
    assert (out / "shoe.3mf").read_bytes() == b"edited by the user"   # changed since: not ours
    # and said so (it was kept without a word)
    assert f"kept {out / 'shoe.3mf'} (an earlier run wrote it; changed since, so it is not removed)" in (
        rerun.stdout.splitlines())
    assert (out / "notes.txt").read_text() == "mine"
    # the last run's record does not list a file it kept: said so, not "not written by this command"
    assert "was not written by this command's last run here" in error_line(cli("shoe", "--format", "3mf", "--out", out))
    # the line's remedy, for a script (it was {})
    refused = json.loads(cli("shoe", "--format", "3mf", "--out", out, "--json").stdout)["error"]
    assert refused["remedy"] == {"--force": True} and refused["remedies"] == [{"--force": True}], refused
    (out / "shoe.stl").write_bytes(b"edited too")
    assert "shoe.stl there exists and was changed since this command wrote it" in error_line(
        cli("shoe", "--format", "stl", "--out", out))
    assert (out / "shoe.stl").read_bytes() == b"edited too"


def test_a_file_kept_as_changed_since_is_in_the_json_report(cli, tmp_path):
    out = tmp_path / "out"
    assert cli("shoe", "--out", out, "-q").exit_code == 0
    (out / "shoe.stl").write_bytes(b"edited")
    dry = json.loads(cli("shoe", "--format", "3mf", "--out", out, "--json", "--dry-run").stdout)
    assert dry["would_keep"] == [str(out / "shoe.stl")] and "kept" not in dry, dry
    report = json.loads(cli("shoe", "--format", "3mf", "--out", out, "--json").stdout)
    assert report["kept"] == [str(out / "shoe.stl")] and "would_keep" not in report, report
    assert (out / "shoe.stl").read_bytes() == b"edited"


def test_a_users_file_of_the_same_name_is_refused_and_nothing_is_written(cli, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "shoe.stl").write_text("my own shoe")
    line = error_line(cli("shoe", "--out", out))
    # the folder as given, with the file in it
    assert line == (f"wheelstep: error: --out = {out}: shoe.stl there exists and was not written by this "
                    "command: it is kept; move it away or give --force to overwrite it")
    assert listing(out) == {"shoe.stl": b"my own shoe"}
    assert cli("shoe", "--out", out, "--force", "-q").exit_code == 0
    assert (out / "shoe.stl").read_bytes() != b"my own shoe" and (out / "shoe.3mf").exists()


def test_batch_keeps_a_file_a_forged_manifest_lists(cli, tmp_path):
    """Issue 16: a manifest.json listing other files must not make batch delete them."""
    batch = write(tmp_path / "shoe1.yaml", SHOE)
    out = tmp_path / "fm"
    out.mkdir()
    (out / "notes.txt").write_text("x\n")
    (out / "manifest.json").write_text('{"outputs":{"notes.txt":"x"}}\n')
    assert "fm: manifest.json there exists and was not written by this command" in error_line(
        cli("batch", batch, "--out", out, "--jobs", "1"))
    assert listing(out) == {"notes.txt": b"x\n", "manifest.json": b'{"outputs":{"notes.txt":"x"}}\n'}
    assert cli("batch", batch, "--out", out, "--jobs", "1", "--force", "-q").exit_code == 0
    assert (out / "notes.txt").read_text() == "x\n"
    manifest = json.loads((out / "manifest.json").read_text())
    assert "notes.txt" not in manifest["outputs"]


def test_files_of_every_writing_command_follow_the_umask(cli, tmp_path):
    old = os.umask(0o022)
    try:
        assert cli("shoe", "--out", tmp_path / "shoe", "-q").exit_code == 0
        assert cli("batch", write(tmp_path / "b.yaml", SHOE), "--out", tmp_path / "batch", "-q",
                   "--jobs", "1").exit_code == 0
        assert cli("kinematics", "--plot", tmp_path / "k.png", "-q").exit_code == 0
        assert cli("trajectory", "--plot", tmp_path / "t.png", "-q").exit_code == 0
    finally:
        os.umask(old)
    files = [p for p in tmp_path.rglob("*") if p.is_file() and p.suffix != ".yaml"]
    assert len(files) >= 12
    assert {p.name: stat.S_IMODE(p.stat().st_mode) for p in files} == {p.name: 0o644 for p in files}


@pytest.mark.parametrize("name", ["plate-1.png", "print-sheet.md", "reports/shoe-1.json"])
def test_batch_refuses_a_file_changed_since_at_a_certain_name_before_it_builds(cli, tmp_path, monkeypatch,
                                                                              name):
    import wheelstep_cli.batch.run as run

    batch = write(tmp_path / "shoe1.yaml", SHOE)
    out = tmp_path / "out"
    assert cli("batch", batch, "--out", out, "--jobs", "1", "-q").exit_code == 0
    (out / name).write_text("edited by the user")
    before = listing(out)
    monkeypatch.setattr(run, "build_entry", _no_build)
    line = error_line(cli("batch", batch, "--out", out, "--jobs", "1"))
    assert line.endswith(f"{out}: {name} there exists and was changed since this command wrote it: it is kept; "
                         "move it away or give --force to overwrite it"), line
    assert listing(out) == before


def test_batch_dry_run_refuses_what_the_run_would_refuse(cli, tmp_path):
    batch = write(tmp_path / "shoe1.yaml", SHOE)
    out = tmp_path / "out"
    out.mkdir()
    (out / "plate-1.png").write_text("my picture")
    line = error_line(cli("batch", batch, "--out", out, "--jobs", "1", "--dry-run", "-q"))
    assert "plate-1.png there exists and was not written by this command" in line
    assert listing(out) == {"plate-1.png": b"my picture"}


@pytest.mark.parametrize("command, option, name", [
    ("kinematics", "--plot", "k.png"), ("stairs", "--plot", "s.png"), ("linkage", "--csv", "l.csv"),
    ("linkage", "--gif", "l.gif"), ("trajectory", "--csv", "t.csv"), ("trajectory", "--dxf", "t.dxf"),
    ("trajectory", "--plot", "t.png")])
def test_mechanism_outputs_keep_a_users_file_of_the_same_name(cli, tmp_path, command, option, name):
    mine, fresh = tmp_path / name, tmp_path / "fresh.png"
    mine.write_bytes(b"the user's file")
    extra = [] if command == "stairs" or option == "--plot" else ["--plot", fresh]
    line = error_line(cli(command, option, mine, *extra))
    assert line.startswith(f"wheelstep: error: {option} = {mine}: exists and was not written"), line
    assert listing(tmp_path) == {name: b"the user's file"}          # all or nothing
    assert cli(command, option, mine, *extra, "-q", "--force").exit_code == 0
    assert mine.read_bytes() != b"the user's file"
    again = listing(tmp_path)
    assert cli(command, option, mine, *extra, "-q").exit_code == 0   # its own file: replaced
    assert listing(tmp_path) == again                                  # byte-identical rerun


def _no_build(*args, **kwargs):
    raise AssertionError("the pair was built before the outputs' names were checked")


@pytest.mark.parametrize("args, mine", [
    (["--format", "stl"], "pinion.stl"), (["--format", "3mf"], "gears.json"),
    (["--format", "3mf", "--dxf"], "wheel.dxf"), (["--format", "3mf", "--svg"], "pinion.svg")])
def test_gears_refuses_a_users_file_of_a_certain_name_before_it_builds(cli, tmp_path, monkeypatch, args, mine):
    import wheelstep_cli.cli.commands.gears_checks as gears_checks

    out = tmp_path / "out"
    out.mkdir()
    (out / mine).write_bytes(b"the user's file")
    monkeypatch.setattr(gears_checks, "checked_pair", _no_build)
    line = error_line(cli("gears", "--profile", "desk-demo", *args, "--out", out))
    assert line.startswith(f"wheelstep: error: --out = {out}: {mine} there exists and was not written"), line
    assert listing(out) == {mine: b"the user's file"}
    (tmp_path / "afile").write_bytes(b"")
    line = error_line(cli("gears", "--profile", "desk-demo", *args, "--out", tmp_path / "afile"))
    assert line == f"wheelstep: error: --out = {tmp_path / 'afile'}: cannot be written (is a file, not a folder)"


@pytest.mark.parametrize("picture, gear", [("pinion.svg", "pinion"), ("sub/../wheel.svg", "wheel")])
def test_gears_refuses_a_picture_where_its_own_export_goes_before_it_builds(cli, tmp_path, monkeypatch,
                                                                          picture, gear):
    """--plot OUT/pinion.svg with --svg: the picture and the export would share one path."""
    import wheelstep_cli.cli.commands.gears_checks as gears_checks

    monkeypatch.setattr(gears_checks, "checked_pair", _no_build)
    out = tmp_path / "out"
    line = error_line(cli("gears", "--profile", "desk-demo", "--svg", "--out", out, "--plot", out / picture))
    assert line == (f"wheelstep: error: --plot = {out / picture}: is where this run writes the {gear}'s "
                    "SVG (--svg): give the picture another name")
    assert not out.exists()


@pytest.mark.parametrize("option, name, magic", [("--plot", "mine.png", b"\x89PNG"),
                                                 ("--gif", "mine.gif", None)])
def test_gears_pictures_keep_a_users_file_of_the_same_name(cli, tmp_path, monkeypatch, option, name, magic):
    """`gears --plot` / `--gif` write where the user names them: a file there that gears did
    not write is refused before the pair is built (so nothing is written), and replaced with
    --force."""
    import wheelstep_cli.cli.commands.gears_checks as gears_checks

    mine, out = tmp_path / name, tmp_path / "out"
    mine.write_bytes(b"the user's file")
    args = ("gears", "--profile", "desk-demo", "--format", "stl", option, mine, "--out", out, "-q")
    with monkeypatch.context() as patch:
        patch.setattr(gears_checks, "checked_pair", _no_build)
        line = error_line(cli(*args))
    assert line.startswith(f"wheelstep: error: {option} = {mine}: exists and was not written"), line
    assert listing(tmp_path) == {name: b"the user's file"}      # all or nothing
    if option == "--gif":
        return      # drawing the animation takes half a minute; the --plot case writes over it
    assert cli(*args, "--force").exit_code == 0
    assert mine.read_bytes().startswith(magic) and (out / "pinion.stl").exists()


def test_a_gears_picture_in_the_output_folder_survives_a_run_without_it(cli, tmp_path):
    """The pictures keep their own record: a later run that draws none does not take them for
    its own stale files."""
    out = tmp_path / "out"
    args = ("gears", "--profile", "desk-demo", "--format", "stl", "--out", out, "-q")
    assert cli(*args, "--plot", out / "p.png").exit_code == 0
    picture = (out / "p.png").read_bytes()
    assert cli(*args).exit_code == 0
    assert (out / "p.png").read_bytes() == picture


def test_a_dry_run_names_the_files_the_run_would_remove(cli, tmp_path):
    """A dry run says all the real run would do to the folder: the files of the earlier run it
    would remove as well as those it would write; and it removes none."""
    out = tmp_path / "shoe"
    assert cli("shoe", "--out", out, "--format", "both", "-q").exit_code == 0
    said = cli("shoe", "--out", out, "--format", "stl", "--dry-run")
    assert said.exit_code == 0
    assert f"would remove {out / 'shoe.3mf'} (written by an earlier run)" in said.stdout.splitlines()
    assert (out / "shoe.3mf").exists()
    # --json says the same in the report (a script cannot read the lines, which go to stderr)
    report = json.loads(cli("shoe", "--out", out, "--format", "stl", "--dry-run", "--json").stdout)
    assert report["would_remove"] == [str(out / "shoe.3mf")] and report["written"] == []
    assert str(out / "shoe.stl") in report["would_write"]
    assert "would remove" not in cli("shoe", "--out", out, "--format", "both", "--dry-run").stdout
    # the real run says what it removed, as the dry run said it would
    done = cli("shoe", "--out", out, "--format", "stl")
    assert f"removed {out / 'shoe.3mf'} (written by an earlier run)" in done.stdout.splitlines()
    assert not (out / "shoe.3mf").exists()
    assert cli("shoe", "--out", out, "--format", "both", "-q").exit_code == 0
    two = write(tmp_path / "two.yaml", SHOE + SHOE.split("\n", 1)[1].replace("fdm-0.4-pla", "resin-0.05-standard")
                .replace("- kind", "- name: resin\n    kind"))
    folder = tmp_path / "batch"
    assert cli("batch", two, "--out", folder, "--jobs", "1", "-q").exit_code == 0
    assert (folder / "plate-2.3mf").exists()
    one = write(tmp_path / "one.yaml", SHOE)
    before = listing(folder)
    said = cli("batch", one, "--out", folder, "--jobs", "1", "--dry-run")
    assert said.exit_code == 0, said.stderr
    # a dry run says what it would build, not that it built it
    assert said.stdout.startswith(f"would build 1 of 1 entry: 1 part on 1 plate in {folder}\n"), said.stdout
    removed = sorted(line for line in said.stdout.splitlines() if line.startswith("would remove"))
    # the second printer's plate, picture, slicer settings and the dropped entry's report
    gone = ("plate-2.3mf", "plate-2.png", "reports/resin.json", "resin-0.05-standard.ini")
    assert removed == sorted(f"would remove {folder / name} (written by an earlier run)" for name in gone)
    assert listing(folder) == before
    done = cli("batch", one, "--out", folder, "--jobs", "1", "--json")
    assert done.exit_code == 0, done.stderr
    assert not any((folder / name).exists() for name in gone)
    # the real run says what it removed too (in its report with --json)
    assert sorted(json.loads(done.stdout)["removed"]) == sorted(str(folder / name) for name in gone)
    # one entry, one part, one plate: each noun in its number (the sheet said "1 parts")
    assert "\n1 of 1 entry built, 1 part on 1 plate.\n" in (folder / "print-sheet.md").read_text()
