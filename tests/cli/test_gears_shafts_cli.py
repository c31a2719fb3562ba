"""`wheelstep gears` shaft options and phase record: refusals and what gears.json says."""

import json

import numpy as np

import pytest

from tests.helpers.clicheck import error_line, with_remedy
from tests.helpers.meshcheck import assert_printable_stl


@pytest.mark.parametrize("args, text", [
    (["--bore-shape", "keyway", "--key-width", "9"], "--key-width = 9: must be < the bore 8 mm"),
    (["--key-width", "3"], "--key-width = 3: needs --bore-shape keyway"),
    (["--flat-depth", "1"], "--flat-depth = 1: needs --bore-shape d-flat"),
    (["--bore-shape", "d-flat", "--flat-depth", "4"], "--flat-depth = 4: must be < half the bore"),
    # the walls a hole leaves (without marks, whose room is the larger limit; test_timing_mark_room)
    (["--bore-shape", "hex", "--bore", "76", "--mark-depth", "0"], "--bore = 76: must be < 65.62 mm (leave 1.5 mm"),
    (["--bore-shape", "keyway", "--bore", "70", "--key-depth", "6", "--mark-depth", "0"], "--key-depth = 6"),
    (["--bore-shape", "oval"], "--bore-shape"),
    (["--key-angle", "400"], "--key-angle = 400"),
    (["--mark-depth", "3"], "--mark-depth = 3"),
    # an engraving through the face: was a mesh defect ("a defect of wheelstep") after the build
    (["--thickness", "1", "--mark-depth", "1.2"], "--mark-depth = 1.2: must be <= half the thickness, 0.5 mm"),
    (["--thickness", "0.5"], "--thickness = 0.5: must be >= twice the mark depth, 1 mm"),
    # the key width is the bore's DIN default: the bore the user gave is named
    (["--bore-shape", "keyway", "--bore", "1"], "--bore = 1: must be > the key width 2 mm"),
    (["--hub-d", "90"], "--hub-d = 90: must be <="),                      # larger than the root
    (["--hub-d", "9"], "--hub-d = 9: must be >="),                        # no wall round the bore
    (["--hub-length", "9"], "--hub-length = 9: needs --hub-d"),
    (["--set-screw", "M3"], "--set-screw = M3: needs --hub-d"),
    (["--hub-d", "14", "--set-screw", "M3"], "--set-screw = M3: does not fit the hub"),
    (["--chamfer", "5"], "--chamfer = 5: must be < half the thickness"),
    # no key depth helps a bore that is itself too large: the bore is named, with its limit
    (["--bore-shape", "keyway", "--bore", "76", "--mark-depth", "0"],
     "--bore = 76: must be < 61.71 mm with the keyway's"),
    (["--bore-shape", "hex", "--bore", "0"], "--bore = 0: must be > 0 mm for a hex"),
    (["--bore", "0", "--hub-d", "20", "--set-screw", "M3"], "--set-screw = M3: needs a bore"),
    (["--key-angle", "30"], "--key-angle = 30: orients a keyed bore or a set screw"),
])
def test_shaft_misfits_are_refused_in_one_line_nothing_written(cli, tmp_path, args, text):
    out = tmp_path / "out"
    assert text in error_line(cli("gears", *args, "--out", out))
    assert not out.exists()


def test_keyway_for_a_printer_states_phase_and_compensates_the_key(cli, tmp_path):
    out = tmp_path / "k"
    result = cli("gears", "--bore-shape", "keyway", "--key-angle", "90", "--printer", "fdm-0.4-pla",
                 "--format", "stl", "--out", out)
    assert result.exit_code == 0, result.stderr
    report = json.loads((out / "gears.json").read_text())
    assert report["parameters"]["key_width"] == 2 and report["parameters"]["key_depth"] == 1.0
    assert report["printed_parameters"]["key_width"] == pytest.approx(2.2)
    phase = report["phase"]
    assert phase["shaft"] == {**phase["shaft"], "bore_shape": "keyway", "key_angle_deg": 90}
    assert [h["carrier_deg"] for h in phase["handovers"]] == pytest.approx([-45, 45, 135, 225])
    assert report["meshing"]["in_phase"] is True
    for name in ("pinion", "wheel"):
        assert_printable_stl(out / f"{name}.stl")


def _figures(record: dict) -> dict:
    """The meshing figures that must agree between gears.json and mesh-check of the files."""
    return {"backlash_min_mm": record["backlash_min_mm"], "in_phase": record["in_phase"],
            "interference": record["interference"],
            **{f"{side}_{key}": record[side][key] for side in ("drive", "coast")
               for key in ("F_i_total_um", "f_i_tooth_um")}}


def test_hub_with_the_printers_chamfer_is_one_shell_and_mesh_check_cuts_the_teeth(cli, tmp_path):
    """A hub taller than the plate (a section half-way up the mesh would cut the hub) with the
    printer's chamfer: each gear one closed shell of the volume gears.json states, and
    mesh-check of the written STL and 3MF files sections the teeth and finds the figures of
    gears.json."""
    out = tmp_path / "hub"
    result = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--hub-d", "16",
                 "--hub-length", "10", "--out", out, "-q")
    assert result.exit_code == 0, result.stderr
    report = json.loads((out / "gears.json").read_text())
    assert report["chamfer"]["mm"] == 0.4 and report["chamfer"]["from"] == "printer profile fdm-0.4-pla"
    assert report["chamfer"]["elephant_foot_inset"].startswith("replaced by the chamfer")
    assert report["parameters"]["chamfer"] is None and report["printed_parameters"]["chamfer"] == 0.4
    for name in ("pinion", "wheel"):
        mesh = assert_printable_stl(out / f"{name}.stl")
        assert mesh.body_count == 1
        assert mesh.bounds[1][2] == pytest.approx(16.0, abs=1e-4)
        assert mesh.volume == pytest.approx(report["parts"][name]["volume_mm3"], rel=1e-5)
    expected = _figures(report["meshing"])
    stl = cli("mesh-check", out / "pinion.stl", out / "wheel.stl", "--profile", "desk-demo",
              "--distance", str(report["meshing"]["distance_mm"]), "--json", "-q")
    plate = cli("mesh-check", out / "gears.3mf", "--json", "-q")
    assert stl.exit_code == 0 and plate.exit_code == 0, stl.stderr + plate.stderr
    for found in (json.loads(stl.stdout), json.loads(plate.stdout)["pairs"][0]):
        figures = _figures(found)   # (the files hold float32 vertices: a few nm off)
        assert figures.pop("backlash_min_mm") == pytest.approx(expected.pop("backlash_min_mm"), abs=1e-3)
        assert figures == pytest.approx(expected, abs=0.2)
        expected = _figures(report["meshing"])


@pytest.mark.parametrize("misfit, limit", [
    (["--profile", "desk-demo", "--hub-d", "15", "--set-screw", "M3", "--bore-shape", "keyway"],
     "--hub-d"),                                                                  # too narrow
    (["--thickness", "2", "--hub-d", "30", "--hub-length", "1", "--set-screw", "M5"], "--hub-length"),  # too short
])
def test_a_set_screw_that_does_not_fit_names_the_hub_size_that_fits_as_printed(cli, tmp_path, misfit, limit):
    """The hub a set screw needs is said rounded up, so that, applied as printed, it fits (a
    hub diameter rounded down was refused again), and a nut too tall for a short hub names the
    hub's length, not its diameter."""
    design = ["--format", "stl", *misfit]
    line = error_line(cli("gears", *design, "--out", tmp_path / "out"))
    assert "does not fit the hub: " in line and f"needs {limit} >= " in line, line
    least = line.split(f"needs {limit} >= ")[1].split(" mm")[0]
    result = cli("gears", *with_remedy(design, [limit, least]), "--out", tmp_path / "fits")
    assert result.exit_code == 0, result.stderr


@pytest.mark.parametrize("screw", ["M3", "M6"])
def test_a_set_screws_hole_leaves_through_the_hubs_side_above_the_plate(cli, tmp_path, screw):
    """A hub too short for the screw's hole (it would run into the plate's web, out of reach)
    is refused with the least hub length; at that length the hole cuts nothing of the plate
    outside the hub."""
    import numpy as np
    import trimesh

    from wheelstep_cli.gears.bore_shapes import SET_SCREWS

    out = tmp_path / "out"
    args = ["gears", "--profile", "desk-demo", "--set-screw", screw, "--hub-d", "24", "--mark-depth", "0",
            "--format", "stl", "--out", out, "-q"]
    line = error_line(cli(*args, "--hub-length", "0.5"))
    assert f"--set-screw = {screw}: does not fit the hub: needs --hub-length >= " in line, line
    least = line.split("--hub-length >= ")[1].split(" mm")[0]
    assert float(least) == pytest.approx(SET_SCREWS[screw][0] + 1.0, abs=0.01)
    assert not out.exists()
    assert cli(*args, "--hub-length", least).exit_code == 0
    mesh = trimesh.load(out / "pinion.stl")
    r = np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 1])
    z = mesh.vertices[:, 2]
    # inside the plate (6 mm), outside the hub (12 mm radius) and clear of the teeth: no vertex
    web = (r > 12.05) & (r < 20.0) & (z > 0.05) & (z < 5.95)
    assert not web.any(), np.column_stack([r[web], z[web]])[:5]


def test_a_keyway_too_deep_for_the_root_is_said_of_the_bore_when_its_depth_is_the_default(cli, tmp_path):
    """The key depth left to its DIN default is not the user's: the bore they gave is named,
    with the largest that leaves the wall; applied, the pair is made."""
    args = ["gears", "--profile", "desk-demo", "--bore-shape", "keyway", "--mark-depth", "0", "--dry-run",
            "--out", tmp_path / "out"]
    line = error_line(cli(*args, "--bore", "30"))
    assert line.startswith("wheelstep: error: --bore = 30: must be < ") and "keyway's 3.3 mm depth" in line, line
    largest = line.split("must be < ")[1].split(" mm")[0]
    assert cli(*args, "--bore", largest).exit_code == 0
    given = error_line(cli(*args, "--bore", "30", "--key-depth", "3.3"))
    assert given.startswith("wheelstep: error: --key-depth = 3.3: must be < "), given


def test_the_report_gives_the_hub_length_built(cli, tmp_path):
    """A hub without --hub-length is 8 mm long: the report says so (it said null)."""
    out = tmp_path / "out"
    assert cli("gears", "--profile", "desk-demo", "--hub-d", "16", "--format", "stl", "--out", out, "-q").exit_code == 0
    report = json.loads((out / "gears.json").read_text())
    assert report["parameters"]["hub_length"] == 8.0
    assert report["parts"]["pinion"]["bounding_box_mm"][1][2] == pytest.approx(6.0 + 8.0, abs=1e-3)


def test_a_keyed_bore_too_large_for_the_timing_mark_gets_one_limit_that_passes(cli, tmp_path):
    """The keyed bore's limit was searched with the typed bore's DIN key (60 -> 56.33 mm,
    80 -> 53.09 mm, while 57 passed), and a search among bores under their key crashed (a
    traceback for --key-depth 20 of a 40-tooth pinion): the default key follows the bore, so
    every bore too large gets the same limit, which applied passes; a given key is kept."""
    limits = set()
    for bore in ("60", "70", "80"):
        args = ["gears", "--bore", bore, "--bore-shape", "keyway", "--out", tmp_path / "k", "--dry-run"]
        line = error_line(cli(*args))
        assert line.startswith(f"wheelstep: error: --bore = {bore}: must be <= "), line
        limits.add(line.split("must be <= ")[1].split(" mm")[0])
    (limit,) = limits
    assert cli("gears", "--bore", limit, "--bore-shape", "keyway", "--out", tmp_path / "k", "--dry-run").exit_code == 0
    for extra in (["--key-depth", "20"], ["--bore", "60"], ["--key-width", "7.9", "--key-depth", "16"]):
        args = ["gears", "--turns", "4", "--z", "40", "--bore-shape", "keyway", *extra]
        result = cli(*args, "--out", tmp_path / "k", "--dry-run")
        assert result.exit_code == 2, result.stderr
        line = error_line(result)
        param, rest = line.split("wheelstep: error: ")[1].split(" = ", 1)
        limit = rest.split("must be <= ")[1].split(" mm")[0]
        fixed = with_remedy(args, [param, limit])
        assert cli(*fixed, "--out", tmp_path / "k", "--dry-run").exit_code == 0, (fixed, line)


def test_a_printers_chamfer_too_large_for_the_gear_names_the_thickness_and_the_printer(cli, tmp_path):
    """The chamfer comes from the printer profile (none given): the refusal named `--chamfer
    = 0.4`, an option the user never typed. It names the thickness and the printer, and the
    chamfer it offers is one the printer takes: applied, the pair is written."""
    args = ["gears", "--printer", "fdm-0.4-pla", "--thickness", "0.7", "--mark-depth", "0",
            "--format", "stl"]
    result = cli(*args, "--out", tmp_path / "thin", "--json")
    line = error_line(result)
    assert line == ("wheelstep: error: --thickness = 0.7: must be > twice the edge chamfer of printer "
                    "fdm-0.4-pla, 0.8 mm; or --chamfer 0 for none"), line
    assert not (tmp_path / "thin").exists()
    remedy = json.loads(result.stdout)["error"]["remedy"]
    applied = with_remedy(args, [str(part) for item in remedy.items() for part in item])
    out = tmp_path / "fixed"
    done = cli(*applied, "--out", out)
    assert done.exit_code == 0, done.stderr
    assert json.loads((out / "gears.json").read_text())["chamfer"]["mm"] == 0
    for name in ("pinion", "wheel"):
        assert_printable_stl(out / f"{name}.stl")


def _limit(line: str) -> str:
    """The number a `must be < X mm` / `must be <= X mm` refusal states, less a hundredth."""
    import re

    return f"{float(re.search(r'must be <=? ([0-9.]+) mm', line).group(1)) - 0.01:.2f}"


def test_a_key_too_wide_for_any_bore_is_named_and_the_limits_applied_converge(cli, tmp_path):
    """A key as wide as the bore leaves no bore that holds it and keeps the wall: the bore's
    limit came out below the key width ("--bore = 60: must be < 0.00 mm"). The key is named;
    its limit, then the bore's, applied, give a pair that is written."""
    args = ["gears", "--bore-shape", "keyway", "--bore", "70", "--key-width", "69", "--mark-depth", "0",
            "--dry-run", "--out", tmp_path / "o"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --key-width = 69: must be < ") and "no bore both holds the key" in line
    args[args.index("--key-width") + 1] = _limit(line)
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --bore = 70: must be < ") and float(_limit(line)) > float(
        args[args.index("--key-width") + 1]), line
    args[args.index("--bore") + 1] = _limit(line)
    done = cli(*args)
    assert done.exit_code == 0, done.stderr


def test_a_hub_with_no_size_that_fits_is_told_to_the_bore(tmp_path):
    """A hole reaching so near the root that no hub leaves its wall on both sides: each of the
    hub's two limits was said alone (>= 88 mm round the hole, then <= 34 mm), and applying one
    broke the other; the line says the hole is what to make smaller."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.geometry.hole_walls import MIN_HOLE_WALL, require_hub_fits

    ring = np.column_stack([np.cos(np.linspace(0, 2 * np.pi, 90, endpoint=False)),
                            np.sin(np.linspace(0, 2 * np.pi, 90, endpoint=False))])
    with pytest.raises(DesignError, match="has no size that fits") as caught:
        require_hub_fits(30.0 * ring, (30.0 - 1.5 * MIN_HOLE_WALL) * ring, 58.0)
    assert caught.value.param == "hub_d" and "make the hole smaller (--bore" in caught.value.limit


def test_marks_reaching_into_the_elephant_foot_name_the_mark_depth(cli, tmp_path):
    """An unchamfered 0.6 mm gear with 0.3 mm marks on an FDM printer: the foot's inset needs a
    prism over the lowest two foot heights, and the refusal said `pinion = elephant foot` (no
    option of the user's, no limit). It names the mark depth with the deepest that fits."""
    args = ["gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--thickness", "0.6", "--mark-depth",
            "0.3", "--chamfer", "0", "--dry-run", "--out", tmp_path / "o"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --mark-depth = 0.3: must be <= 0.20 mm: deeper, the marks reach "
                           "into the lowest 0.4 mm"), line
    args[args.index("--mark-depth") + 1] = "0.20"
    done = cli(*args)
    assert done.exit_code == 0, done.stderr


def test_a_chamfer_on_a_gear_too_thin_for_any_the_printer_takes_is_told_only_0_does(cli, tmp_path):
    """On fdm-0.4-pla a chamfer must be 0 or at least 0.4 mm (it replaces the foot's inset), and
    below half the thickness: on a 0.6 mm gear the first line offered >= 0.4, the second then
    refused 0.4 (no value passed both). It says only 0 does; 0, applied, passes."""
    args = ["gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--thickness", "0.6", "--mark-depth",
            "0.2", "--chamfer", "0.1", "--dry-run", "--out", tmp_path / "o"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --chamfer = 0.1: must be 0 on printer fdm-0.4-pla for a 0.6 mm gear"), line
    args[args.index("--chamfer") + 1] = "0"
    done = cli(*args)
    assert done.exit_code == 0, done.stderr


def test_a_key_too_deep_for_any_bore_is_told_by_its_depth_not_a_width_of_zero(cli, tmp_path):
    """A key deeper than the wall room leaves no bore at any width: the refusal said
    `--key-width = 2: must be < 0.00 mm`, a limit no key meets. The depth is named, with a limit
    that applied gives a pair that is written."""
    args = ["gears", "--profile", "desk-demo", "--bore-shape", "keyway", "--bore", "5", "--key-width", "2",
            "--key-depth", "19", "--mark-depth", "0", "--dry-run", "--out", tmp_path / "o"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --key-depth = 19: must be < "), line
    args[args.index("--key-depth") + 1] = _limit(line)
    done = cli(*args)
    assert done.exit_code == 0, done.stderr
    # a bore too large besides: its limit is one a bore can meet (it said < 0.00 mm), then the depth's
    args = ["gears", "--bore-shape", "keyway", "--bore", "95", "--key-depth", "60", "--key-width", "4",
            "--mark-depth", "0", "--dry-run", "--out", tmp_path / "o"]
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --bore = 95: must be < ") and float(_limit(line)) > 0.0, line
    args[args.index("--bore") + 1] = _limit(line)
    line = error_line(cli(*args))
    assert line.startswith("wheelstep: error: --key-depth = 60: must be < "), line
    args[args.index("--key-depth") + 1] = _limit(line)
    assert cli(*args).exit_code == 0
