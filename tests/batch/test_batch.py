"""`wheelstep batch`: the example builds into strict 3MF plates; failures are isolated and
located; output is deterministic; invalid files are refused with file:line before building."""

from __future__ import annotations

import hashlib
import json
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from tests.helpers.clicheck import error_line
from tests.helpers.files import SMALL_BATCH as SMALL, line_of, write
from tests.helpers.meshcheck import read_3mf_strict
from wheelstep_cli.geometry.planar import tooth_heights_lost

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "shop-floor.yaml"


def object_metadata(path: Path) -> dict[str, dict[str, str]]:
    """Object name -> its metadata, read straight from the 3MF XML."""
    import xml.etree.ElementTree as ET

    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    with zipfile.ZipFile(path) as zf:
        root = ET.fromstring(zf.read("3D/3dmodel.model"))
    return {obj.get("name"): {m.get("name"): m.text for m in obj.iter(f"{{{ns['m']}}}metadata")}
            for obj in root.iter(f"{{{ns['m']}}}object")}


def placed_meshes(path: Path) -> dict[str, np.ndarray]:
    """Object name -> its vertices placed on the bed (build item transform applied), via lib3mf."""
    import lib3mf

    model = lib3mf.get_wrapper().CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(path))
    placed = {}
    items = model.GetBuildItems()
    while items.MoveNext():
        item = items.GetCurrent()
        obj = item.GetObjectResource()
        mesh = model.GetMeshObjectByID(obj.GetResourceID())
        vertices = np.array([v.Coordinates[0:3] for v in mesh.GetVertices()])
        fields = np.array([list(row) for row in item.GetObjectTransform().Fields])  # 4 x 3
        placed[mesh.GetName()] = vertices @ fields[:3] + fields[3]
    return placed


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    out = tmp_path_factory.mktemp("example")
    from wheelstep_cli.cli import run

    assert run(["batch", str(EXAMPLE), "--out", str(out), "--jobs", "1"]) == 0
    return out


def test_example_builds_every_part_times_quantity_on_strict_3mf_plates(example):
    import yaml

    batch = yaml.safe_load(EXAMPLE.read_text())
    parts_per_kind = {"gear-pair": 2, "shoe": 1}
    expected = sum(parts_per_kind[e["kind"]] * e.get("quantity", 1) for e in batch["parts"])
    plates = sorted(example.glob("plate-*.3mf"))
    assert plates and [p.name for p in plates] == [f"plate-{i}.3mf" for i in range(1, len(plates) + 1)]
    names = []
    for plate in plates:
        info = read_3mf_strict(plate)
        assert info["warnings"] == [], plate
        assert info["unit"] is not None and info["build_items"] == len(info["objects"])
        assert all(v > 0 for v in info["objects"].values())
        names += list(info["objects"])
        assert (example / plate.with_suffix(".png").name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(names) == expected and len(set(names)) == expected
    for entry in batch["parts"]:
        assert sum(n.startswith(entry["name"] + " ") for n in names) == \
            parts_per_kind[entry["kind"]] * entry.get("quantity", 1)


def test_plates_fit_their_bed_without_overlap(example):
    """Independent check of the packing: every mesh inside its bed, footprints disjoint."""
    import shapely

    manifest = json.loads((example / "manifest.json").read_text())
    beds = {"fdm-0.4-pla": (256, 256), "fdm-0.4-petg": (256, 256)}
    for plate in manifest["plates"]:
        bed = beds[plate["printer_profile"]]
        boxes = []
        for vertices in placed_meshes(example / plate["file"]).values():
            lo, hi = vertices.min(axis=0), vertices.max(axis=0)
            assert lo[0] >= 0 and lo[1] >= 0 and hi[0] <= bed[0] and hi[1] <= bed[1]
            assert lo[2] == pytest.approx(0.0, abs=1e-6)
            boxes.append(shapely.box(lo[0], lo[1], hi[0], hi[1]))
        for i in range(len(boxes)):
            for j in range(i + 1, len(boxes)):
                assert boxes[i].intersection(boxes[j]).area == pytest.approx(0.0, abs=1e-6)


def test_manifest_hashes_inputs_and_every_output(example):
    manifest = json.loads((example / "manifest.json").read_text())
    files = sorted(p.relative_to(example).as_posix() for p in example.rglob("*") if p.is_file())
    assert sorted(manifest["outputs"]) == [f for f in files if f != "manifest.json"]
    for name, digest in manifest["outputs"].items():
        assert hashlib.sha256((example / name).read_bytes()).hexdigest() == digest
    assert manifest["inputs"]["batch"] == {
        "file": "shop-floor.yaml", "sha256": hashlib.sha256(EXAMPLE.read_bytes()).hexdigest()}
    assert set(manifest["inputs"]["printer_profiles"]) == {"fdm-0.4-pla", "fdm-0.4-petg"}
    assert set(manifest["inputs"]["design_profiles"]) == {"bntu-2024", "desk-demo"}
    assert manifest["checks"]["meshes_printable"] is True
    assert manifest["versions"]["manifold3d"] and manifest["versions"]["numpy"]
    text = (example / "manifest.json").read_text()
    assert str(example) not in text and "/tmp" not in text
    assert not re.search(r"\d{4}-\d{2}-\d{2}[T ]\d{2}:\d{2}", text)  # no timestamps


def test_printer_compensation_is_in_the_geometry_and_metadata(example):
    """PETG: bores +0.25 mm, backlash +0.2 mm; written into the parts and the 3MF metadata."""
    report = json.loads((example / "reports" / "bntu-gears.json").read_text())
    assert report["parameters"]["bore"] == 8
    assert report["printed_parameters"]["bore"] == pytest.approx(8.25)
    # the default backlash of generated teeth already holds the printer's tooth clearance
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.gear_laws import design_backlash

    assert report["printed_parameters"]["backlash"] == pytest.approx(
        max(design_backlash(gear_pair_spec("bntu-2024")), 0.2))
    shoes = json.loads((example / "reports" / "bntu-shoes.json").read_text())
    assert shoes["printed_parameters"]["strut_diameter"] == pytest.approx(12.25)
    manifest = json.loads((example / "manifest.json").read_text())
    plate = next(p for p in manifest["plates"] if "bntu-gears pinion" in p["parts"])
    meta = object_metadata(example / plate["file"])["bntu-gears pinion"]
    assert meta["wheelstep:bore"] == "8.25" and meta["wheelstep:part"] == "pinion"
    assert meta["wheelstep:z"] == "48" and meta["wheelstep:pair"] == "bntu-gears/1"
    assert meta["wheelstep:printer_profile"] == "fdm-0.4-petg"
    sheet = (example / "print-sheet.md").read_text()
    for needle in ("bntu-gears", "demo-shoes", "| 8 |", "plate-1.png", "fill_density", "g/cm3"):
        assert needle in sheet
    # the gears' face chamfer replaces the elephant-foot inset the shoes get
    petg = sheet.split("### fdm-0.4-petg", 1)[1].split("###", 1)[0]
    assert ("gear faces chamfered 0.5 mm at 45 deg, which takes the place of the elephant-foot inset; "
            "other parts' bed-side edges inset 0.25 mm over the lowest 0.2 mm (elephant foot)") in petg


def test_elephant_foot_inset_in_the_written_mesh(example):
    """The lowest 0.2 mm of a PLA part is 0.2 mm smaller on every side than the rest."""
    manifest = json.loads((example / "manifest.json").read_text())
    plate = next(p for p in manifest["plates"] if "demo-shoes shoe #1" in p["parts"])
    vertices = placed_meshes(example / plate["file"])["demo-shoes shoe #1"]
    z = vertices[:, 2]
    bottom = vertices[np.isclose(z, 0.0, atol=1e-4)]
    upper = vertices[z > 0.25]
    assert bottom[:, 0].min() == pytest.approx(upper[:, 0].min() + 0.2, abs=2e-3)
    assert bottom[:, 0].max() == pytest.approx(upper[:, 0].max() - 0.2, abs=2e-3)


GOOD_BAD_GOOD = """\
# two good parts and two that cannot be built
defaults:
  design: desk-demo
  printer: fdm-0.4-pla
parts:
  - name: good-1
    kind: shoe
    overrides: {width: 12}
  - name: bored-out
    kind: gear-pair
    overrides:
      thickness: 2
      bore: 40           # no wall left round the bore: fails while building
  - name: too-big
    kind: gear-pair
    design: bntu-2024
    printer: resin-0.05-standard
    overrides: {thickness: 2}
  - name: good-2
    kind: shoe
    quantity: 2
    overrides: {width: 11}
"""


def test_bad_parts_fail_alone_named_with_their_line(cli, tmp_path):
    batch = write(tmp_path / "mixed.yaml", GOOD_BAD_GOOD)
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1")
    assert result.exit_code == 1
    assert f"bored-out ({batch}:{line_of(batch, 'bore: 40')}): bore = 40 (40.2 as printed): must be <" in result.stderr, result.stderr
    assert f"too-big ({batch}:{line_of(batch, 'name: too-big')})" in result.stderr
    assert "does not fit the bed of printer 'resin-0.05-standard' (218 x 123 mm" in result.stderr
    assert "part 'wheel'" in result.stderr
    names = []
    for plate in sorted(out.glob("plate-*.3mf")):
        assert read_3mf_strict(plate)["warnings"] == []
        names += list(read_3mf_strict(plate)["objects"])
    assert sorted(names) == ["good-1 shoe", "good-2 shoe #1", "good-2 shoe #2"]
    assert sorted(p.name for p in (out / "reports").iterdir()) == ["good-1.json", "good-2.json"]
    assert not [p for p in out.rglob("*") if p.name.endswith(".part") or p.name.startswith(".")]
    manifest = json.loads((out / "manifest.json").read_text())
    assert {f["name"]: f["where"] for f in manifest["failed"]} == {
        "bored-out": f"mixed.yaml:{line_of(batch, 'bore: 40')}",
        "too-big": f"mixed.yaml:{line_of(batch, 'name: too-big')}"}
    assert "## Not built" in (out / "print-sheet.md").read_text()


def test_same_batch_twice_identical_bytes_serial_and_parallel(cli, tmp_path):
    """In-process --jobs 1 and a separate process with --jobs 2 (spawned workers) agree byte for byte."""
    batch = write(tmp_path / "small.yaml", SMALL)
    verbose = cli("batch", batch, "--out", tmp_path / "a", "--jobs", "1", "-v")   # -v changes no file
    assert verbose.exit_code == 0, verbose.stderr
    subprocess.run([sys.executable, "-m", "wheelstep_cli", "batch", str(batch), "--out",
                    str(tmp_path / "b"), "--jobs", "2"], check=True, capture_output=True, cwd=ROOT)
    files_a = sorted(p.relative_to(tmp_path / "a") for p in (tmp_path / "a").rglob("*") if p.is_file())
    files_b = sorted(p.relative_to(tmp_path / "b") for p in (tmp_path / "b").rglob("*") if p.is_file())
    assert files_a == files_b and len(files_a) >= 7
    for name in files_a:
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name
    # -v says what each entry resolved to and every file written
    resolved = [line for line in verbose.stderr.splitlines() if " from desk-demo for printer " in line]
    assert len(resolved) == SMALL.count("kind:") and all(" = " in line for line in resolved), verbose.stderr
    assert {f"  wrote {tmp_path / 'a' / name}" for name in files_a} <= set(verbose.stderr.splitlines())


def test_rerun_into_the_same_folder_removes_stale_plates(cli, tmp_path):
    batch = write(tmp_path / "small.yaml", SMALL)
    out = tmp_path / "out"
    assert cli("batch", batch, "--out", out, "--jobs", "1").exit_code == 0
    assert (out / "plate-2.3mf").exists()
    write(batch, SMALL.replace("printer: resin-0.05-standard", "printer: fdm-0.4-pla"))
    (out / "notes.txt").write_text("mine")
    with open(out / "plate-2.png", "ab") as picture:      # a plate picture the user changed
        picture.write(b"x")
    dry = cli("batch", batch, "--out", out, "--jobs", "1", "--dry-run")
    assert f"would keep {out / 'plate-2.png'} (an earlier run wrote it; changed since, so it is not removed)" in (
        dry.stdout.splitlines()), dry.stdout
    # the dry run's --json says the same as its lines, as gears' and shoe's do
    planned = json.loads(cli("batch", batch, "--out", out, "--jobs", "1", "--dry-run", "--json").stdout)
    assert planned["would_keep"] == [str(out / "plate-2.png")] and planned["written"] == [], planned
    assert str(out / "plate-2.3mf") in planned["would_remove"] and str(out / "manifest.json") in planned["would_write"]
    assert (out / "plate-2.3mf").exists()
    rerun = cli("batch", batch, "--out", out, "--jobs", "1", "--json")
    assert rerun.exit_code == 0, rerun.stderr
    assert not (out / "plate-2.3mf").exists() and (out / "plate-2.png").exists()
    assert (out / "notes.txt").read_text() == "mine"  # not ours: left alone
    report = json.loads(rerun.stdout)
    assert report["kept"] == [str(out / "plate-2.png")] and str(out / "plate-2.3mf") in report["removed"]


VALID_ENTRY = """\
parts:
  - name: pair
    kind: gear-pair
    design: desk-demo
    printer: fdm-0.4-pla
"""


@pytest.mark.parametrize("text, needle, expect", [
    (VALID_ENTRY + "    colour: red\n", "colour", "parts[0].colour: unknown key; allowed: name, kind"),
    (VALID_ENTRY + "    quantitiy: 2\n", "quantitiy", "parts[0].quantitiy: unknown key; did you mean quantity? allowed:"),
    (VALID_ENTRY + "    quantity: two\n", "quantity", "parts[0].quantity = 'two': must be a whole number"),
    (VALID_ENTRY + "    quantity: 0\n", "quantity", "must be between 1 and 200"),
    # 2.0 is 2, as z's 42.0 is 42; a fraction is said as written
    (VALID_ENTRY + "    quantity: 1.5\n", "quantity", "parts[0].quantity = 1.5: must be a whole number"),
    (VALID_ENTRY + "    overrides:\n      zz: 3\n", "zz", "overrides.zz: unknown key; did you mean z? allowed: a, b, c, z"),
    # a fit is the printer's (its band's): said where it goes, not "did you mean fillet?"
    (VALID_ENTRY + "    overrides:\n      fit: auto\n", "fit", "parts[0].overrides.fit: unknown key here; a fit is "
     "the printer's: `fit: auto` (or tight, normal, loose) in the printer profile's `band:` section"),
    (VALID_ENTRY + "    fit: auto\n", "fit", "parts[0].fit: unknown key here; a fit is the printer's"),
    # the printer is the entry's, not an override (was "did you mean corner?")
    (VALID_ENTRY + "    overrides:\n      printer: resin-0.05-standard\n", "printer: resin",
     "parts[0].overrides.printer: unknown key here; a printer is chosen where the parts are made: "
     "`--printer NAME` (a preset or a profile's path), or a batch entry's `printer:` beside its `design:`"),
    (VALID_ENTRY + "    overrides:\n      z: 24.5\n", "z: 24.5", "overrides.z = 24.5: must be a whole number"),
    (VALID_ENTRY + "    overrides:\n      module: fine\n", "module", "must be a number"),
    (VALID_ENTRY + "    overrides:\n      b: 110\n", "b: 110", "b = 110: must be <"),
    (VALID_ENTRY + "    overrides:\n      z: 23\n", "z: 23", "z = 23: must make z*n/4 whole sectors"),
    # taller than the printer prints: refused before anything is built, at its line
    (VALID_ENTRY + "    overrides:\n      thickness: 300\n", "thickness: 300",
     "overrides.thickness = 300: makes part 'pinion' 300.0 mm tall, more than the 250 mm printer"),
    # a strut socket wider than the shoe: refused at the plan, as the value given (not the 100.2
    # the printer's hole compensation would draw)
    (VALID_ENTRY.replace("gear-pair", "shoe") + "    overrides:\n      strut_diameter: 100\n", "strut_diameter",
     "parts[0].overrides.strut_diameter = 100: must be <= 15.79 mm (<= 16.00 mm as printed) (socket wider "
     "than the body"),
    # a shoe stands on its side: its width is its height on the bed
    (VALID_ENTRY.replace("gear-pair", "shoe") + "    overrides:\n      width: 300\n", "width: 300",
     "overrides.width = 300: makes part 'shoe' 300.0 mm tall, more than the 250 mm printer 'fdm-0.4-pla' prints; "
     "nothing written; use width: 250"),
    (VALID_ENTRY.replace("gear-pair", "shoe") + "    overrides:\n      width: -3\n", "width",
     "parts[0].overrides.width = -3: must be > 0 mm"),
    # the R_min rule names the parameter the entry gave (b), not the design's strut c
    (VALID_ENTRY.replace("gear-pair", "shoe") + "    overrides:\n      b: 60\n", "b: 60",
     "parts[0].overrides.b = 60: must be <= (a + c - 0.001)/4 = 52.4997 mm"),
    (VALID_ENTRY.replace("kind: gear-pair", "kind: gears"), "kind", "unknown kind; allowed: gear-pair, shoe"),
    (VALID_ENTRY.replace("printer: fdm-0.4-pla", "printer: fdm-0.6-abs"), "printer",
     "not found; known printer profiles: fdm-0.4-petg, fdm-0.4-pla, resin-0.05-standard"),
    # a design not found lists the designs, not the printers too
    (VALID_ENTRY.replace("design: desk-demo", "design: desk-demos"), "design",
     "= 'desk-demos': not found; known design profiles: bntu-2024, desk-demo"),
    (VALID_ENTRY.replace("printer: fdm-0.4-pla", "printer: desk-demo"), "printer",
     "is a design profile, not a printer profile; printer profiles: fdm-0.4-petg, fdm-0.4-pla"),
    (VALID_ENTRY.replace("design: desk-demo", "design: fdm-0.4-pla"), "design", "is not a design profile"),
    (VALID_ENTRY + "  - name: 'pair'\n    kind: shoe\n    printer: fdm-0.4-pla\n", "'pair'",
     "= 'pair': already used at"),
    # one report file on a case-insensitive file system
    (VALID_ENTRY + "  - name: 'PAIR'\n    kind: shoe\n    printer: fdm-0.4-pla\n", "'PAIR'",
     "bad.yaml:2 as 'pair' (names are compared ignoring case"),
    # a name the file did not give, said as the one the tool gives
    (VALID_ENTRY.replace("name: pair\n    kind", "kind") + "  - name: gear-pair-1\n    kind: shoe\n    printer: fdm-0.4-pla\n",
     "gear-pair-1", "bad.yaml:2, the name that entry without one gets (KIND-N"),
    (VALID_ENTRY + "  - kind: shoe\n    printer: fdm-0.4-pla\n  - name: shoe-2\n    kind: shoe\n    printer: fdm-0.4-pla\n",
     "name: shoe-2", "bad.yaml:6, the name that entry without one gets"),
    (VALID_ENTRY + "  - name: shoe-3\n    kind: shoe\n    printer: fdm-0.4-pla\n  - kind: shoe\n    printer: fdm-0.4-pla\n",
     "- kind: shoe", "bad.yaml:6; give it a `name:`"),
    (VALID_ENTRY + "  - name: '.'\n    kind: shoe\n    printer: fdm-0.4-pla\n", "'.'",
     "starting with a letter or digit"),
    (VALID_ENTRY + "    quantity: 1\n    quantity: 2\n", "quantity: 2", "duplicate key 'quantity'"),
    (VALID_ENTRY + "    quantity: 1: 2\n", "quantity: 1: 2", "is not valid YAML"),
])
def test_invalid_batch_reports_file_line_exit_2_nothing_written(cli, tmp_path, text, needle, expect):
    batch = write(tmp_path / "bad.yaml", text)
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out)
    line = error_line(result)
    assert line.startswith(f"wheelstep: error: {batch}:{line_of(batch, needle)}: "), line
    assert expect in line
    assert not out.exists()


@pytest.mark.parametrize("other, expect", [
    (VALID_ENTRY, "is a batch file, not a printer profile (`wheelstep batch other.yaml` takes it)"),
    ("{}\n", "is not a printer profile (no printer keys: a printer profile has a printer: section)"),
])
def test_a_printer_entry_naming_no_printer_profile_says_what_it_names(cli, tmp_path, other, expect):
    write(tmp_path / "other.yaml", other)
    batch = write(tmp_path / "bad.yaml", VALID_ENTRY.replace("printer: fdm-0.4-pla", "printer: other.yaml"))
    line = error_line(cli("batch", batch, "--out", tmp_path / "out"))
    assert line.startswith(f"wheelstep: error: {batch}:{line_of(batch, 'printer:')}: "
                           f"parts[0].printer = 'other.yaml': {expect}; printer profiles: "), line
    assert not (tmp_path / "out").exists()


def test_all_problems_reported_together(cli, tmp_path):
    """Every problem of the file, each at its line, in the file's line order (they came in the
    validator's field order: line 8 before line 7)."""
    batch = write(tmp_path / "bad.yaml", VALID_ENTRY + "    quantity: -1\n  - kind: shoe\n    colour: 1\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert [re.match(r"wheelstep: error: (.*?:\d+): ", ln).group(1) for ln in lines] == [
        f"{batch}:{line_of(batch, 'quantity: -1')}", f"{batch}:{line_of(batch, '- kind: shoe')}",
        f"{batch}:{line_of(batch, 'colour')}"]
    assert "needs a printer" in lines[1]


def test_every_repeated_key_is_reported_at_once(cli, tmp_path):
    """A file that repeats keys got the first only; fixed, the next came in the next run."""
    batch = write(tmp_path / "twice.yaml", "defaults:\n  printer: fdm-0.4-pla\n  printer: fdm-0.4-petg\n"
                  "parts:\n  - kind: shoe\n    design: desk-demo\n    design: bntu-2024\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert result.stderr.strip().splitlines() == [f"wheelstep: error: {batch}:3: duplicate key 'printer'",
                                                  f"wheelstep: error: {batch}:7: duplicate key 'design'"]
    # and with a value that does not read, after them (they were dropped)
    write(batch, batch.read_text() + "    quantity: !!float abc\n")
    lines = cli("batch", batch, "--out", tmp_path / "out").stderr.strip().splitlines()
    assert [re.match(r"wheelstep: error: .*?:(\d+): ", line).group(1) for line in lines] == ["3", "7", "8"], lines
    # a design profile the batch names that repeats keys: every one too (it said the first)
    design = write(tmp_path / "dup.yaml", "mechanism:\n  a: 30\n  a: 31\ngears:\n  z: 24\n  z: 30\n")
    write(batch, "parts:\n  - kind: shoe\n    design: dup.yaml\n    printer: fdm-0.4-pla\n")
    assert cli("batch", batch, "--out", tmp_path / "out").stderr.strip().splitlines() == [
        f"wheelstep: error: {design}:3: duplicate key 'a'", f"wheelstep: error: {design}:6: duplicate key 'z'"]


def test_every_rule_an_entrys_design_profile_breaks_is_reported_at_once(cli, tmp_path):
    """The design's first rule problem came alone (one run per problem), as in `gears --profile`
    before: now every one, in the design file's line order, each with the line of its key there;
    an override's problem is still the override's alone (its stand-in is the design's value)."""
    write(tmp_path / "rules.yaml", "gears:\n  thickness: 1\n  chamfer: 2\n  mark_depth: 0.8\n  key_width: 2\n"
          "  hub_length: 3\n")
    batch = write(tmp_path / "b.yaml", "parts:\n  - kind: gear-pair\n    design: rules.yaml\n"
                  "    printer: fdm-0.4-pla\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    said = [line.split(": parts[0]: ", 1)[1] for line in result.stderr.strip().splitlines()]
    assert said == ["chamfer = 2: must be < half the thickness 0.5 mm (from design rules.yaml:3)",
                    "mark_depth = 0.8: must be <= half the thickness, 0.5 mm (from design rules.yaml:4)",
                    "key_width = 2: needs bore_shape keyway (from design rules.yaml:5)",
                    "hub_length = 3: needs hub_d (from design rules.yaml:6)"], said
    # a printer's rule of the design's value (its least chamfer) at the key's line too
    write(tmp_path / "rules.yaml", "gears:\n  thickness: 6\n  chamfer: 0.2\n")
    line = error_line(cli("batch", batch, "--out", tmp_path / "out"))
    assert "chamfer = 0.2: must be 0 or >= 0.4 mm on printer fdm-0.4-pla" in line and line.endswith(
        "(from design rules.yaml:3)"), line


def test_an_entrys_override_rules_are_reported_beside_its_other_problems(cli, tmp_path):
    """An entry with a problem of its own (quantity 0) and an override breaking a rule
    (hub_d under the bore's wall): both in one run (the rule was found only once the
    quantity was fixed)."""
    batch = write(tmp_path / "bad.yaml", VALID_ENTRY + "    quantity: 0\n    overrides:\n      hub_d: 4\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert [re.match(r"wheelstep: error: .*?:(\d+): ", ln).group(1) for ln in lines] == [
        str(line_of(batch, "quantity: 0")), str(line_of(batch, "hub_d: 4"))], lines
    assert "parts[0].overrides.hub_d = 4: must be >= " in lines[1], lines


def test_every_override_at_fault_is_reported_at_once_in_the_files_words(cli, tmp_path):
    """The shaft rules stop at the first input at fault; the entry is checked again without it,
    so one run names every override to fix, each at its line, by its key (not its flag)."""
    batch = write(tmp_path / "bad.yaml", VALID_ENTRY + "    overrides:\n      key_angle: 30\n"
                  "      hub_length: 5\n      flat_depth: 1\n      z: 48\n")
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert lines == [
        f"wheelstep: error: {batch}:{line_of(batch, 'key_angle')}: parts[0].overrides.key_angle = 30: orients "
        "a keyed bore or a set screw: needs bore_shape d-flat, keyway or hex, or set_screw",
        f"wheelstep: error: {batch}:{line_of(batch, 'hub_length')}: parts[0].overrides.hub_length = 5: needs hub_d",
        f"wheelstep: error: {batch}:{line_of(batch, 'flat_depth')}: parts[0].overrides.flat_depth = 1: needs "
        "bore_shape d-flat"]
    assert not out.exists()
    # each remedy applied, the entry passes the plan's checks
    fixed = write(tmp_path / "fixed.yaml", VALID_ENTRY + "    overrides:\n      key_angle: 30\n"
                  "      hub_length: 5\n      flat_depth: 1\n      bore_shape: d-flat\n      hub_d: 16\n")
    from wheelstep_cli.batch.plan import load_batch

    (entry,) = load_batch(fixed, str(fixed)).entries
    assert (entry.spec.key_angle, entry.spec.hub_length, entry.spec.flat_depth) == (30, 5, 1)


def _stated_bound(line: str, key: str) -> float:
    """The number a refusal line asks ``key`` to be at least (``... >= 8.22 mm``)."""
    import re

    found = re.search(rf"(?:= \S+: must be|needs {key}) >= (\d+(?:\.\d+)?) mm", line)
    assert found, line
    return float(found.group(1))


@pytest.mark.parametrize("overrides, key", [
    ("      hub_d: 4\n", "hub_d"),
    ("      hub_d: 8\n      set_screw: M4\n", "hub_d"),
])
def test_a_hub_that_cannot_fit_round_the_bore_is_refused_at_the_plan(cli, tmp_path, overrides, key):
    """A hub (or its set screw's nut) too small round the printed bore is refused at its line
    before anything is built (exit 2), with the bound for the bore as printed (the printer
    draws holes larger); that bound applied, the entry passes the plan and builds."""
    from wheelstep_cli.batch.plan import load_batch

    batch = write(tmp_path / "bad.yaml", VALID_ENTRY + "    overrides:\n" + overrides)
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert not (tmp_path / "out").exists()
    bound = max(_stated_bound(line, key) for line in lines)
    fixed = write(tmp_path / "fixed.yaml", VALID_ENTRY + "    overrides:\n" + overrides.replace(
        overrides.split("hub_d: ")[1].split("\n")[0], f"{bound:g}", 1))
    (entry,) = load_batch(fixed, str(fixed)).entries
    assert entry.spec.hub_d == bound
    from wheelstep_cli.parts.kinds import build_for_printer

    pair = build_for_printer("gear-pair", entry.spec, entry.printer)
    assert pair.pinion.bounds[1][2] == pytest.approx(entry.spec.thickness + 8.0, abs=1e-3)   # the hub stands


def test_an_entrys_law_csv_is_found_beside_the_batch_file(tmp_path, monkeypatch):
    from wheelstep_cli.batch.plan import load_batch

    jobs = tmp_path / "jobs"
    jobs.mkdir()
    phi = np.linspace(0.0, 360.0, 37)
    (jobs / "law.csv").write_text("driving_deg,driven_deg\n" + "\n".join(
        f"{a:.9f},{np.degrees(np.radians(a) - 0.3 * np.sin(np.radians(a))):.9f}" for a in phi))
    batch = write(jobs / "b.yaml", VALID_ENTRY + "    overrides:\n      law_csv: law.csv\n")
    monkeypatch.chdir(tmp_path)         # no law.csv here: only the batch file's folder has one
    (entry,) = load_batch(batch, str(batch)).entries
    assert entry.spec.law_csv == "jobs/law.csv"     # from the working folder: no temporary folder recorded


@pytest.mark.parametrize("overrides, expect", [
    # b's rule ties c: checked again without c, the design's c must not be blamed on b
    ("      c: -5\n      b: 100\n", ["c = -5: must be > 0 mm"]),
    ("      b: -5\n      c: 100\n", ["b = -5: must be >= 0 mm"]),
    # a field rule (width) and a mechanism rule (a) at fault together: both, in file order
    ("      width: -3\n      a: -5\n", ["width = -3: must be > 0 mm", "a = -5: must be > 0 mm"]),
    ("      a: -5\n      width: -3\n", ["a = -5: must be > 0 mm", "width = -3: must be > 0 mm"]),
])
def test_a_rule_tied_to_an_override_at_fault_is_not_reported_again(cli, tmp_path, overrides, expect):
    batch = write(tmp_path / "bad.yaml", VALID_ENTRY.replace("gear-pair", "shoe") + "    overrides:\n"
                  + overrides)
    lines = cli("batch", batch, "--out", tmp_path / "out").stderr.strip().splitlines()
    assert [line.split("parts[0].overrides.", 1)[1] for line in lines] == expect


@pytest.mark.parametrize("overrides, line", [
    # dedendum: 99 breaks its field's range; checked again without it, the design's dedendum
    # standing in is not reported at the same line (as 'dedendum = 1.25: must be > the addendum')
    ("{dedendum: 99, addendum: 1.3}", "dedendum = 99: must be above the addendum and <= 2.5 x module"),
    # turns: 3 gives no law: the sectors rule of z (z*n/4 whole) is not said of it
    ("{turns: 3}", "turns = 3: must be 2 (balanced pinion) or 4 (one pinion turn per shoe)"),
])
def test_an_override_at_fault_is_named_once_and_nothing_follows_from_it(cli, tmp_path, overrides, line):
    batch = write(tmp_path / "bad.yaml", VALID_ENTRY + f"    overrides: {overrides}\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert result.stderr.strip().splitlines() == [f"wheelstep: error: {batch}:6: parts[0].overrides.{line}"]


@pytest.mark.parametrize("file, text, replaced, expect", [
    ("wobbly.yaml", "printer:\n  technology: fdm\n  bed: [200, 200]\n  tooth_clearance: -0.1\n"
     "material:\n  density: 1.2\n", "fdm-0.4-pla",
     "{profile}:4: printer.tooth_clearance = -0.1: must be >= 0"),
    ("mine.yaml", "mechanism: {a: 30, b: 50, r_min: 10}\ngears:\n  z: 24\n  colour: red\n", "desk-demo",
     "{profile}:4: gears.colour: unknown key; allowed: a, b, c, z"),
])
def test_bad_profile_is_located_in_the_profile(cli, tmp_path, file, text, replaced, expect):
    """A bad printer or design profile: the problem is reported at its line in the profile."""
    profile = write(tmp_path / file, text)
    batch = write(tmp_path / "b.yaml", VALID_ENTRY.replace(replaced, str(profile)))
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert expect.format(profile=profile) in result.stderr
    assert not (tmp_path / "out").exists()


@pytest.fixture(scope="module")
def demo_pair():
    """The desk-demo gear pair as drawn for PETG (the largest FDM tooth clearance)."""
    import tempfile

    from wheelstep_cli.batch import load_batch
    from wheelstep_cli.parts.gear_pair import build_gear_pair

    with tempfile.TemporaryDirectory() as folder:
        path = write(Path(folder) / "d.yaml",
                     "parts:\n  - kind: gear-pair\n    design: desk-demo\n    printer: fdm-0.4-petg\n")
        spec = load_batch(path).entries[0].printed
    return spec, build_gear_pair(spec)


def test_demo_gears_build_printable_and_fit_a_resin_plate(demo_pair):
    spec, pair = demo_pair
    from wheelstep_cli.parts.gear_laws import design_backlash

    default = design_backlash(spec.model_copy(update={"backlash": None}))
    assert spec.backlash == pytest.approx(max(default, 0.2))
    assert spec.bore == pytest.approx(5.25)
    assert all(check.ok for check in pair.checks.values())
    size = pair.wheel.bounds[1] - pair.wheel.bounds[0]
    assert size[0] < 123 - 8 and size[1] < 123 - 8  # desk-top: even the 218 x 123 mm resin plate takes it


def test_demo_pinion_teeth_keep_two_extrusion_lines(demo_pair):
    """A 0.4 mm nozzle lays 0.8 mm (two lines) across the pinion's tooth tips: the typical tooth
    loses at most 0.1 mm of height; at most 8 teeth (two on each side of each of the pinion's
    2 handover corners, SPEC §3, which the generator tops) lose more than 0.2 mm. (At z 44 12
    teeth did: the preset has z 42, and `gears` refuses z 44 for this printer.)"""
    spec, pair = demo_pair
    lost = tooth_heights_lost(pair.pinion_outline, pair.generated.module, 0.8)
    assert len(lost) == spec.z
    assert np.median(lost) <= 0.1 and (lost > 0.2).sum() <= 8


def test_demo_wheel_teeth_keep_two_extrusion_lines(demo_pair):
    """As for the pinion. (The paper method's sector-involute wheel teeth fail this: most come
    to sharp points; the generated teeth, now the default, keep their tips.)"""
    spec, pair = demo_pair
    lost = tooth_heights_lost(pair.wheel_outline, pair.generated.module, 0.8)
    assert len(lost) == spec.z * spec.turns
    assert np.median(lost) <= 0.1 and (lost > 0.2).sum() <= 8


def test_inset_bottom_volume_exact_on_a_plate_with_a_hole():
    """20 x 20 mm plate, 3 mm thick, 6 mm bore: the foot loses exactly the offset ring."""
    from wheelstep_cli.geometry.mesh_checks import check_part
    from wheelstep_cli.geometry.solids import bore_segments, extrude_plate, inset_bottom

    square = np.array([[-10, -10], [10, -10], [10, 10], [-10, 10]], dtype=float)
    plate = extrude_plate("plate", square, 3.0, bore=6.0)
    footed = inset_bottom(plate, 0.2, 0.3)
    n = bore_segments(6.0)
    apothem = 3.0  # the bore polygon is circumscribed: its flats touch the 3 mm circle
    hole = n * apothem**2 * np.tan(np.pi / n)
    hole_inset = n * (apothem + 0.3) ** 2 * np.tan(np.pi / n)
    exact = (400 - hole) * 2.8 + ((20 - 0.6) ** 2 - hole_inset) * 0.2
    report = check_part(footed)
    assert report.watertight and report.winding_consistent
    assert report.volume == pytest.approx(exact, rel=1e-6)
    assert footed.expected_volume == pytest.approx(exact, rel=1e-6)
    bottom = footed.vertices[np.isclose(footed.vertices[:, 2], 0.0)]
    assert np.abs(bottom[:, :2]).max() == pytest.approx(9.7, abs=1e-5)


def test_packing_keeps_boxes_apart_and_on_the_bed():
    from hypothesis import given, settings, strategies as st

    from wheelstep_cli.geometry.packing import DoesNotFit, pack_boxes

    @settings(max_examples=60, deadline=None)
    @given(st.lists(st.tuples(st.floats(1, 120), st.floats(1, 120)), min_size=1, max_size=25),
           st.floats(0, 8))
    def check(sizes, margin):
        bed = (200.0, 150.0)
        try:
            spots = pack_boxes(sizes, bed, margin)
        except DoesNotFit as err:
            w, h = sizes[err.key]
            assert min(w, h) > 150 - 2 * margin or max(w, h) > 200 - 2 * margin
            return
        assert spots == pack_boxes(sizes, bed, margin)  # deterministic
        rects = []
        for spot, (w, h) in zip(spots, sizes):
            if spot.rotated:
                w, h = h, w
            assert spot.x >= margin - 1e-9 and spot.y >= margin - 1e-9
            assert spot.x + w <= bed[0] - margin + 1e-6 and spot.y + h <= bed[1] - margin + 1e-6
            rects.append((spot.bed, spot.x, spot.y, w, h))
        for i, a in enumerate(rects):
            for b in rects[i + 1:]:
                if a[0] == b[0]:
                    apart_x = a[1] + a[3] + margin <= b[1] + 1e-6 or b[1] + b[3] + margin <= a[1] + 1e-6
                    apart_y = a[2] + a[4] + margin <= b[2] + 1e-6 or b[2] + b[4] + margin <= a[2] + 1e-6
                    assert apart_x or apart_y
        assert len({s.bed for s in spots}) == max(s.bed for s in spots) + 1

    check()


def test_relative_profile_next_to_the_batch_and_r_min_gives_c(tmp_path, monkeypatch):
    from wheelstep_cli.batch import load_batch

    folder = tmp_path / "jobs"
    folder.mkdir()
    write(folder / "mine.yaml", "mechanism: {a: 30, b: 50, r_min: 10}\ngears: {z: 24}\n")
    batch = write(folder / "b.yaml", VALID_ENTRY.replace("desk-demo", "mine.yaml"))
    monkeypatch.chdir(tmp_path)  # not the batch file's folder
    entry = load_batch(batch).entries[0]
    assert (entry.spec.a, entry.spec.b, entry.spec.c, entry.spec.z) == (30, 50, 10 - 30 + 4 * 50, 24)
    assert entry.printed.bore == pytest.approx(entry.spec.bore + 0.2)  # PLA hole compensation


def test_profiles_given_as_absolute_paths_leave_no_folder_in_the_outputs(cli, tmp_path):
    folder = tmp_path / "my-profiles"
    folder.mkdir()
    printer = write(folder / "shop-printer.yaml", (ROOT / "profiles" / "fdm-0.4-pla.yaml").read_text())
    design = write(folder / "shop-design.yaml", (ROOT / "profiles" / "desk-demo.yaml").read_text())
    batch = write(tmp_path / "b.yaml", f"parts:\n  - kind: shoe\n    design: {design}\n"
                  f"    printer: {printer}\n    overrides: {{width: 12}}\n")
    out = tmp_path / "out"
    assert cli("batch", batch, "--out", out, "--jobs", "1").exit_code == 0
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["entries"][0]["design_profile"] == "shop-design.yaml"
    assert manifest["entries"][0]["printer_profile"] == "shop-printer.yaml"
    for file in out.rglob("*"):
        if file.suffix in (".json", ".md"):
            assert str(tmp_path) not in file.read_text(), file
    with zipfile.ZipFile(out / "plate-1.3mf") as zf:
        assert str(tmp_path).encode() not in zf.read("3D/3dmodel.model")


def test_two_profiles_of_one_file_name_are_refused_before_anything_is_written(cli, tmp_path):
    """The outputs name profiles by file name (slicer settings FILE.ini, manifest, print sheet):
    two printer files named alike, or a file named as a preset, would be written over."""
    for sub in ("a", "b"):
        (tmp_path / sub).mkdir()
        write(tmp_path / sub / "shop.yaml", (ROOT / "profiles" / "fdm-0.4-pla.yaml").read_text())
    write(tmp_path / "b" / "fdm-0.4-pla.yaml", (ROOT / "profiles" / "fdm-0.4-pla.yaml").read_text())
    entry = "  - kind: shoe\n    design: desk-demo\n    printer: {}\n"
    for first, second in (("a/shop.yaml", "b/shop.yaml"), ("fdm-0.4-pla", "b/fdm-0.4-pla.yaml")):
        batch = write(tmp_path / "batch.yaml", "parts:\n" + entry.format(first) + entry.format(first)
                      + entry.format(second))
        out = tmp_path / "out"
        line = error_line(cli("batch", batch, "--out", out))
        assert line == (f"wheelstep: error: {batch}:{line_of(batch, second)}: parts[2].printer = '{second}': "
                        f"names another file than '{first}' of the same name ({Path(second).stem}), and the "
                        "outputs name profiles by file name: rename one of the two files"), line
        assert not out.exists()


def test_batch_refuses_teeth_too_thin_for_the_entrys_printer_with_a_remedy_that_prints(cli, tmp_path):
    """The desk demonstrator at z 44 on the PLA printer: its pinion's tip lands are under two
    0.4 mm lines, so the entry fails alone (exit 1) with the tooth count to use; the same
    design on the resin printer (no extrusion lines) and at the remedy's z are built."""
    entry = "  - name: {name}\n    kind: gear-pair\n    design: desk-demo\n    printer: {printer}\n" \
            "    overrides: {{z: {z}, thickness: 2}}\n"
    batch = write(tmp_path / "b.yaml", "parts:\n"
                  + entry.format(name="fine", printer="fdm-0.4-pla", z=44)
                  + entry.format(name="resin", printer="resin-0.05-standard", z=44)
                  + entry.format(name="remedy", printer="fdm-0.4-pla", z=42))
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1")
    assert result.exit_code == 1
    line = line_of(batch, "z: 44")
    assert (f"fine ({batch}:{line}): z = 44: the teeth are too thin for printer 'fdm-0.4-pla' "
            "(tip land under two 0.4 mm extrusion lines; pinion: 12 teeth lose more than 0.2 mm") \
        in result.stderr
    assert "use overrides {z: 42}" in result.stderr
    assert sorted(p.name for p in (out / "reports").iterdir()) == ["remedy.json", "resin.json"]


def test_a_bounds_refusal_names_the_override_that_shares_the_blame(cli, tmp_path):
    """The desk demonstrator with a backlash of 0.5 mm meshes outside the bounds: the entry's
    line names the backlash it gave (as `gears` names --backlash), at its line, with the
    remedy as the file's keys."""
    batch = write(tmp_path / "b.yaml", VALID_ENTRY + "    overrides:\n      backlash: 0.5\n")
    result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1")
    assert result.exit_code == 1, result.stderr
    assert f"({batch}:{line_of(batch, 'backlash')}): backlash = 0.5: with it, z = 42 fails: the pair would " \
        "mesh outside the bounds" in result.stderr, result.stderr
    assert "use overrides {" in result.stderr


def test_a_batch_gear_pair_whose_hub_makes_it_too_tall_is_refused_before_it_is_built(cli, tmp_path):
    """The batch's early height check is gears': the plate and the hub both gears carry."""
    from tests.helpers.files import line_of, write

    batch = write(tmp_path / "tall.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                  "    design: desk-demo\n    printer: fdm-0.4-pla\n    overrides:\n"
                  "      thickness: 200\n      hub_d: 20\n      hub_length: 60\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2, result.stderr
    assert (f"{batch}:{line_of(batch, 'thickness: 200')}: parts[0].overrides.thickness = 200: makes "
            "part 'pinion' 260.0 mm tall (its 200 mm plate and 60 mm hub), more than the 250 mm printer "
            "'fdm-0.4-pla' prints") in result.stderr
    assert not (tmp_path / "out").exists()


def test_a_design_profiles_value_too_tall_is_offered_as_an_override(cli, tmp_path):
    """The entry's design profile gives the plate that is too tall: the remedy is the
    override the entry adds (as a build's refusals say theirs), and added, the file passes."""
    write(tmp_path / "thick.yaml", "gears:\n  thickness: 300\n")
    text = "parts:\n  - name: g\n    kind: gear-pair\n    design: thick.yaml\n    printer: fdm-0.4-pla\n"
    line = error_line(cli("batch", write(tmp_path / "b.yaml", text), "--out", tmp_path / "out"))
    assert line.endswith("; nothing written; use overrides {thickness: 250} (from design thick.yaml:2)"), line
    fixed = write(tmp_path / "fixed.yaml", text + "    overrides: {thickness: 250}\n")
    assert cli("batch", fixed, "--out", tmp_path / "out", "--dry-run").exit_code == 0


def test_an_empty_override_is_refused_at_its_line(cli, tmp_path):
    """`width: ~` overrode nothing while the manifest listed it as given: refused, naming it."""
    batch = write(tmp_path / "b.yaml", "parts:\n  - kind: shoe\n    design: desk-demo\n"
                  "    printer: fdm-0.4-pla\n    overrides:\n      rim: 3\n      width: ~\n")
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out)
    assert result.exit_code == 2 and not out.exists()
    assert error_line(result) == (f"wheelstep: error: {batch}:{line_of(batch, 'width')}: parts[0].overrides.width "
                                  "= null: give a value, or leave the key out for the design's")


def test_a_quantity_written_with_a_point_zero_is_that_many(cli, tmp_path):
    """`quantity: 2.0` (YAML reads a float) is 2 parts, as `z: 42.0` is 42 teeth (it was
    refused as 'quantity = 2: must be a whole number', a line at odds with itself)."""
    batch = write(tmp_path / "two.yaml", VALID_ENTRY.replace("gear-pair", "shoe").replace(
        "    design: desk-demo\n", "") + "    quantity: 2.0\n")
    result = cli("batch", batch, "--out", tmp_path / "out", "--dry-run", "--json")
    assert result.exit_code == 0, result.stderr
    assert json.loads(result.stdout)["parts"] == 2


def test_a_plate_pictures_title_counts_its_parts_in_words(cli, tmp_path, monkeypatch):
    """A plate of one part was titled "1 parts"."""
    from wheelstep_cli.render import plate_png

    titles = []
    drawn = plate_png.plate_png
    monkeypatch.setattr(plate_png, "plate_png", lambda *args: titles.append(args[-1]) or drawn(*args))
    one = write(tmp_path / "one.yaml", "parts:\n  - kind: shoe\n    design: desk-demo\n    printer: fdm-0.4-pla\n")
    assert cli("batch", one, "--out", tmp_path / "one", "--jobs", "1", "-q").exit_code == 0
    two = write(tmp_path / "two.yaml", "parts:\n  - kind: shoe\n    design: desk-demo\n    quantity: 2\n"
                "    printer: fdm-0.4-pla\n")
    assert cli("batch", two, "--out", tmp_path / "two", "--jobs", "1", "-q").exit_code == 0
    assert [title.rsplit(", ", 1)[1] for title in titles] == ["1 part", "2 parts"], titles
