"""`wheelstep batch` runs the meshing check of `wheelstep gears` on every gear pair it builds,
on the meshes as written, and refuses an interfering pair like any failing entry."""

from __future__ import annotations

import json
import re
from pathlib import Path

from tests.helpers.files import SMALL_BATCH, line_of, write

PAPER = """\
  - name: paper
    kind: gear-pair
    design: desk-demo
    printer: fdm-0.4-pla
    overrides:
      teeth: paper
      z: 24
"""


def test_paper_teeth_entry_is_refused_with_its_line_the_good_entries_are_written(cli, tmp_path):
    batch = write(tmp_path / "paper.yaml", SMALL_BATCH + PAPER)
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1")
    assert result.exit_code == 1
    line = line_of(batch, "teeth: paper")
    assert f"paper ({batch}:{line}): teeth = paper: the teeth interfere at " in result.stderr
    assert "allow_interference: true builds it anyway" in result.stderr
    assert sorted(p.name for p in (out / "reports").iterdir()) == ["pair.json", "shoes.json"]
    report = json.loads((out / "reports" / "pair.json").read_text())
    assert report["meshing"]["interference"] is False and report["meshing"]["samples"] == 1536
    assert report["meshing"] == report["design_report"]["meshing"]
    # a shoe's strut and sole radius, one given, the other resolved: both stated, as its design
    # report states them (r_min was null where the preset gives c)
    shoes = json.loads((out / "reports" / "shoes.json").read_text())
    for key in ("parameters", "printed_parameters"):
        assert (shoes[key]["c"], shoes[key]["r_min"]) == (180, 10), shoes[key]
        assert shoes[key]["r_min"] == shoes["design_report"][key]["r_min"]
    manifest = json.loads((out / "manifest.json").read_text())
    entries = {e["name"]: e for e in manifest["entries"]}
    assert entries["pair"]["meshing"]["interference"] is False
    assert entries["paper"]["status"] == "failed" and entries["paper"]["meshing"]["interference"] is True
    assert manifest["failed"][0]["where"] == f"paper.yaml:{line}"
    assert manifest["checks"]["gear_pairs_without_interference"] is True
    sheet = (out / "print-sheet.md").read_text()
    assert "## Gear meshing" in sheet and "| pair | 72.125 | none (1536 poses) |" in sheet
    assert "| paper |" in sheet.split("## Parts")[0]  # under "Not built" only


def test_allow_interference_builds_the_paper_pair_and_reports_the_interference(cli, tmp_path):
    batch = write(tmp_path / "paper.yaml", PAPER.replace("  - name", "parts:\n  - name", 1)
                  + "    allow_interference: true\n")
    out = tmp_path / "out"
    assert cli("batch", batch, "--out", out, "--jobs", "1").exit_code == 0
    report = json.loads((out / "reports" / "paper.json").read_text())
    assert report["meshing"]["interference"] is True and report["meshing"]["interfering_poses"] > 0
    assert json.loads((out / "manifest.json").read_text())["checks"]["gear_pairs_without_interference"] is False
    assert "(allowed)" in (out / "print-sheet.md").read_text()


def test_allow_interference_is_refused_on_an_entry_without_teeth(cli, tmp_path):
    batch = write(tmp_path / "shoe.yaml", "parts:\n  - kind: shoe\n    printer: fdm-0.4-pla\n"
                                          "    allow_interference: true\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert (f"{batch}:{line_of(batch, 'allow_interference')}: parts[0].allow_interference = true: "
            "only gear-pair entries have teeth to check, not shoe") in result.stderr
    assert not (tmp_path / "out").exists()


SOURCE_Z24 = """\
  - name: source24
    kind: gear-pair
    printer: fdm-0.4-pla
    overrides:
      z: 24
      thickness: 2
"""


def test_pair_outside_the_bounds_is_refused_like_gears_with_its_remedy(cli, tmp_path):
    """The source design at z 24, which `gears` refuses by the SPEC §10 bounds with a remedy,
    fails alone in a batch with the same reason and remedy (as override keys): named with its
    line, no report or plate of it, exit 1; the other entries are written."""
    alone = cli("gears", "--z", "24", "--thickness", "2", "--printer", "fdm-0.4-pla", "--dry-run")
    assert alone.exit_code == 2
    found = re.search(r"the pair would mesh outside the bounds \((.*)\); nothing written; "
                      r"use (--z \d+(?: --backlash [\d.]+)?)$", alone.stderr.strip())
    reason, remedy = found.groups()
    flags = remedy.split()
    keys = ", ".join(f"{flag[2:]}: {value}" for flag, value in zip(flags[::2], flags[1::2]))
    batch = write(tmp_path / "b.yaml", SMALL_BATCH + SOURCE_Z24)
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1", "--json")
    assert result.exit_code == 1
    line = line_of(batch, "z: 24")
    # --json gives the remedy as data too: the entry's keys and values the line says
    (failed,) = json.loads(result.stdout)["failed"]
    assert failed["remedies"] == [{flag[2:]: float(value) for flag, value in zip(flags[::2], flags[1::2])}]
    assert f"source24 ({batch}:{line}): z = 24: the pair would mesh outside the bounds ({reason})" \
        in result.stderr
    # the entry is not built; the file's other entries are written
    assert f"({reason}); not built; use overrides {{{keys}}}" in result.stderr
    assert sorted(p.name for p in (out / "reports").iterdir()) == ["pair.json", "shoes.json"]
    manifest = json.loads((out / "manifest.json").read_text())
    entries = {e["name"]: e for e in manifest["entries"]}
    assert entries["source24"]["status"] == "failed"
    assert entries["source24"]["meshing"]["interference"] is False
    assert [f["name"] for f in manifest["failed"]] == ["source24"]
    # the manifest keeps the remedy as --json gives it
    assert manifest["failed"][0]["remedies"] == failed["remedies"]
    assert "| source24 |" in (out / "print-sheet.md").read_text().split("## Parts")[0]


def test_an_entry_mounted_so_close_that_it_interferes_names_its_distance_and_the_remedy(cli, tmp_path):
    """An interfering pair mounted inside its rolling distance is refused for that distance, with
    the remedy as the entry's override keys (as `wheelstep gears` names --install-distance)."""
    batch = write(tmp_path / "close.yaml", "parts:\n  - name: close\n    kind: gear-pair\n"
                  "    design: desk-demo\n    printer: fdm-0.4-pla\n    overrides:\n"
                  "      center_distance: 72.4\n")
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1")
    assert result.exit_code == 1
    assert f"close ({batch}:" in result.stderr
    # named for the override given, the installed distance it leaves the pair at stated
    assert "center_distance = 72.4: with it, install-distance = 72.125 fails: the teeth interfere at " \
        in result.stderr
    assert "use overrides {install_distance: 72.4} (for more play, more backlash)" in result.stderr
    # no entry built: nothing is written, not even a manifest of the failure
    assert "built none of 1 entry: nothing written to" in result.stdout
    assert not out.exists()


def test_an_entry_mounted_closer_than_its_tip_clearance_is_refused_before_its_teeth_are_cut(cli, tmp_path):
    """Mounted far inside its rolling distance (the desk preset's 72.125 mm against 80), an
    entry is refused from its tip clearance, as `wheelstep gears` refuses it, with the
    distance they roll at as its remedy, as data too; applied, the entry is built."""
    text = ("parts:\n  - name: close\n    kind: gear-pair\n    design: desk-demo\n"
            "    printer: fdm-0.4-pla\n    overrides:\n      center_distance: 80\n")
    result = cli("batch", write(tmp_path / "close.yaml", text), "--out", tmp_path / "out", "--jobs", "1",
                 "--json", "--no-tolerance")
    assert result.exit_code == 1, result.stderr
    (failed,) = json.loads(result.stdout)["failed"]
    assert failed["reason"].startswith("center_distance = 80: with it, install-distance = 72.125 fails: mounted "
                                       "7.875 mm closer than the pitch curves roll (80 mm), more than the tip "
                                       "clearance"), failed["reason"]
    assert failed["reason"].endswith("; not built; use overrides {install_distance: 80}")
    assert failed["remedies"] == [{"install_distance": 80.0}]
    applied = cli("batch", write(tmp_path / "rolling.yaml", text + "      install_distance: 80\n"),
                  "--out", tmp_path / "rolling", "--jobs", "1", "--no-tolerance")
    assert applied.exit_code == 0, applied.stderr


def test_a_batch_whose_every_entry_fails_leaves_an_earlier_batch_in_its_folder(cli, tmp_path):
    out = tmp_path / "out"
    assert cli("batch", write(tmp_path / "good.yaml", SMALL_BATCH), "--out", out, "--jobs", "1",
               "--no-tolerance").exit_code == 0
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    bad = write(tmp_path / "bad.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                "    printer: fdm-0.4-pla\n    overrides:\n      hub_d: 90\n")
    result = cli("batch", bad, "--out", out, "--jobs", "1")
    assert result.exit_code == 1, result.stderr
    assert "pair (" in result.stderr and "hub_d = 90" in result.stderr
    assert f"nothing written to {out} (the earlier batch's files there are kept)" in result.stdout
    dry = cli("batch", bad, "--out", out, "--jobs", "1", "--dry-run")
    assert dry.exit_code == 1 and "would remove" not in dry.stdout + dry.stderr, dry.stdout + dry.stderr
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before


def test_an_undercut_entry_is_offered_only_a_remedy_a_build_for_its_printer_passed(cli, tmp_path):
    """z 12 undercuts the source design's pinion. The counts that clear the undercut mesh
    outside the bounds or print too thin on the entry's 0.4 mm nozzle, so the entry is
    offered what a build for its printer passed, as override keys; applied, it is built."""
    entry = ("parts:\n  - name: small\n    kind: gear-pair\n    printer: fdm-0.4-pla\n"
             "    overrides:\n      z: 12\n      thickness: 2\n")
    batch = write(tmp_path / "b.yaml", entry)
    result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1")
    assert result.exit_code == 1
    found = re.search(r"small \(.*:6\): z = 12: the rack undercuts the pinion: .*; use overrides \{(.*)\}$",
                      result.stderr.strip(), re.M)
    assert found and "pinion z >=" not in result.stderr, result.stderr
    remedy = dict(pair.split(": ") for pair in found.group(1).split(", "))
    fixed = entry.replace("      z: 12\n", "".join(f"      {k}: {v}\n" for k, v in remedy.items()))
    applied = cli("batch", write(tmp_path / "fixed.yaml", fixed), "--out", tmp_path / "fixed", "--jobs", "1")
    assert applied.exit_code == 0, applied.stderr


def test_no_backlash_on_a_printer_without_clearance_gets_the_play_remedy_that_builds(cli, tmp_path):
    """backlash: 0 drawn for a printer that adds no tooth clearance: rigid teeth with no play
    interfere by micrometres. The entry is refused at its backlash line with the backlash a
    build for that printer found to mesh, as an override key; applied, it is built."""
    printer = write(tmp_path / "exact.yaml", (Path(__file__).resolve().parents[2] / "profiles"
                                              / "fdm-0.4-pla.yaml").read_text().replace(
        "tooth_clearance: 0.15", "tooth_clearance: 0"))
    entry = f"parts:\n  - name: rigid\n    kind: gear-pair\n    printer: {printer}\n    overrides:\n      backlash: 0\n"
    batch = write(tmp_path / "b.yaml", entry)
    result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1")
    assert result.exit_code == 1
    found = re.search(r"rigid \(.*:6\): backlash = 0: the teeth interfere at .* rigid teeth no play; "
                      r".*use overrides \{backlash: ([0-9.]+)\}", result.stderr)
    assert found, result.stderr
    fixed = entry.replace("backlash: 0\n", f"backlash: {found.group(1)}\n")
    applied = cli("batch", write(tmp_path / "fixed.yaml", fixed), "--out", tmp_path / "fixed", "--jobs", "1")
    assert applied.exit_code == 0, applied.stderr


def test_a_pair_no_bed_holds_is_refused_for_its_size_before_its_figures(cli, tmp_path):
    """module 3 draws the desk demo's wheel 260 mm across: refused at the module's line for the
    bed, as `gears` refuses it, before the meshing check (whose figures no remedy on that bed
    could cure)."""
    batch = write(tmp_path / "b.yaml", "parts:\n  - name: big\n    kind: gear-pair\n    design: desk-demo\n"
                  "    printer: fdm-0.4-pla\n    overrides:\n      module: 3\n")
    result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1")
    assert result.exit_code == 1
    assert (f"big ({batch}:{line_of(batch, 'module: 3')}): module = 3: with it, part 'wheel' is "
            in result.stderr), result.stderr
    assert "larger than the bed of printer 'fdm-0.4-pla'" in result.stderr and "bounds" not in result.stderr


def test_a_pair_too_large_for_its_bed_is_offered_the_pair_drawn_smaller_that_the_bed_holds(cli, tmp_path):
    """The source pair (its wheel 208 mm across) on the resin printer's 115 mm deep bed:
    refused for the bed with the same pair at a smaller installed distance as the entry's
    override; applied, that entry is written on one plate."""
    entry = ("parts:\n  - name: big\n    kind: gear-pair\n    design: bntu-2024\n"
             "    printer: resin-0.05-standard\n")
    batch = write(tmp_path / "big.yaml", entry)
    result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1")
    assert result.exit_code == 1
    assert "does not fit the bed of printer 'resin-0.05-standard'" in result.stderr, result.stderr
    found = re.search(r"; not built; use overrides \{install_distance: ([0-9.]+)\} \(the pair drawn at", result.stderr)
    assert found, result.stderr
    fixed = write(tmp_path / "fixed.yaml", entry + f"    overrides: {{install_distance: {found.group(1)}}}\n")
    applied = cli("batch", fixed, "--out", tmp_path / "fixed", "--jobs", "1")
    assert applied.exit_code == 0, applied.stderr
    assert [p.name for p in (tmp_path / "fixed").glob("plate-*.3mf")] == ["plate-1.3mf"]
