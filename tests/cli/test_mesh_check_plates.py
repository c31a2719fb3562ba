"""`gears` lays the pair out on the printer's bed; `mesh-check PLATE.3mf` finds the pair by its
metadata and reproduces what `gears` measured; parts too large or tall are refused."""

import json
import re

import numpy as np
import pytest

from tests.helpers.clicheck import error_line
from wheelstep_cli.formats.mesh_read import read_3mf_objects


@pytest.fixture(scope="module")
def desk_pair(tmp_path_factory):
    from wheelstep_cli.cli import run

    out = tmp_path_factory.mktemp("desk")
    assert run(["gears", "--profile", "desk-demo", "--out", str(out), "-q"]) == 0
    return out


def _placed(obj) -> np.ndarray:
    return np.column_stack([obj.vertices, np.ones(len(obj.vertices))]) @ obj.transform


def test_mesh_check_on_gears_3mf_reproduces_the_gears_figures(desk_pair, cli):
    stored = json.loads((desk_pair / "gears.json").read_text())["meshing"]
    result = cli("mesh-check", desk_pair / "gears.3mf", "--json")
    assert result.exit_code == 0, result.stderr
    (measured,) = json.loads(result.stdout)["pairs"]
    assert measured["pair"] == "gears" and measured["interference"] == stored["interference"]
    for key in ("backlash_min_mm", "backlash_max_mm"):
        assert measured[key] == pytest.approx(stored[key], rel=0.01), key
    text = cli("mesh-check", desk_pair / "gears.3mf", "--pair", "gears", "--samples", "160")
    assert text.exit_code == 0 and "pair gears" in text.stdout


def test_a_plates_two_objects_named_are_checked_with_the_design_they_carry(desk_pair, cli, tmp_path):
    """FILE.3mf:NAME of a wheelstep plate's pinion and wheel, no design option given: the
    design in their metadata (the desk pair at 72.125 mm; it was checked at the default 144
    and refused as no pair there). Named the other way round they are refused by their
    metadata; with design options the options give the design, as for two meshes."""
    plate = desk_pair / "gears.3mf"
    result = cli("mesh-check", f"{plate}:pinion", f"{plate}:wheel", "--samples", "160", "--json")
    assert result.exit_code == 0, result.stderr
    (measured,) = json.loads(result.stdout)["pairs"]
    assert measured["distance_mm"] == 72.125 and measured["pinion"] == f"{plate}:pinion"
    assert measured["pinion_teeth"] == 42 and not measured["interference"]
    line = error_line(cli("mesh-check", f"{plate}:wheel", f"{plate}:pinion", "--plot", tmp_path / "p.png"))
    assert line == (f"wheelstep: error: pinion = {plate}:wheel: is a wheel by its wheelstep:part metadata (and "
                    f"{plate}:pinion a pinion): give the pinion first, then the wheel (PINION WHEEL)"), line
    assert not (tmp_path / "p.png").exists()
    line = error_line(cli("mesh-check", f"{plate}:pinion", f"{plate}:pinion"))
    assert line == (f"wheelstep: error: wheel = {plate}:pinion: is a pinion by its wheelstep:part metadata, as "
                    "is the pinion given: name a wheel's object (FILE.3mf:NAME)"), line
    other = tmp_path / "other"
    assert cli("gears", "--profile", "desk-demo", "--z", "44", "--format", "3mf", "--out", other,
               "-q").exit_code == 0
    line = error_line(cli("mesh-check", f"{plate}:pinion", f"{other / 'gears.3mf'}:wheel"))
    assert line.startswith(f"wheelstep: error: wheel = {other / 'gears.3mf'}:wheel: carries another design than "
                           "the pinion of pair 'gears': z = 44 (the pinion's 42)"), line
    given = cli("mesh-check", f"{plate}:pinion", f"{plate}:wheel", "--profile", "desk-demo", "--samples",
                "160", "--json")
    assert given.exit_code == 0 and "pairs" not in json.loads(given.stdout), given.stderr


def test_gears_3mf_objects_keep_their_frame_and_lie_inside_the_bed(desk_pair):
    objects = {o.metadata["part"]: o for o in read_3mf_objects(desk_pair / "gears.3mf", "x")}
    assert set(objects) == {"pinion", "wheel"}
    for obj in objects.values():
        # the axis stays at the frame's origin: the bore is centred there
        assert np.hypot(*obj.vertices[:, :2].mean(axis=0)) < 0.2 * np.ptp(obj.vertices[:, 0])
        placed = _placed(obj)
        assert placed[:, :2].min() >= 5.0 - 1e-6 and placed[:, :2].max() <= 256 - 5.0 + 1e-6
        assert placed[:, 2].min() == pytest.approx(0.0, abs=1e-6)
        assert obj.metadata["install_distance"] and obj.metadata["z"]


@pytest.mark.parametrize("args, param", [
    (["--distance", "70"], "--distance"), (["--a", "30"], "--a"), (["--pair", "nope"], "--pair")])
def test_plate_mode_refuses_design_options_and_unknown_pairs(desk_pair, cli, args, param):
    result = cli("mesh-check", desk_pair / "gears.3mf", *args)
    assert result.exit_code == 2 and param in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_two_meshes_that_are_not_a_pair_are_refused(desk_pair, cli, tmp_path):
    other = tmp_path / "other"
    assert cli("shoe", "--profile", "desk-demo", "--out", other, "-q").exit_code == 0
    for args in ([other / "shoe.3mf"], [desk_pair / "gears.3mf", other / "shoe.3mf"]):
        result = cli("mesh-check", *args)
        assert result.exit_code == 2, result.stderr
        assert len(result.stderr.strip().splitlines()) == 1
        assert "gear pair" in result.stderr


def test_two_mesh_form_still_works(desk_pair, cli):
    result = cli("mesh-check", desk_pair / "pinion.stl", desk_pair / "wheel.stl", "--profile",
                 "desk-demo", "--samples", "160", "--pair", "x")
    assert result.exit_code == 2 and "--pair" in result.stderr


@pytest.mark.parametrize("command, args, param", [
    ("gears", ["--profile", "desk-demo", "--thickness", "300"], "--thickness"),
    ("shoe", ["--profile", "desk-demo", "--width", "300"], "--width")])
def test_part_taller_than_the_printer_prints_is_refused(cli, tmp_path, command, args, param):
    result = cli(command, *args, "--out", tmp_path / "out")
    assert result.exit_code == 2 and param in result.stderr and "250" in result.stderr
    assert not (tmp_path / "out").exists()


def test_full_scale_pair_goes_on_two_plates_and_checks_as_a_pair(cli, tmp_path):
    out = tmp_path / "big"
    result = cli("gears", "--z", "48", "--out", out, "-q", "--json")
    assert result.exit_code == 0, result.stderr
    stored = json.loads(result.stdout)["meshing"]
    assert not (out / "gears.3mf").exists()
    plates = [out / "gears-1.3mf", out / "gears-2.3mf"]
    for plate in plates:
        (obj,) = read_3mf_objects(plate, "x")
        placed = _placed(obj)
        assert placed[:, :2].min() >= 5.0 - 1e-6 and placed[:, :2].max() <= 251.0 + 1e-6
    check = cli("mesh-check", *plates, "--json", "--samples", "768")
    assert check.exit_code == 0, check.stderr
    (measured,) = json.loads(check.stdout)["pairs"]
    assert measured["interference"] == stored["interference"]
    assert measured["backlash_max_mm"] == pytest.approx(stored["backlash_max_mm"], rel=0.01)
    # one of the two plates alone: told which gear it holds and to name the other plate too
    line = error_line(cli("mesh-check", plates[0]))
    assert "holds no gear pair" in line and "it holds only the " in line
    assert "of pair '" in line and "name the plate with the other gear too" in line


def test_the_same_mesh_twice_is_refused_before_any_work(desk_pair, cli, tmp_path):
    wheel = desk_pair / "wheel.stl"
    copy = tmp_path / "copy.stl"
    copy.write_bytes(wheel.read_bytes())
    for pinion in (wheel, copy):
        result = cli("mesh-check", pinion, wheel, "--profile", "desk-demo", "--samples", "160")
        line = error_line(result)
        assert line.startswith(f"wheelstep: error: wheel = {wheel}: is the same mesh as the pinion"), line


def test_two_wheels_or_two_pinions_are_refused_before_any_work(desk_pair, cli, tmp_path):
    """Two different wheels (not a pinion and its wheel) overlap everywhere; their check ran
    for minutes. Refused from the outlines' sizes against the centre distance, one line,
    naming the file whose size is not its part's (the other one's fits)."""
    from wheelstep_cli.formats.mesh_read import read_mesh
    from wheelstep_cli.formats.stl import stl_bytes

    for part in ("wheel", "pinion"):
        vertices, faces = read_mesh(str(desk_pair / f"{part}.stl"), part)
        other = tmp_path / f"other-{part}.stl"          # another such part, 1 % larger
        other.write_bytes(stl_bytes(vertices * [1.01, 1.01, 1.0], faces))
        result = cli("mesh-check", desk_pair / f"{part}.stl", other, "--profile", "desk-demo")
        line = error_line(result)
        # two wheels: the one given as the pinion is not one; two pinions: the one given as the wheel
        named = (f"pinion = {desk_pair / 'wheel.stl'}: its radius by area 47.7 mm is not the pinion's"
                 if part == "wheel" else f"wheel = {other}: its radius by area 24.1 mm is not the wheel's")
        assert line.startswith(f"wheelstep: error: {named} of a pair at the centre distance 72.125 mm"), line
        assert "two wheels or two pinions" in line
    # a pinion and its wheel (sizes in the law's ratio) at a distance far off: the distance
    # named, given or the design's
    for given in (["--distance", "100"], []):
        far = error_line(cli("mesh-check", desk_pair / "pinion.stl", desk_pair / "wheel.stl", *given))
        # not given: the help's default, marked as such (as every refusal marks one)
        assert far == (f"wheelstep: error: --distance = {given[1] if given else '144 (the default)'}: the "
                       "pinion and the "
                       "wheel given are a pair for about 71.6 mm (radii by area 23.8 + 47.7 mm), more than "
                       "20 % off: give the distance they were designed for, or their design's --profile"), far
    # neither fits, nor are they in the law's ratio: said of both, as the sizes that do not add up
    odd = tmp_path / "odd-wheel.stl"
    vertices, faces = read_mesh(str(desk_pair / "wheel.stl"), "wheel")
    odd.write_bytes(stl_bytes(vertices * [1.6, 1.6, 1.0], faces))
    far = error_line(cli("mesh-check", desk_pair / "pinion.stl", odd, "--distance", "200"))
    assert far.startswith(f"wheelstep: error: wheel = {odd}: its radius by area ") and \
        "and the pinion's 23.8 mm add to " in far and "not the centre distance 200 mm" in far, far
    apart = cli("mesh-check", desk_pair / "pinion.stl", desk_pair / "wheel.stl", "--profile",
                  "desk-demo", "--samples", "160", "--distance", "75")
    assert apart.exit_code in (0, 1), apart.stderr       # a real pair a little apart: checked


def test_a_part_without_the_teeth_of_the_pair_is_refused_though_the_sizes_add_up(desk_pair, cli, tmp_path):
    """A shoe or a plain disc of the right size passed the size checks and was reported as
    interfering at every pose: teeth are counted along each pitch curve first."""
    import trimesh

    shoe = tmp_path / "shoe"
    assert cli("shoe", "--out", shoe, "--format", "stl", "-q").exit_code == 0
    result = cli("mesh-check", desk_pair / "pinion.stl", shoe / "shoe.stl", "--profile", "desk-demo")
    # (the shoe, drawn about its strut pivot, does not even surround the axis)
    assert error_line(result).startswith(f"wheelstep: error: wheel = {shoe / 'shoe.stl'}: does not surround (0, 0)")
    ring = tmp_path / "ring.stl"
    ring.write_bytes(trimesh.creation.annulus(r_min=20.0, r_max=47.9, height=6.0, sections=256).export(file_type="stl"))
    # (a plain ring crosses the non-circular pitch curve a few times: counted as that many teeth)
    assert re.fullmatch(
        f"wheelstep: error: wheel = {re.escape(str(ring))}: has [0-9] teeth? along its pitch curve, not the 84 "
        "that the pinion's 42 need under the law: give the wheel of this pinion's pair, both as written "
        r"\(a gear turned about its axis is counted against the wrong stretch of its pitch curve\), and its "
        r"design \(--profile, --a/--b/--c, --law-csv\)",
        error_line(cli("mesh-check", desk_pair / "pinion.stl", ring, "--profile", "desk-demo")))
    disc = tmp_path / "disc.stl"
    disc.write_bytes(trimesh.creation.cylinder(radius=24.0, height=6.0, sections=256).export(file_type="stl"))
    line = error_line(cli("mesh-check", disc, desk_pair / "wheel.stl", "--profile", "desk-demo"))
    # (a disc crosses the non-circular pitch curve once or twice per lobe)
    assert re.match(f"wheelstep: error: pinion = {re.escape(str(disc))}: has [0-2] teeth? along the pitch "
                    "curve of the law; a pinion has at least 6: give the pinion mesh of a gear pair", line), line
    # the pair itself: its teeth counted as the law needs them, checked
    assert cli("mesh-check", desk_pair / "pinion.stl", desk_pair / "wheel.stl", "--profile", "desk-demo",
               "--samples", "160", "-q").exit_code == 0


def test_two_plates_each_holding_a_pair_are_both_checked(desk_pair, cli, tmp_path, monkeypatch):
    """Two plates of two `gears` runs hold a pair each, of one pair id: both pairs are checked
    (they were refused as 'not a gear pair'); one plate named twice is checked once."""
    other = tmp_path / "other"
    assert cli("gears", "--profile", "desk-demo", "--z", "44", "--format", "3mf", "--out", other,
               "-q").exit_code == 0
    result = cli("mesh-check", desk_pair / "gears.3mf", other / "gears.3mf", "--samples", "160", "--json")
    assert result.exit_code == 0, result.stderr
    pairs = json.loads(result.stdout)["pairs"]
    assert [p["pinion_teeth"] for p in pairs] == [42, 44]
    assert [p["pinion"] for p in pairs] == [f"{desk_pair / 'gears.3mf'}:pinion", f"{other / 'gears.3mf'}:pinion"]
    # a plot draws one pair: the refusal names the ids to choose from
    line = error_line(cli("mesh-check", desk_pair / "gears.3mf", other / "gears.3mf", "--plot",
                          tmp_path / "pair.png"))
    assert line.endswith(f"draws one pair: add --pair ID, one of 'gears', 'gears ({other / 'gears.3mf'})'")
    monkeypatch.chdir(other)
    twice = cli("mesh-check", "gears.3mf", "./gears.3mf", "--samples", "160", "--json")
    assert twice.exit_code == 0, twice.stderr
    assert len(json.loads(twice.stdout)["pairs"]) == 1


@pytest.mark.parametrize("printer", [None, "fdm-0.4-petg"])
def test_a_band_that_jams_is_warned_of_on_stderr(desk_pair, cli, printer):
    """The desk pair drawn without clearance jams over the FDM band: the report says JAMS among
    its lines, and a warning on stderr names the cases (it was easy to miss at exit 0). The
    command it suggests fits to the same printer's band (it named none: the default's)."""
    given = ["--printer", printer] if printer else []
    result = cli("mesh-check", desk_pair / "pinion.stl", desk_pair / "wheel.stl", "--profile", "desk-demo",
                 "--tolerance", *given, "--samples", "384", "--json")
    assert result.exit_code == 0, result.stderr
    band = json.loads(result.stdout)["tolerance"]
    jammed = [case["case"] for case in band["cases"] if case["jams"]]
    assert band["jams"] and jammed
    assert result.stderr.strip().splitlines()[-1] == (
        f"WARNING: over the band of {printer or 'fdm-0.4-pla'} the pair jams in {len(jammed)} of 4 cases "
        f"({'; '.join(jammed)}): printed there it may not turn; `wheelstep gears"
        f"{' --printer ' + printer if printer else ''} --fit auto` with the pair's design options draws the "
        "teeth to clear the band (if the inset leaves the teeth too thin, its refusal names the tooth count "
        "that prints)")
    # a jammed case predicts no backlash at all (its figure is an estimate where teeth cannot go)
    from wheelstep_cli.parts.gcode_check import least_backlash_range

    assert least_backlash_range(band)[0] == 0.0


def test_too_few_poses_for_the_figures_are_refused_with_the_least_that_serves(desk_pair, cli):
    """16 poses over the desk pair's 21 teeth a period gave f'i 0.0 um: the band-limited figures
    need more than 6 poses per tooth pitch (3 tooth harmonics). The least is named, and it serves."""
    for args in ([desk_pair / "pinion.stl", desk_pair / "wheel.stl", "--profile", "desk-demo"],
                 [desk_pair / "gears.3mf"]):
        line = error_line(cli("mesh-check", *args, "--samples", "126"))
        assert line == ("wheelstep: error: --samples = 126: must be >= 127 for a pinion of 42 teeth (more than 6 "
                        "poses per tooth pitch: fewer cannot hold the 3 tooth harmonics of the figures)")
    result = cli("mesh-check", desk_pair / "gears.3mf", "--samples", "127", "--json")
    assert result.exit_code == 0, result.stderr
    (measured,) = json.loads(result.stdout)["pairs"]
    assert measured["drive"]["f_i_tooth_um"] > 0.0


def test_one_gear_alone_is_told_to_name_its_wheel(desk_pair, cli):
    """A single STL (or one 3MF object) is half a pair: it was taken for a plate and refused
    for --profile, 'which comes from the plate's metadata'."""
    for one in (desk_pair / "pinion.stl", f"{desk_pair / 'gears.3mf'}:pinion"):
        line = error_line(cli("mesh-check", one, "--profile", "desk-demo"))
        assert line == (f"wheelstep: error (wheelstep mesh-check): Missing argument 'WHEEL': {one} is one "
                        "gear; give the wheel mesh after it (PINION WHEEL), or a plate (3MF) holding the pair")


def test_a_missing_file_named_alone_is_said_missing(cli, tmp_path):
    """As when two are named: the file is missing, before it is taken for a plate or half a pair."""
    other = tmp_path / "other.stl"
    for missing in ("nothere.3mf", "nothere.stl", "nothere.3mf:pinion"):
        given = f"{tmp_path / missing}"
        line = error_line(cli("mesh-check", given))
        assert line == f"wheelstep: error: pinion = {given}: no such file"
        assert line == error_line(cli("mesh-check", given, other))


def test_a_plot_over_a_users_file_is_refused_unless_forced(desk_pair, cli, tmp_path):
    mine = tmp_path / "mine.png"
    mine.write_bytes(b"the user's picture")
    args = ["mesh-check", desk_pair / "gears.3mf", "--samples", "160", "--plot", mine]
    assert "--plot = " in error_line(cli(*args))
    assert mine.read_bytes() == b"the user's picture"
    assert cli(*args, "--force").exit_code == 0
    assert mine.read_bytes().startswith(b"\x89PNG")


def _model_metadata(plate) -> dict[str, str]:
    import re
    import zipfile
    from xml.sax.saxutils import unescape

    model = zipfile.ZipFile(plate).read("3D/3dmodel.model").decode()
    head = model.split("<resources>")[0]
    return {k: unescape(v) for k, v in re.findall(r'<metadata name="wheelstep:([^"]+)">([^<]*)</metadata>', head)}


def test_a_bad_turns_in_a_plates_metadata_is_said_of_the_metadata(desk_pair, cli, tmp_path):
    """The plate's wheelstep:turns edited to 3: refused as its metadata, as other keys are,
    not as a --turns the user never typed."""
    import zipfile

    plate = tmp_path / "edited.3mf"
    with zipfile.ZipFile(desk_pair / "gears.3mf") as source, zipfile.ZipFile(plate, "w") as edited:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "3D/3dmodel.model":
                text = data.decode()
                assert '<metadata name="wheelstep:turns">2</metadata>' in text
                data = text.replace('<metadata name="wheelstep:turns">2</metadata>',
                                    '<metadata name="wheelstep:turns">3</metadata>').encode()
            edited.writestr(item, data)
    assert error_line(cli("mesh-check", plate)) == (
        f"wheelstep: error: pinion = {plate}: metadata turns = 3: must be 2 (balanced pinion) or 4 "
        "(one pinion turn per shoe)")


def test_a_plate_says_whether_its_parts_were_drawn_for_its_printer(desk_pair, cli, tmp_path):
    # no --printer: laid out on the default printer's bed with its slicer settings, drawn as designed
    plain = _model_metadata(desk_pair / "gears.3mf")
    assert plain["printer"] == "fdm-0.4-pla" and plain["compensated"].startswith("no: drawn as designed")
    out = tmp_path / "printed"
    printed = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--format", "3mf", "--out", out)
    assert printed.exit_code == 0, printed.stderr
    assert _model_metadata(out / "gears.3mf")["compensated"] == "yes"
    # the desk pair's default backlash is under the printer's tooth clearance: all of it is the
    # clearance, and a print a little larger than expected jams (exit 0 said nothing of it)
    report = json.loads((out / "gears.json").read_text())
    assert report["generated"]["backlash"]["normal_backlash_mm"] == pytest.approx(
        report["printer_geometry"]["tooth_clearance"])
    assert "WARNING: printed on 'fdm-0.4-pla' the teeth keep no play of their own" in printed.stderr


def test_the_pose_count_a_design_needs_is_the_one_run_and_printed(cli, tmp_path):
    """With n = 4 a 64-tooth pinion's shortest tooth pitch needs more than 1536 poses for 16
    (SPEC §10): gears and mesh-check on its plates run and print that count."""
    from wheelstep_cli.config.specs import GearPairSpec
    from wheelstep_cli.gears.meshing.check import default_pose_count

    need = default_pose_count(GearPairSpec(z=64, turns=4).law(), 64)
    assert need > 1536
    out = tmp_path / "p"
    made = cli("gears", "--teeth", "paper", "--z", "64", "--turns", "4", "--module", "1.2",
               "--allow-interference", "--out", out, "-q", "--json")
    assert made.exit_code == 0, made.stderr
    assert json.loads(made.stdout)["meshing"]["samples"] == need
    checked = cli("mesh-check", *sorted(out.glob("gears-*.3mf")))
    assert f", {need} poses over 360 deg of pinion" in checked.stdout.splitlines()[0]
    assert "interference: YES at " in checked.stdout and f" of {need} poses" in checked.stdout


def test_a_pair_drawn_for_other_pinion_turns_is_told_which(cli, tmp_path):
    """A --turns 4 pair checked as the default design (n = 2): its pinion counts 1 tooth along
    that law's pitch curve; the refusal says the two count as one pair's at n = 4 and to give
    -n 4 (it said to give the pinion of a gear pair); applied, the check passes."""
    out = tmp_path / "t4"
    assert cli("gears", "--turns", "4", "--z", "32", "--format", "stl", "--out", out, "-q").exit_code == 0
    meshes = [out / "pinion.stl", out / "wheel.stl"]
    line = error_line(cli("mesh-check", *meshes))
    assert line.endswith("but the two count as one pair's at 4: give -n 4"), line
    assert cli("mesh-check", *meshes, "-n", "4", "--samples", "768").exit_code == 0


@pytest.mark.parametrize("distance, cause", [
    ("75", "the teeth lose contact (mounted too far apart?)"),
    ("71.9", "the teeth interfere"),
])
def test_out_of_phase_says_what_the_check_found(desk_pair, cli, distance, cause):
    """A pair mounted far off its distance is out of phase for what the check found, not for a
    list of guesses (it said 'assembled a tooth off, or interfering' where contact was lost)."""
    result = cli("mesh-check", desk_pair / "pinion.stl", desk_pair / "wheel.stl", "--profile", "desk-demo",
                 "--distance", distance, "--samples", "384")
    assert result.exit_code == 1
    assert f"phase: OUT OF PHASE (the pair does not follow its law: {cause})" in result.stdout, result.stdout


def test_a_gear_moved_off_its_axis_is_told_to_give_it_in_its_own_frame(desk_pair, cli, tmp_path):
    """A pinion exported where it lay on a bed (30 mm off its axis) does not surround the
    origin the check turns it about: said of that file, before any pose is run."""
    import trimesh

    moved = trimesh.load(desk_pair / "pinion.stl")
    moved.apply_translation([30.0, 0.0, 0.0])
    moved.export(tmp_path / "pinion_on_bed.stl")
    line = error_line(cli("mesh-check", tmp_path / "pinion_on_bed.stl", desk_pair / "wheel.stl",
                          "--profile", "desk-demo"))
    assert line.startswith(f"wheelstep: error: pinion = {tmp_path / 'pinion_on_bed.stl'}: does not surround "
                           "(0, 0), where the check takes its axis (its section is centred near (30.0, 0.0) mm)")


def test_meshes_out_of_phase_with_the_law_given_are_told_to_give_the_options_they_were_made_with(desk_pair, cli):
    """Two meshes carry no law: the desk pair checked with a blend it was not cut for runs off
    that law, and the check says it was the law of the options given (a user who forgot
    --blend read only OUT OF PHASE); checked with its own design there is no such line."""
    meshes = [desk_pair / "pinion.stl", desk_pair / "wheel.stl"]
    wrong = cli("mesh-check", *meshes, "--profile", "desk-demo", "--blend", "10", "--samples", "384")
    assert wrong.exit_code == 1 and "phase: OUT OF PHASE" in wrong.stdout, wrong.stdout
    assert wrong.stderr.strip().splitlines()[-1].startswith(
        "WARNING: out of phase, checked against the law of the options given (mechanism, --turns, --blend, "
        "--law-csv)")
    # a small blend keeps the law in phase and puts the figures far outside the bounds (F'i 24
    # um): the same warning, without which the user read only OUTSIDE
    slight = cli("mesh-check", *meshes, "--profile", "desk-demo", "--blend", "3", "--samples", "384")
    assert "phase: in phase" in slight.stdout and "bounds: OUTSIDE" in slight.stdout, slight.stdout
    assert slight.stderr.strip().splitlines()[-1].startswith(
        "WARNING: outside the bounds: one cause is a law or a distance other than the pair was made for "
        "(checked against the options given: mechanism, --turns, --blend, --law-csv, at --distance 72.125 mm;")
    # mounted farther than it was made for (0.875 mm), in phase but far outside: the distance is named
    farther = cli("mesh-check", *meshes, "--profile", "desk-demo", "--distance", "73", "--samples", "384")
    assert "bounds: OUTSIDE" in farther.stdout, farther.stdout
    assert "a law or a distance other than the pair was made for" in farther.stderr
    assert "at --distance 73 mm;" in farther.stderr, farther.stderr
    right = cli("mesh-check", *meshes, "--profile", "desk-demo", "--samples", "384")
    assert right.exit_code == 0 and "in phase with the law" in right.stdout and "WARNING" not in right.stderr
    # mounted 0.1 mm closer the teeth interfere, and the warning names the distance as a cause
    closer = cli("mesh-check", *meshes, "--profile", "desk-demo", "--distance", "72.025", "--samples", "384")
    assert closer.exit_code == 1 and "phase: OUT OF PHASE" in closer.stdout, closer.stdout
    assert closer.stderr.strip().splitlines()[-1].endswith(
        "; teeth that interfere may also be mounted closer than the pair was made for (--distance 72.025 mm)")


def _edited_plate(source, plate, edit) -> None:
    """``source`` plate copied to ``plate`` with ``edit(model text) -> text`` applied."""
    import zipfile

    with zipfile.ZipFile(source) as old, zipfile.ZipFile(plate, "w") as new:
        for item in old.infolist():
            data = old.read(item)
            if item.filename == "3D/3dmodel.model":
                data = edit(data.decode()).encode()
            new.writestr(item, data)


def test_a_plate_whose_gears_are_mislabelled_is_refused_before_the_check(desk_pair, cli, tmp_path):
    """Labels swapped (the wheel object says pinion): refused as two swapped meshes are, exit 2,
    not run into 1149 interfering poses; two wheels of one pair id are refused, not one of
    them skipped; gears of two designs say which key differs."""
    pinion, wheel = ('<metadata name="wheelstep:part">pinion</metadata>',
                     '<metadata name="wheelstep:part">wheel</metadata>')
    swapped = tmp_path / "swapped.3mf"
    _edited_plate(desk_pair / "gears.3mf", swapped,
                  lambda t: t.replace(pinion, "@").replace(wheel, pinion).replace("@", wheel))
    result = cli("mesh-check", swapped)
    assert result.exit_code == 2
    assert error_line(result).startswith(f"wheelstep: error: pinion = {swapped}:wheel: is the larger gear")
    assert error_line(result).endswith("look swapped; swap the two objects' wheelstep:part metadata "
                                       "(pinion, wheel) or write the pair again")

    def second_wheel(text: str) -> str:
        start = text.index('<object id="2"')
        body = text[start:text.index("</object>", start) + len("</object>")]
        twin = body.replace('<object id="2"', '<object id="9"')
        return text.replace(body, body + twin).replace('<item objectid="2"', '<item objectid="9" transform='
                                                       '"1 0 0 0 1 0 0 0 1 0 0 0"/><item objectid="2"')
    twins = tmp_path / "twins.3mf"
    _edited_plate(desk_pair / "gears.3mf", twins, second_wheel)
    result = cli("mesh-check", twins)
    assert result.exit_code == 2
    assert error_line(result) == (f"wheelstep: error: pinion = {twins}: holds two wheels of pair 'gears' "
                                  "(objects 'wheel' and 'wheel'): remove one, or give it its own "
                                  "wheelstep:pair id")

    def moved_wheel(text: str) -> str:
        start = text.index('<object id="2"')
        return text[:start] + text[start:].replace(
            '<metadata name="wheelstep:install_distance">72.125</metadata>',
            '<metadata name="wheelstep:install_distance">73</metadata>', 1)
    other = tmp_path / "other.3mf"
    _edited_plate(desk_pair / "gears.3mf", other, moved_wheel)
    assert error_line(cli("mesh-check", other)) == (
        f"wheelstep: error: wheel = {other}: carries another design than the pinion of pair 'gears': "
        "install_distance = 73 (the pinion's 72.125)")


def test_a_report_named_as_a_mesh_is_said_to_be_no_mesh(desk_pair, cli):
    """gears.json named alone was told to 'give the wheel mesh after it', as if it were a gear."""
    report = desk_pair / "gears.json"
    for args, param in (([report], "pinion"), ([report, desk_pair / "wheel.stl"], "pinion"),
                        ([desk_pair / "pinion.stl", report], "wheel")):
        result = cli("mesh-check", *args)
        assert result.exit_code == 2
        assert error_line(result) == f"wheelstep: error: {param} = {report}: must be an .stl or .3mf file"
