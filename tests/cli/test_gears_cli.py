"""`wheelstep gears` end to end: files written, printable, deterministic; bad input refused."""

import json
import subprocess
import sys

import numpy as np
import pytest

from tests.helpers.clicheck import error_line, remedy_in, with_remedy
from tests.helpers.meshcheck import assert_printable_stl, read_3mf_strict


@pytest.fixture(scope="module")
def default_pair(tmp_path_factory):
    out = tmp_path_factory.mktemp("gears")
    from wheelstep_cli.cli import run

    # the paper pair interferes at the shoe handovers: written only on request (test_gears_meshing)
    assert run(["gears", "--z", "48", "--allow-interference", "--out", str(out)]) == 0
    return out


def test_writes_printable_meshes_and_report(default_pair):
    names = sorted(p.name for p in default_pair.iterdir())
    # the full-scale pair does not fit one 256 mm bed together: one plate per gear; the record
    # of what this command wrote (SHA-256 per file) lets a later run clean up only its own files
    assert names == [".wheelstep-gears.json", "gears-1.3mf", "gears-2.3mf", "gears.json", "pinion.stl",
                     "wheel.stl"]
    from wheelstep_cli.cli.commands.sweep import _BEST_FILES

    assert set(_BEST_FILES["gears"]) <= set(names)    # what sweep --keep checks before its run
    report = json.loads((default_pair / "gears.json").read_text())
    for name in ("pinion", "wheel"):
        mesh = assert_printable_stl(default_pair / f"{name}.stl")
        part = report["parts"][name]
        assert mesh.volume == pytest.approx(part["volume_mm3"], rel=1e-4)
        assert np.allclose(mesh.bounds, part["bounding_box_mm"], atol=1e-3)
        assert mesh.bounds[1, 2] - mesh.bounds[0, 2] == pytest.approx(10.0)
    assert report["parameters"]["install_distance"] == 144
    assert report["parameters"]["backlash"] == pytest.approx(0.239)   # what the ripple bound allows
    assert report["parameters"]["teeth"] == "generated"       # the default since issue 6
    assert report["generated"]["pinion_teeth"] == 48 and report["generated"]["wheel_teeth"] == 96
    assert report["parts"]["pinion"]["teeth"] == 48 and report["parts"]["wheel"]["teeth"] == 96


def test_paper_method_still_writes_its_sector_table(cli, tmp_path):
    assert cli("gears", "--teeth", "paper", "--allow-interference", "--format", "stl",
               "--out", tmp_path).exit_code == 0
    report = json.loads((tmp_path / "gears.json").read_text())
    assert len(report["sectors"]) == 24 and "generated" not in report
    assert report["parts"]["pinion"]["teeth"] == 48 and report["parts"]["wheel"]["teeth"] == 96


def test_3mf_plates_read_back_strict_with_the_two_named_objects(default_pair):
    infos = [read_3mf_strict(default_pair / f"gears-{i}.3mf") for i in (1, 2)]
    assert [i["warnings"] for i in infos] == [[], []]
    objects = {name: volume for info in infos for name, volume in info["objects"].items()}
    assert set(objects) == {"pinion", "wheel"}
    assert [i["build_items"] for i in infos] == [1, 1]
    report = json.loads((default_pair / "gears.json").read_text())
    for name, volume in objects.items():
        assert volume == pytest.approx(report["parts"][name]["volume_mm3"], rel=1e-4)


def test_bore_is_cut(default_pair, cli, tmp_path):
    assert cli("gears", "--bore", "0", "--format", "stl", "--allow-interference",
               "--out", tmp_path).exit_code == 0
    solid = assert_printable_stl(tmp_path / "pinion.stl")
    bored = assert_printable_stl(default_pair / "pinion.stl")
    # without a bore the timing mark's groove starts at the axis instead of beyond the bore:
    # 4 mm longer, 0.8 mm wide, 0.5 mm deep
    removed = solid.volume - bored.volume + 4.0 * 0.8 * 0.5
    assert np.pi * 4.0**2 * 10.0 <= removed <= 1.005 * np.pi * 4.0**2 * 10.0
    # the hole's polygon is circumscribed: an 8 mm shaft fits, with < 0.02 mm play at the corners
    radius = np.hypot(bored.vertices[:, 0], bored.vertices[:, 1])
    assert 4.0 < radius.min() < 4.02


def test_same_inputs_give_identical_files(default_pair, tmp_path):
    # a separate process, so nothing cached in this one can make them equal
    subprocess.run([sys.executable, "-m", "wheelstep_cli", "gears", "--allow-interference",
                    "--out", str(tmp_path)],
                   check=True, capture_output=True)
    for name in ("pinion.stl", "wheel.stl", "gears-1.3mf", "gears-2.3mf", "gears.json"):
        assert (tmp_path / name).read_bytes() == (default_pair / name).read_bytes(), name


def test_profile_reproduces_defaults_and_cli_overrides(cli, tmp_path, default_pair):
    assert cli("gears", "--profile", "bntu-2024", "--allow-interference",
               "--out", tmp_path / "p").exit_code == 0
    assert (tmp_path / "p" / "wheel.stl").read_bytes() == (default_pair / "wheel.stl").read_bytes()
    assert cli("gears", "--profile", "bntu-2024", "--thickness", "6", "--format", "stl",
               "--allow-interference", "--out", tmp_path / "q").exit_code == 0
    mesh = assert_printable_stl(tmp_path / "q" / "pinion.stl")
    assert mesh.bounds[1, 2] == pytest.approx(6.0)
    assert not (tmp_path / "q" / "gears.3mf").exists()


@pytest.mark.parametrize("args, param", [
    (["--b", "110", "--c", "360"], "c ="),         # R_min = a - 4b + c < 0
    (["--rmin", "0"], "--rmin = 0: must be >= 0.001 mm"),   # the strut as R_min, as shoe takes it
    (["--rmin", "20", "--c", "300"], "--rmin = 20: contradicts c = 300 mm"),
    (["--z", "47"], "z ="),                        # not whole sectors
    (["--teeth", "paper", "--module", "4"], "module ="),   # pointed teeth
    (["--bore", "100"], "bore ="),                 # bore larger than the root
    (["--a", "-60"], "a ="),                       # negative length
    (["--a", "sixty"], "--a = sixty: must be a number"),   # not a number
    (["--z", "1e9"], "--z = 1e9: must be a whole number, 6..240 (pinion teeth)"),
    (["--z=4.5"], "--z = 4.5: must be a whole number, 6..240"),
    (["--thickness", "0"], "thickness ="),
    (["--teeth", "paper", "--center-distance", "143.5", "--install-distance", "140"],
     "install-distance ="),                       # paper sectors mounted closer than they roll
    (["--module", "2.5", "--center-distance", "144"], "center-distance ="),  # the module sets it
    (["--turns", "3"], "turns ="),
    (["--backlash", "5"], "--backlash = 5:"),      # pointed teeth: the rule named for the backlash
    (["--profile", "no-such-design"], "profile ="),
    # the generator's settings do not shape paper teeth: refused, not ignored
    (["--teeth", "paper", "--tilt", "0.5"], "--tilt = 0.5: shapes generated teeth only"),
    (["--teeth", "paper", "--corner", "tooth"], "--corner = tooth: shapes generated teeth only"),
    (["--teeth", "paper", "--pressure-angle", "25"], "--pressure-angle = 25: shapes generated"),
    (["--teeth", "paper", "--clearance", "0.3"], "--clearance = 0.3: shapes generated"),
])
def test_bad_input_one_line_exit_2_nothing_written(cli, tmp_path, args, param):
    out = tmp_path / "out"
    result = cli("gears", *args, "--out", out)
    assert param in error_line(result), result.stderr
    assert "Traceback" not in result.stderr
    assert not out.exists()


def test_unwritable_output_is_one_line(cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    result = cli("gears", "--out", blocker / "sub")
    line = error_line(result, code=2)                     # a bad output path is bad input
    assert f"--out = {blocker / 'sub'}: cannot be written ({blocker}: is a file, not a folder)" in line
    assert blocker.read_text() == "not a folder"


def test_generated_teeth_roll_at_the_center_distance_and_mount_at_the_install_distance(cli, tmp_path):
    """--center-distance is where the pitch curves roll, --install-distance where the pair is
    mounted and checked. Off the rolling distance the pitch curves do not roll: 25 um
    farther (opening backlash) or closer breaks the bounds; both are refused with the
    remedy, which applied is written, stored and re-checked on the plate there."""
    farther = cli("gears", "--profile", "desk-demo", "--center-distance", "72.1", "--out", tmp_path / "a")
    line = error_line(farther)
    # named for the option given, the installed distance it leads to stated
    assert line.startswith("wheelstep: error: --center-distance = 72.1: with it, install-distance = "
                           "72.125 fails: the pair would mesh outside")
    assert "0.025 mm farther than the pitch curves roll (72.1 mm)" in line
    assert line.endswith("use --install-distance 72.1")
    closer = cli("gears", "--profile", "desk-demo", "--center-distance", "72.15", "--out", tmp_path / "b")
    line = error_line(closer)
    # the wheel's tip clearance lets it run 25 um closer, off its law: the figures say so
    assert "the pair would mesh outside the bounds" in line and "interfere" not in line
    assert "0.025 mm closer than the pitch curves roll (72.15 mm)" in line
    assert line.endswith("use --install-distance 72.15")
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
    out = tmp_path / "c"
    assert cli("gears", "--profile", "desk-demo", "--center-distance", "72.1", "--install-distance",
               "72.1", "--out", out, "-q").exit_code == 0
    report = json.loads((out / "gears.json").read_text())
    assert report["parameters"]["center_distance"] == report["parameters"]["install_distance"] == 72.1
    assert report["generated"]["rolling_center_distance_mm"] == 72.1
    assert report["generated"]["backlash"]["center_distance_opening_mm"] == 0.0
    assert report["meshing"]["distance_mm"] == 72.1
    from wheelstep_cli.formats.mesh_read import read_3mf_objects

    for obj in read_3mf_objects(out / "gears.3mf", "x"):
        assert (obj.metadata["center_distance"], obj.metadata["install_distance"]) == ("72.1", "72.1")
    checked = cli("mesh-check", out / "gears.3mf", "--json")
    assert checked.exit_code == 0, checked.stderr
    (measured,) = json.loads(checked.stdout)["pairs"]
    assert measured["distance_mm"] == 72.1
    assert measured["drive"]["F_i_total_um"] == pytest.approx(report["meshing"]["drive"]["F_i_total_um"],
                                                             abs=0.5)


def test_a_pair_mounted_so_close_that_it_interferes_is_the_distance_s_error(cli, tmp_path):
    """Mounted far enough inside its rolling distance the pair interferes: the cause is the
    distance the user gave, refused like a pair mounted farther off (exit 2, one line naming
    the option, the remedy), not as a failed check (exit 1)."""
    closer = cli("gears", "--profile", "desk-demo", "--center-distance", "72.4", "--out", tmp_path / "a")
    line = error_line(closer, code=2)
    assert line.startswith("wheelstep: error: --center-distance = 72.4: with it, install-distance = "
                           "72.125 fails: the teeth interfere at ")
    assert "0.275 mm closer than the pitch curves roll (72.4 mm)" in line
    assert line.endswith("use --install-distance 72.4 (for more play, more backlash)")
    given = cli("gears", "--profile", "desk-demo", "--center-distance", "72.4", "--install-distance",
                "72.125", "--out", tmp_path / "a")
    assert error_line(given, code=2).startswith("wheelstep: error: --install-distance = 72.125: the teeth "
                                                "interfere at ")
    assert not (tmp_path / "a").exists()


def test_a_pair_mounted_closer_than_its_tip_clearance_is_refused_before_it_is_cut(cli, tmp_path):
    """The desk preset's installed distance (72.125) with --center-distance 80: mounted 7.9 mm
    inside the rolling distance the tips run into the space bottoms; found after a build and a
    meshing check (85 s), it is refused from the tip clearance before any tooth is cut, with
    the remedy, which applied is written with that tip clearance."""
    line = error_line(cli("gears", "--profile", "desk-demo", "--center-distance", "80", "--out", tmp_path / "a"))
    assert line.startswith("wheelstep: error: --center-distance = 80: with it, install-distance = 72.125 fails: "
                           "mounted 7.875 mm closer than the pitch curves roll (80 mm), more than the tip "
                           "clearance "), line
    assert line.endswith(" mm: tips run into the shallower spaces' bottoms where they cross the line of centres; "
                         "nothing written; use --install-distance 80"), line
    assert not (tmp_path / "a").exists()
    applied = cli("gears", "--profile", "desk-demo", "--center-distance", "80", "--install-distance", "80",
                  "--format", "stl", "--out", tmp_path / "b", "--json", "-q")
    assert applied.exit_code == 0, applied.stderr
    spaces = json.loads(applied.stdout)["generated"]["tip_clearance"]
    said = float(line.split("more than the tip clearance ")[1].split(" mm")[0])
    assert said == pytest.approx(min(spaces["pinion_spaces_mm"], spaces["wheel_spaces_mm"]), abs=5e-4)


def test_a_module_sets_where_the_presets_pair_rolls_and_the_plate_is_checked_there(cli, tmp_path):
    """--module on the desk preset (which gives an installed distance): the module's distance
    replaces the preset's (generated teeth roll and are mounted where the module fits), and
    mesh-check of the written plate mounts the pair there from its metadata."""
    out = tmp_path / "m"
    result = cli("gears", "--profile", "desk-demo", "--module", "1.25", "--out", out, "--json", "-q")
    assert result.exit_code == 0, result.stderr
    report = json.loads(result.stdout)
    rolling = report["generated"]["rolling_center_distance_mm"]
    assert rolling > 73.0 and report["generated"]["module_mm"] == pytest.approx(1.25)
    assert report["parameters"]["install_distance"] == report["meshing"]["distance_mm"] == rolling
    checked = cli("mesh-check", out / "gears.3mf", "--json")
    assert checked.exit_code == 0, checked.stderr
    (measured,) = json.loads(checked.stdout)["pairs"]
    assert measured["distance_mm"] == pytest.approx(rolling, abs=1e-6)
    assert measured["interference"] is False


def test_a_pair_taller_than_the_printer_is_refused_before_any_tooth_is_cut(cli, tmp_path, monkeypatch):
    """The printer's height is checked before the teeth are generated (the pair would be
    refused by its plate anyway, after seconds of work), naming --thickness and the limit."""
    import wheelstep_cli.parts.gear_pair as gear_pair

    def no_build(spec):
        raise AssertionError("the teeth were cut before the height was checked")

    monkeypatch.setattr(gear_pair, "_build", no_build)
    for args, printer in ((["--thickness", "300", "--printer", "fdm-0.4-pla", "--format", "stl"], "fdm-0.4-pla"),
                          (["--thickness", "1e5"], None),
                          # a fit is for the default printer's band: drawn for that printer
                          (["--thickness", "300", "--fit", "auto", "--format", "stl"], None),
                          # both gears carry the hub above their top face
                          (["--thickness", "200", "--hub-d", "40", "--hub-length", "60"], None)):
        result = cli("gears", *args, "--out", tmp_path / "tall")
        assert result.exit_code == 2, result.stderr
        line = error_line(result)
        assert line.startswith(f"wheelstep: error: --thickness = {args[1]}: makes part 'pinion'")
        assert "mm tall" in line and "more than the" in line and (printer is None or f"printer '{printer}'" in line)
        # with a hub the line says what the height is made of
        assert ("260.0 mm tall (its 200 mm plate and 60 mm hub), more" in line) == ("--hub-d" in args)
        assert ("(the default printer; --printer chooses another" in line) == (printer is None)
        assert not (tmp_path / "tall").exists()
    # only the hub made it too tall: the line names the hub length, with the same note
    line = error_line(cli("gears", "--hub-d", "40", "--hub-length", "300", "--out", tmp_path / "tall"))
    assert line.startswith("wheelstep: error: --hub-length = 300: with it, thickness = 10 (the default) fails: makes "
                           "part 'pinion' 310.0 mm tall"), line
    assert line.endswith("(the default printer; --printer chooses another, --format stl writes no plate); "
                         "nothing written; use --hub-length 240")
    assert not (tmp_path / "tall").exists()


def test_a_pair_too_tall_is_offered_the_plate_the_printer_prints_and_that_is_written(cli, tmp_path):
    """The height refusal offers the thickness that makes the part as tall as the printer
    prints (the hub kept, rounded down to 0.1 mm); applied, the pair is written that tall."""
    import trimesh

    args = ["gears", "--thickness", "250", "--hub-d", "40", "--hub-length", "8.20005", "--printer", "fdm-0.4-pla"]
    line = error_line(cli(*args, "--out", tmp_path / "tall"))
    assert "mm tall (its 250 mm plate and 8.20005 mm hub)" in line, line
    # a 50 um of hub off the tenths: 241.8 would stand 250.00005 mm tall
    assert line.endswith("; nothing written; use --thickness 241.7"), line
    assert not (tmp_path / "tall").exists()
    written = cli(*with_remedy(args, remedy_in(line)), "--format", "stl", "--out", tmp_path / "fits")
    assert written.exit_code == 0, written.stderr
    height = np.ptp(trimesh.load(tmp_path / "fits" / "pinion.stl").vertices[:, 2])
    assert 249.8 < height <= 250.0
    # a hub that leaves too thin a plate: the hub lowered is offered, not a plate the spec refuses
    args = ["gears", "--hub-d", "40", "--hub-length", "249.7", "--printer", "fdm-0.4-pla"]
    line = error_line(cli(*args, "--out", tmp_path / "tall"))
    assert line.endswith("; nothing written; use --hub-length 240"), line
    assert cli(*with_remedy(args, remedy_in(line)), "--dry-run", "--out", tmp_path / "hub").exit_code == 0


def test_a_pair_too_large_for_the_default_printers_bed_says_so_and_how_to_write_it(cli, tmp_path):
    """--module 3 draws a 296 mm wheel: with no --printer it is refused for the default
    printer's bed, saying that it is the default printer, that --format stl writes no plate,
    and the smaller pair the bed holds; each way applied, the pair is written."""
    line = error_line(cli("gears", "--module", "3", "--out", tmp_path / "big"))
    assert line.startswith("wheelstep: error: --module = 3: with it, part 'wheel' is "), line
    assert ", larger than the bed of printer 'fdm-0.4-pla' (256 x 256 mm" in line, line
    assert "(the default printer; --printer chooses another, --format stl writes no plate); nothing written; use " in line
    assert not (tmp_path / "big").exists()
    written = cli("gears", "--module", "3", "--format", "stl", "--out", tmp_path / "big")
    assert written.exit_code == 0, written.stderr
    smaller = cli(*with_remedy(["gears", "--module", "3"], remedy_in(line)), "--out", tmp_path / "smaller")
    assert smaller.exit_code == 0, smaller.stderr
    assert sorted(p.name for p in (tmp_path / "smaller").glob("*.3mf")) == ["gears-1.3mf", "gears-2.3mf"]


def test_a_pair_exactly_as_tall_as_the_printer_prints_is_not_refused_early(cli, tmp_path):
    """The early height check sees the thickness as the meshes hold it (float32), as the
    plate's check does: a millionth of a millimetre over the printer's height rounds to it."""
    from wheelstep_cli.config.profiles import load_printer_profile

    tallest = load_printer_profile("resin-0.05-standard").max_height
    result = cli("gears", "--profile", "desk-demo", "--thickness", f"{tallest + 1e-6:.6f}", "--printer",
                 "resin-0.05-standard", "--format", "stl", "--dry-run", "-q", "--out", tmp_path / "o")
    assert result.exit_code == 0, result.stderr


def test_a_pair_that_tolerates_no_closer_mounting_is_warned_of(cli, tmp_path):
    """--clearance 0 leaves the wheel's spaces no room below the pinion's tips, --backlash 0.02
    next to no play between the flanks: written (they mesh where designed), each with a warning
    that a printed frame cannot hold that distance; the default pair (0.047 mm) gets none."""
    for option, value in (("--clearance", "0"), ("--backlash", "0.02")):
        result = cli("gears", option, value, "--format", "stl", "--dry-run", "--out", tmp_path / "o")
        assert result.exit_code == 0, result.stderr
        assert result.stderr.startswith("WARNING: mounted 0.00") and "--" not in result.stderr
    assert cli("gears", "--format", "stl", "--dry-run", "--out", tmp_path / "o").stderr == ""


def test_a_written_pair_that_interferes_is_warned_of_with_its_overlap_in_um2(cli, tmp_path):
    """--allow-interference on a pair with no play: written, warned of with the refusal's own
    words (an overlap under a thousandth of a mm2 in um2, never '0.000 mm2')."""
    result = cli("gears", "--backlash", "0", "--allow-interference", "--format", "stl", "--dry-run",
                 "--out", tmp_path / "o")
    assert result.exit_code == 0, result.stderr
    warning = next(line for line in result.stderr.splitlines() if "interfere" in line)
    assert warning.startswith("WARNING: the teeth interfere at ") and " um2); pointwise" in warning, warning


def test_the_tip_clearance_said_is_the_shallower_gears_spaces(cli, tmp_path):
    """A longer addendum leaves the pinion's spaces shallower below the wheel's tips than the
    wheel's below the pinion's: the mounting line gives that smaller clearance, the one that
    bounds how much closer the pair may be mounted."""
    result = cli("gears", "--addendum", "1.2", "--format", "stl", "--dry-run", "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    report = json.loads(result.stdout)
    spaces = report["generated"]["tip_clearance"]
    assert spaces["pinion_spaces_mm"] < spaces["wheel_spaces_mm"]
    assert report["meshing"]["mounting"]["tip_clearance_mm"] == pytest.approx(spaces["pinion_spaces_mm"])


def test_the_mounting_line_gives_each_gears_tip_clearance(cli, tmp_path):
    """--clearance 0.5 deepens the wheel's spaces only; the line gave the shallower one (the
    pinion's, 0.25 module), the same as without the option, so the option looked ignored:
    it gives both, as gears.json's mounting record and the generated teeth state them."""
    result = cli("gears", "--clearance", "0.5", "--format", "stl", "--dry-run", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    report = json.loads(cli("gears", "--clearance", "0.5", "--format", "stl", "--dry-run", "--json",
                            "--out", tmp_path).stdout)
    spaces, mounting = report["generated"]["tip_clearance"], report["meshing"]["mounting"]
    assert spaces["wheel_spaces_mm"] == pytest.approx(2.0 * spaces["pinion_spaces_mm"])
    for gear in ("pinion", "wheel"):
        assert mounting[f"{gear}_spaces_mm"] == pytest.approx(spaces[f"{gear}_spaces_mm"])
    line = next(s for s in result.stdout.splitlines() if s.strip().startswith("mounting:"))
    assert line.endswith(f"; tip clearance {spaces['pinion_spaces_mm']:.3f} mm in the pinion's spaces, "
                         f"{spaces['wheel_spaces_mm']:.3f} mm in the wheel's (the wheel's set by --clearance)"), line


def test_the_no_closer_mounting_warning_says_what_the_mounting_line_says(cli, tmp_path):
    """With next to no backlash the mounting line says the outlines come within its
    resolution or overlap; the warning said "mounted 0.000 mm closer the teeth meet"."""
    result = cli("gears", "--backlash", "0.01", "--out", tmp_path / "o")
    assert result.exit_code == 0, result.stderr
    mounting = next(line for line in result.stdout.splitlines() if line.strip().startswith("mounting:"))
    assert "come within" in mounting and "or overlap" in mounting, mounting
    assert ("WARNING: mounted any closer than designed the teeth may meet (see 'mounting')" in result.stderr), \
        result.stderr


@pytest.mark.parametrize("command", ["gears", "pitch"])
def test_the_strut_given_as_r_min_is_the_strut_it_sizes(cli, tmp_path, command):
    """--rmin R sizes c = R - a + 4b, as shoe and kinematics take it: the same tables as --c."""
    args = ["--json", "-q"] + (["--z", "54", "--dry-run", "--out", tmp_path / "o"] if command == "gears" else [])
    by_r_min = cli(command, "--rmin", "30", *args)
    by_c = cli(command, "--c", "370", *args)
    assert by_r_min.exit_code == 0 and by_c.exit_code == 0, by_r_min.stderr + by_c.stderr
    assert json.loads(by_r_min.stdout)["parameters"]["c"] == 370
    assert json.loads(by_r_min.stdout) == json.loads(by_c.stdout)


def test_a_refusal_shared_by_the_strut_names_r_min_when_it_is_given_so(cli, tmp_path):
    """A rule the strut shares the blame for (the installed distance sizes the pair, c the
    law) names --rmin when the command line gives the strut as R_min, as it names --c."""
    for flag, value in (("--c", "370"), ("--rmin", "30")):
        line = error_line(cli("gears", flag, value, "--install-distance", "8", "--dry-run", "--out", tmp_path / "o"))
        assert line.startswith(f"wheelstep: error: {flag} = {value}: with it, bore = 8 (the default) fails: "
                               "must be < "), line
