"""`wheelstep batch`: every gear pair checked over its printer's band (by default; `--no-tolerance`
skips it), per case in its report and the manifest; a printer without a band is told to add
one (SPEC §11)."""

from __future__ import annotations

import json

from tests.batch.test_batch import object_metadata
from tests.helpers.clicheck import error_line
from tests.helpers.files import printer_profile_without_band, write


def test_batch_records_the_band_per_case_and_names_a_printer_without_one(cli, tmp_path):
    bare = printer_profile_without_band(tmp_path)
    batch = write(tmp_path / "band.yaml", "parts:\n"
                  "  - name: banded\n    kind: gear-pair\n    design: desk-demo\n    printer: fdm-0.4-pla\n"
                  f"  - name: bare\n    kind: gear-pair\n    design: desk-demo\n    printer: {bare}\n")
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1")    # the band check is the default
    assert result.exit_code == 0, result.stderr
    report = json.loads((out / "reports" / "banded.json").read_text())
    band = report["tolerance"]
    assert band["checked"] and band["printer"] == "fdm-0.4-pla" and band["tooth_clearance_mm"] == 0.15
    assert [c["case"] for c in band["cases"]][0] == "tight" and len(band["cases"]) == 4
    # the printer's clearance does not cover the FDM band's tight corner on this pair
    assert band["jams"] is True and band["cases"][0]["jams"] is True
    assert band["cases"][-1]["case"] == "loose" and band["cases"][-1]["jams"] is False
    # hole shrink: the desk shaft (5 mm) in its bore drawn 0.2 mm larger, at the band's extremes
    assert band["bore"]["shaft_mm"] == 5 and band["bore"]["drawn_mm"] == 5.2
    assert band["bore"]["clearance_mm"] == [0.0, 0.2]
    manifest = json.loads((out / "manifest.json").read_text())
    entries = {e["name"]: e for e in manifest["entries"]}
    assert entries["banded"]["tolerance"]["cases"]["loose"]["backlash_min_mm"] > 0
    assert entries["bare"]["tolerance"]["checked"] is False
    assert "add a `band:` section" in entries["bare"]["tolerance"]["note"]
    assert manifest["checks"]["gear_pairs_mesh_over_printer_bands"] is False
    assert manifest["checks"]["printers_without_band"] == [str(bare)] or \
        manifest["checks"]["printers_without_band"][0].endswith("no-band.yaml")
    assert "banded jams over the band of fdm-0.4-pla" in result.stderr
    # a jammed band's least "backlash" is an overlap estimate, not shown as a backlash
    warning = next(l for l in result.stderr.splitlines() if "banded jams" in l)
    assert "least backlash -" not in warning and "insets the tooth outlines until the band clears" in warning
    # the advice does not promise what --fit auto may refuse
    assert "says so when none within its limits does" in warning
    assert "`gears --slice` checks the pair as PrusaSlicer prints it" in warning
    # each pair's report says it meshes within the bounds, judged on the meshes written
    assert report["meshing"]["bounds"]["within"] is True and report["meshing"]["bounds"]["broken"] == []
    assert "has no dimensional band: add a `band:` section" in result.stderr
    # the bare printer's pair alone: nothing jams, but it was never checked over a band
    alone = write(tmp_path / "alone.yaml", "parts:\n"
                  f"  - name: bare\n    kind: gear-pair\n    design: desk-demo\n    printer: {bare}\n")
    assert cli("batch", alone, "--out", tmp_path / "alone", "--jobs", "1").exit_code == 0
    checks = json.loads((tmp_path / "alone" / "manifest.json").read_text())["checks"]
    assert checks["gear_pairs_mesh_over_printer_bands"] is None and len(checks["printers_without_band"]) == 1


def test_no_tolerance_runs_no_band_check(cli, tmp_path):
    batch = write(tmp_path / "plain.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                                           "    design: desk-demo\n    printer: fdm-0.4-pla\n")
    out = tmp_path / "out"
    result = cli("batch", batch, "--out", out, "--jobs", "1", "--no-tolerance")
    assert result.exit_code == 0, result.stderr
    assert "jams over the band" not in result.stderr
    assert "tolerance" not in json.loads((out / "reports" / "pair.json").read_text())
    # unchecked, its backlash all the printer's tooth clearance is warned of, as gears warns
    assert ("WARNING: pair: printed on 'fdm-0.4-pla' the teeth keep no play of their own (the backlash "
            "is all the printer's tooth clearance)") in result.stderr
    assert "gear_pairs_mesh_over_printer_bands" not in json.loads((out / "manifest.json").read_text())["checks"]


def _resin_with_fit(folder, fit: str):
    """The resin preset with ``fit`` in its band, written into ``folder``."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "profiles" / "resin-0.05-standard.yaml").read_text()
    path = folder / "resin-fit.yaml"
    path.write_text(text.replace("  center_distance: 0.03\n", f"  center_distance: 0.03\n  fit: {fit}\n"))
    return path


def test_a_printer_band_with_a_fit_has_batch_inset_its_gear_pairs_to_the_band(cli, tmp_path):
    """A band's `fit:` is what batch fits gear pairs to, as `gears --fit` does: the design
    drawn without the printer's tooth clearance, both outlines inset until no case of the
    band jams and the least backlash keeps the margin; the parts written are the fitted ones
    (`gears` with that printer and no --fit fits the same pair), the plate's metadata says
    them as printed and `mesh-check` reads the plate back (a module in the design: its
    distances are stored as the design gives them)."""
    from wheelstep_cli.config.printers import FIT_MARGINS, Fit

    printer = _resin_with_fit(tmp_path, "normal")
    batch = write(tmp_path / "fit.yaml", "parts:\n  - name: pair\n    kind: gear-pair\n"
                                         f"    design: desk-demo\n    printer: {printer}\n"
                                         "    overrides: {module: 1.2}\n")
    out = tmp_path / "out"
    # --no-tolerance skips the band check, not the fit: the fit is how the printer draws pairs
    result = cli("batch", batch, "--out", out, "--jobs", "1", "--no-tolerance")
    assert result.exit_code == 0, result.stderr
    report = json.loads((out / "reports" / "pair.json").read_text())
    band = report["tolerance"]
    assert band["fit"]["fit"] == "normal" and band["fit"]["inset_mm"] > 0.0
    manifest = json.loads((out / "manifest.json").read_text())
    assert [e["tolerance"]["inset_mm"] for e in manifest["entries"]] == [band["fit"]["inset_mm"]]
    assert not band["jams"] and band["least_backlash_mm"] >= FIT_MARGINS[Fit.normal] - 0.005
    assert report["design_report"]["outline_inset_mm"]["inset_mm"] == band["fit"]["inset_mm"]
    assert report["printer_geometry"]["tooth_clearance"] == 0.0
    assert report["printer_geometry"]["outline_inset"] == band["fit"]["inset_mm"]
    assert report["meshing"]["mounting"]["closer_mm"] > 0.0   # the inset outlines' own mounting gap
    assert "inset along their normals for the band's fit 'normal'" in (out / "print-sheet.md").read_text()
    assert "jams over the band" not in result.stderr
    assert (f"pair: fit normal to the band of {band['printer']}: both tooth outlines drawn "
            f"{band['fit']['inset_mm']:.3f} mm smaller") in result.stdout
    # the plate's 3MF metadata says the parts as printed: no tooth clearance, the inset, and
    # the design's backlash (not the printer's clearance added to it)
    plates = sorted(out.glob("*.3mf"))
    placed = [meta for plate in plates for meta in object_metadata(plate).values()]
    assert placed and all(meta["wheelstep:printer.tooth_clearance"] == "0"
                          and abs(float(meta["wheelstep:outline_inset"]) - band["fit"]["inset_mm"]) < 1e-9
                          and abs(float(meta["wheelstep:backlash"]) - report["printed_parameters"]["backlash"]) < 1e-9
                          and meta["wheelstep:module"] == "1.2" and "wheelstep:center_distance" not in meta
                          for meta in placed)
    read = cli("mesh-check", plates[0], "--samples", "256", "--json")
    assert read.exit_code == 0, read.stderr
    (measured,) = json.loads(read.stdout)["pairs"]
    assert measured["interference"] is False and measured["backlash_min_mm"] > 0.0

    gears = cli("gears", "--profile", "desk-demo", "--module", "1.2", "--printer", printer, "--json", "-q",
                "--out", tmp_path / "g")
    assert gears.exit_code == 0, gears.stderr
    assert json.loads(gears.stdout)["meshing"]["tolerance"]["fit"]["inset_mm"] == band["fit"]["inset_mm"]
    written = [meta for plate in sorted((tmp_path / "g").glob("*.3mf")) for meta in object_metadata(plate).values()]
    assert written and all(abs(float(meta["wheelstep:outline_inset"]) - band["fit"]["inset_mm"]) < 1e-9
                           for meta in written)


def test_a_resin_pair_jamming_over_its_band_is_not_sent_to_the_fdm_read_back(cli, tmp_path):
    """`gears --slice` reads back FDM G-code and refuses a resin printer: a resin pair's jam
    warning offers the fit alone."""
    batch = write(tmp_path / "resin.yaml", "parts:\n  - name: rgears\n    kind: gear-pair\n"
                  "    design: desk-demo\n    printer: resin-0.05-standard\n")
    result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1")
    assert result.exit_code == 0, result.stderr
    warning = next(l for l in result.stderr.splitlines() if "rgears jams over the band" in l)
    assert "--slice" not in warning and "`fit: auto` in the printer profile's band section" in warning


def test_the_band_switch_on_a_batch_without_gear_pairs_is_refused(cli, tmp_path):
    """--tolerance / --no-tolerance act on gear pairs only: given for a batch of shoes, refused
    (exit 2, nothing written) rather than ignored; left out, the batch builds."""
    batch = write(tmp_path / "shoes.yaml", "parts:\n  - kind: shoe\n    design: desk-demo\n    printer: fdm-0.4-pla\n")
    for switch in ("--tolerance", "--no-tolerance"):
        result = cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1", switch)
        assert result.exit_code == 2
        assert error_line(result) == (f"wheelstep: error: {switch} = on: the band check is of gear pairs, "
                                      "and the batch has none")
        assert not (tmp_path / "out").exists()
    assert cli("batch", batch, "--out", tmp_path / "out", "--jobs", "1").exit_code == 0
