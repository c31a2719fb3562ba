"""`gears --tolerance / --fit`: a printer without a band is told to add one (SPEC §11)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.helpers.clicheck import error_line, remedy_in, with_remedy
from tests.helpers.files import printer_profile_without_band


def test_a_printer_without_a_band_is_refused_by_tolerance_and_fit(cli, tmp_path):
    printer = printer_profile_without_band(tmp_path)
    for option in (["--tolerance"], ["--fit", "auto"]):
        result = cli("gears", "--printer", str(printer), *option, "--out", tmp_path / "out")
        line = error_line(result)
        assert "has no dimensional band: add a `band:` section" in line
        # the printer as the user wrote it, folder and all
        assert line.startswith(f"wheelstep: error: --printer = {printer}: ")
        assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("kept, expect", [
    (["outline"], "needs the keys 'hole_shrink', 'center_distance'"),
    (["outline", "hole_shrink"], "needs the key 'center_distance'"),
])
def test_a_band_that_leaves_out_keys_is_refused_at_its_line_naming_them(cli, tmp_path, kept, expect):
    """A key left out of a band is not taken as 0 (it said `centre distance +-0 mm`)."""
    from pathlib import Path

    preset = (Path(__file__).resolve().parents[2] / "profiles" / "fdm-0.4-pla.yaml").read_text()
    head, band = preset.split("\nband:", 1)
    body, tail = band.split("\nmaterial:", 1)
    keep = [line for line in body.splitlines()[1:] if line.strip().split(":")[0] in kept]
    printer = tmp_path / "partial.yaml"
    printer.write_text(f"{head}\nband:\n" + "\n".join(keep) + f"\nmaterial:{tail}")
    line_no = printer.read_text().splitlines().index("band:") + 1
    line = error_line(cli("gears", "--tolerance", "--printer", printer, "--out", tmp_path / "out"))
    assert line == f"wheelstep: error: {printer}:{line_no}: band: {expect}"
    assert not (tmp_path / "out").exists()


def test_an_unknown_fit_is_refused(cli, tmp_path):
    result = cli("gears", "--fit", "snug", "--out", tmp_path / "out")
    assert result.exit_code == 2 and "--fit" in result.stderr
    assert result.stderr.strip() == "wheelstep: error: --fit = snug: must be one of auto, tight, normal, loose"
    assert "Value error" not in result.stderr


def test_mesh_check_printer_without_tolerance_is_refused(cli, tmp_path):
    result = cli("mesh-check", "a.stl", "b.stl", "--printer", "fdm-0.4-pla")
    assert "--printer = fdm-0.4-pla: names the band --tolerance checks" in error_line(result)


def test_mesh_check_tolerance_on_a_plate_checks_the_band_of_the_printer_it_was_written_for(cli, tmp_path):
    """A batch user holds plates, not two meshes: --tolerance on a plate checks its pair over
    the band of the printer the plate was written for (it was refused), case by case as
    `gears --tolerance` found it when it wrote the plate, and warns of the jam naming that
    printer; --printer names another band."""
    import json

    out = tmp_path / "out"
    written = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--tolerance", "-q",
                  "--out", out)
    assert written.exit_code == 0, written.stderr
    drawn = json.loads((out / "gears.json").read_text())["meshing"]["tolerance"]
    result = cli("mesh-check", out / "gears.3mf", "--tolerance", "--json")
    assert result.exit_code == 0, result.stderr
    (pair,) = json.loads(result.stdout)["pairs"]
    band = pair["tolerance"]
    assert band["printer"] == "fdm-0.4-pla" and band["jams"] is drawn["jams"]
    for case, before in zip(band["cases"], drawn["cases"], strict=True):
        assert (case["case"], case["jams"]) == (before["case"], before["jams"])
        if not case["jams"]:    # the plate's section against the outline drawn: to a micrometre
            assert case["backlash_min_mm"] == pytest.approx(before["backlash_min_mm"], abs=1e-3)
    if band["jams"]:
        assert "WARNING: over the band of fdm-0.4-pla the pair jams" in result.stderr
        assert "`wheelstep gears --printer fdm-0.4-pla --fit auto`" in result.stderr
    # the shaft fit of the bores, as gears found it: the plate says it was drawn for the printer
    assert band["bore"] == drawn["bore"] and band["bore"]["shaft_mm"] == 5, band["bore"]
    assert "  bore: shaft 5 mm in a bore drawn 5.2 mm" in cli("mesh-check", out / "gears.3mf", "--tolerance").stdout
    resin = cli("mesh-check", out / "gears.3mf", "--tolerance", "--printer", "resin-0.05-standard", "--json")
    resin_band = json.loads(resin.stdout)["pairs"][0]["tolerance"]
    # drawn for another printer's hole compensation: the shaft is not known
    assert resin_band["printer"] == "resin-0.05-standard" and resin_band["bore"] is None


def test_gears_tolerance_reports_every_case_and_the_loose_corner_has_more_play(cli, tmp_path):
    import json

    result = cli("gears", "--profile", "desk-demo", "--tolerance", "--printer", "resin-0.05-standard",
                 "--json", "-q", "--out", tmp_path / "out")
    assert result.exit_code == 0, result.stderr
    meshing = json.loads((tmp_path / "out" / "gears.json").read_text())["meshing"]
    band = meshing["tolerance"]
    assert band["printer"] == "resin-0.05-standard" and band["band"]["outline_mm"] == 0.05
    cases = {case["case"]: case for case in band["cases"]}
    assert list(cases) == ["tight", "pinion grown, wheel shrunk", "pinion shrunk, wheel grown", "loose"]
    loose = cases["loose"]
    assert loose["distance_mm"] == pytest.approx(meshing["distance_mm"] + 0.03)
    assert not loose["jams"] and loose["backlash_min_mm"] > meshing["backlash_min_mm"]
    # a case whose teeth overlap gives no backlash (only estimates where rigid teeth cannot go)
    assert all((c["backlash_max_mm"] is None) == (c["interfering_poses"] > 0) for c in band["cases"])
    assert band["largest_backlash_mm"] == max(c["backlash_max_mm"] for c in band["cases"]
                                              if c["backlash_max_mm"] is not None)



def test_a_jam_over_the_band_suggests_the_same_command_with_a_fit(cli, tmp_path):
    """The desk pair on the FDM band jams: the warning suggests the command as given with
    --fit auto (a bare `wheelstep gears --fit auto` would draw the full-scale pair instead)."""
    result = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--tolerance",
                 "--format", "stl", "--out", tmp_path / "out")
    assert result.exit_code == 0, result.stderr
    warning = result.stderr.strip().splitlines()[-1]
    assert warning.startswith("WARNING: over the band of fdm-0.4-pla the pair jams in "), warning
    assert warning.endswith("; the same command with --fit auto draws the teeth to clear the band (if the "
                            "inset leaves the teeth too thin, its refusal names the tooth count that prints)")


def test_fit_auto_insets_the_default_pair_until_the_fdm_band_no_longer_jams(cli, tmp_path):
    """The default pair on the FDM PLA band: drawn as designed (no clearance) its tight case
    jams, much of it at the pitch-curve corners; `--fit auto` draws both outlines smaller
    along their normals until no case of the band jams and the least backlash keeps the
    auto margin, and the design before the inset is the one the design bounds judged."""
    import json

    from wheelstep_cli.config.printers import FIT_MARGINS, Fit
    from wheelstep_cli.parts.mesh_bounds import MeshBounds

    out = tmp_path / "out"
    result = cli("gears", "--printer", "fdm-0.4-pla", "--fit", "auto", "--json", "-q", "--out", out)
    assert result.exit_code == 0, result.stderr
    meshing = json.loads((out / "gears.json").read_text())["meshing"]
    band = meshing["tolerance"]
    fit = band["fit"]
    assert fit["from"] == "--fit" and fit["replaces_tooth_clearance_mm"] == 0.15
    # the play the inset adds, as the meshing check measures it on the wheel pitch curve: 4e
    # of normal backlash (both flanks of the pinion's tooth and of the wheel's space move e)
    added = meshing["backlash_min_mm"] - fit["design"]["backlash_mm"][0]
    expected = fit["normal_backlash_added_mm"] / np.cos(np.radians(20.0))
    assert 0.8 * expected <= added <= 1.3 * expected
    zero = fit["search"][0]
    assert zero["inset_mm"] == 0.0 and zero["jams"] and zero["jammed_at_corners"] > 0
    assert not band["jams"] and all(not case["jams"] for case in band["cases"])
    assert band["least_backlash_mm"] >= FIT_MARGINS[Fit.auto]
    assert 0.0 < fit["inset_mm"] <= 0.5 and fit["normal_backlash_added_mm"] == pytest.approx(4 * fit["inset_mm"])
    # the written pair's own check closes the search: clear at the inset written, and no
    # smaller inset was found clear
    written = [t for t in fit["search"] if t["checked_on"] == "fitted pair"]
    assert written[-1]["inset_mm"] == fit["inset_mm"] and not written[-1]["jams"]
    clear = [t["inset_mm"] for t in fit["search"]
             if not t["jams"] and t["tight_least_backlash_mm"] >= FIT_MARGINS[Fit.auto]]
    assert fit["inset_mm"] <= min(clear) + 0.5 * max(t["tight_depth_mm"] for t in written) + 0.002 + 1e-9
    bounds = MeshBounds()
    for side in ("drive", "coast"):
        assert fit["design"][side]["F_i_total_um"] <= bounds.total_um
        assert fit["design"][side]["hub_speed_ripple_pct"] <= bounds.ripple_pct
    # the mounting tolerance is the written (inset) outlines': their least gap, and the tip
    # clearance the inset deepened by 2e (each tip e in, each space e deeper)
    generated = json.loads((out / "gears.json").read_text())["generated"]
    mounting = meshing["mounting"]
    assert mounting["closer_mm"] > 0.0
    assert mounting["tip_clearance_mm"] == pytest.approx(0.25 * generated["module_mm"] + 2.0 * fit["inset_mm"])


@pytest.mark.parametrize("option", [["--fit", "auto"], ["--tolerance"], []])
def test_a_pair_too_big_for_the_printer_is_refused_before_the_band(cli, tmp_path, monkeypatch, option):
    """The default wheel (208 mm) on the resin printer's 218 x 123 mm bed: the bed refuses it
    as soon as the gears are built, before the meshing check, a fit search or a band that the
    written files could never use; the only pair checked is the remedy's, smaller, which the
    bed holds, and applied, the remedy writes the pair on that bed."""
    import wheelstep_cli.parts.fit as fit
    import wheelstep_cli.parts.mesh_check as mesh_check
    import wheelstep_cli.parts.tolerance_cli as tolerance_cli
    from wheelstep_cli.config.profiles import load_printer

    room = min(load_printer("resin-0.05-standard").bed) - 2 * load_printer("resin-0.05-standard").edge_margin
    checked, check, case = [], mesh_check.check_gear_pair, fit.check_case

    def on_the_bed_only(pair, *args, **kwargs):
        checked.append(float(np.ptp(pair.wheel.vertices[:, :2], axis=0).max()))
        assert checked[-1] <= room, "a pair larger than the bed was checked"
        return check(pair, *args, **kwargs)

    def case_on_the_bed_only(sections, *args, **kwargs):    # a fit's or a band's case (the remedy's)
        assert float(np.ptp(sections.wheel, axis=0).max()) <= room, "a band of a pair larger than the bed was checked"
        return case(sections, *args, **kwargs)

    monkeypatch.setattr(fit, "check_case", case_on_the_bed_only)
    monkeypatch.setattr(tolerance_cli, "check_case", case_on_the_bed_only)
    monkeypatch.setattr(mesh_check, "check_gear_pair", on_the_bed_only)
    args = ["gears", "--printer", "resin-0.05-standard", *option]
    line = error_line(cli(*args, "--out", tmp_path / "o"))
    assert line.startswith("wheelstep: error: --printer = resin-0.05-standard: part 'wheel'")
    assert "does not fit the bed" in line and not (tmp_path / "o").exists()
    assert checked, "the remedy was not built and checked"
    monkeypatch.undo()
    applied = cli(*with_remedy(args, remedy_in(line)), "--out", tmp_path / "o")
    assert applied.exit_code == 0, applied.stderr
    assert (tmp_path / "o" / "gears.3mf").exists()


def test_fit_auto_meets_the_petg_band_with_the_default_pair(cli, tmp_path):
    """The other FDM preset: its wider band (+-0.12 mm) is met by the default pair under
    `--fit auto` too, every case clear with the auto margin of least backlash."""
    import json

    from wheelstep_cli.config.printers import FIT_MARGINS, Fit
    from wheelstep_cli.config.profiles import load_printer_profile

    out = tmp_path / "out"
    result = cli("gears", "--printer", "fdm-0.4-petg", "--fit", "auto", "--json", "-q", "--out", out)
    assert result.exit_code == 0, result.stderr
    meshing = json.loads((out / "gears.json").read_text())["meshing"]
    band = meshing["tolerance"]
    outline = load_printer_profile("fdm-0.4-petg").band.outline
    assert band["printer"] == "fdm-0.4-petg" and band["band"]["outline_mm"] == outline
    assert not meshing["interference"] and band["fit"]["inset_mm"] > 0.0
    assert not band["jams"] and all(not case["jams"] for case in band["cases"])
    assert band["least_backlash_mm"] >= FIT_MARGINS[Fit.auto]


def test_the_default_pair_fitted_to_the_resin_band_does_not_jam():
    """The resin preset's bed (218 x 123 mm) cannot hold the default 208 mm wheel, so `gears`
    refuses it there; its band is still met by the default pair's fit (the fit as `gears`
    runs it, without the bed)."""
    from wheelstep_cli.config.printers import FIT_MARGINS, Fit
    from wheelstep_cli.config.profiles import load_printer_profile
    from wheelstep_cli.config.specs import GearPairSpec
    from wheelstep_cli.parts.tolerance_cli import design_pair, fitted_pair

    resin = load_printer_profile("resin-0.05-standard")
    spec = GearPairSpec()
    pair, band, nominal = fitted_pair(spec, resin, "auto", design_pair(spec, resin))
    assert band["printer"] == "resin-0.05-standard" and not nominal.interference.any()
    assert not band["jams"] and all(not case["jams"] for case in band["cases"])
    assert band["least_backlash_mm"] >= FIT_MARGINS[Fit.auto]
    assert 0.0 < band["fit"]["inset_mm"] == pair.inset
