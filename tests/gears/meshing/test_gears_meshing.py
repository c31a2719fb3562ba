"""`wheelstep gears` checks what it writes (SPEC §10) and `wheelstep mesh-check` on files."""

import json
import re

import pytest

from tests.helpers.clicheck import error_line


@pytest.fixture(scope="module")
def paper_pair(tmp_path_factory):
    from wheelstep_cli.cli import run

    out = tmp_path_factory.mktemp("paper")
    assert run(["gears", "--teeth", "paper", "--allow-interference", "--out", str(out)]) == 0
    return out


def test_default_paper_pair_is_refused_because_it_interferes(cli, tmp_path):
    out = tmp_path / "out"
    result = cli("gears", "--teeth", "paper", "--out", out)
    line = error_line(result, code=1)
    assert "interfere" in line and "nothing written" in line
    assert not out.exists() or not any(out.iterdir())


def test_allowed_pair_stores_the_check_and_prints_the_ripple(paper_pair, cli, tmp_path):
    report = json.loads((paper_pair / "gears.json").read_text())
    meshing = report["meshing"]
    assert meshing["interference"] is True and meshing["distance_mm"] == 144
    assert meshing["interfering_poses"] > 0 and meshing["max_overlap_area_mm2"] > 0
    # away from the handovers the paper teeth mesh with backlash of the order of j_n = 0.5 mm
    assert 0.2 < meshing["backlash_max_mm"] < 1.0
    assert meshing["diagnostic_pointwise_ripple_clear_pct"] > 1.0   # not conjugate: visible ripple
    result = cli("gears", "--teeth", "paper", "--allow-interference", "--format", "stl",
                 "--out", tmp_path)
    assert "hub speed ripple" in result.stdout and "interfere" in result.stderr
    # the backlash is said where it is measured, as mesh-check says it
    assert re.search(r"meshing at 144 mm: backlash [-\d.]+\.\.[-\d.]+ mm on the wheel pitch curve",
                     result.stdout), result.stdout


def test_mesh_check_on_the_written_files_agrees_with_gears_json(paper_pair, cli, tmp_path):
    stored = json.loads((paper_pair / "gears.json").read_text())["meshing"]
    png = tmp_path / "check.png"
    result = cli("mesh-check", paper_pair / "pinion.stl", paper_pair / "wheel.stl",
                 "--distance", "144", "--json", "--plot", png)
    assert result.exit_code == 1   # interference is a failed check
    measured = json.loads(result.stdout)
    assert measured["interfering_poses"] == pytest.approx(stored["interfering_poses"], abs=3)
    for key in ("backlash_max_mm", "diagnostic_pointwise_ripple_clear_pct", "max_overlap_area_mm2"):
        assert measured[key] == pytest.approx(stored[key], rel=0.02), key
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the 3MF objects, by default name and by explicit name, give the same answer
    # (the full-scale pair is on two plates, one gear each: gears-1.3mf holds the wheel)
    three = cli("mesh-check", paper_pair / "gears-2.3mf", f"{paper_pair / 'gears-1.3mf'}:wheel",
                "--distance", "144", "--json", "--samples", "384")
    stl = cli("mesh-check", paper_pair / "pinion.stl", paper_pair / "wheel.stl",
              "--json", "--samples", "384")
    a, b = json.loads(three.stdout), json.loads(stl.stdout)
    assert a["backlash_max_mm"] == pytest.approx(b["backlash_max_mm"], abs=1e-3)
    for side in ("drive", "coast"):
        assert a[side]["te_max_arcmin"] == pytest.approx(b[side]["te_max_arcmin"], abs=0.05)


def test_a_pair_that_meshes_is_written_and_mesh_check_exits_0(cli, tmp_path):
    # a small crank (b = 20, on the source's strut) gives gentle handovers: the teeth clear everywhere
    result = cli("gears", "--b", "20", "--c", "360", "--format", "stl", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    meshing = json.loads((tmp_path / "gears.json").read_text())["meshing"]
    assert meshing["interference"] is False and not meshing["contact_lost"]
    assert meshing["backlash_min_mm"] > 0
    check = cli("mesh-check", tmp_path / "pinion.stl", tmp_path / "wheel.stl", "--b", "20", "--c", "360",
                "--samples", "384")
    assert check.exit_code == 0 and "interference: none" in check.stdout
    assert "hub speed ripple" in check.stdout


@pytest.mark.parametrize("args, param", [
    (["missing.stl", "wheel.stl"], "pinion ="),
    (["PIN", "nothing.txt"], "wheel ="),
    (["PIN", "WHEEL", "--samples", "3"], "samples ="),
    (["PIN", "WHEEL", "--distance", "-5"], "distance ="),
    (["PIN", "WHEEL", "--plot", "x.pdf"], "plot ="),
    (["PIN", "WHEEL", "--b", "110", "--c", "360"], "c ="),
])
def test_mesh_check_bad_input_one_line_exit_2(paper_pair, cli, tmp_path, args, param):
    named = {"PIN": paper_pair / "pinion.stl", "WHEEL": paper_pair / "wheel.stl"}
    args = [str(named[a]) if a in named else a for a in args]
    (tmp_path / "nothing.txt").write_text("x")
    result = cli("mesh-check", *[str(tmp_path / a) if a.endswith((".stl", ".txt")) and "/" not in a
                                 else a for a in args])
    assert param in error_line(result), result.stderr
    assert not (tmp_path / "x.pdf").exists()


def test_a_pair_given_wheel_first_is_told_to_swap_before_any_pose(paper_pair, cli, monkeypatch):
    """Wheel first, every pose interferes: the check would run for nothing."""
    import wheelstep_cli.parts.mesh_check_files as files

    def no_check(*args, **kwargs):
        raise AssertionError("the check ran on a swapped pair")

    monkeypatch.setattr(files, "run_written_pair_check", no_check)
    wheel, pinion = paper_pair / "wheel.stl", paper_pair / "pinion.stl"
    line = error_line(cli("mesh-check", wheel, pinion))
    assert line.startswith(f"wheelstep: error: pinion = {wheel}: is the larger gear (radius by area ")
    assert line.endswith("while the law turns the wheel 2 times slower than the pinion: the two look "
                         "swapped; give the pinion first, then the wheel"), line


def test_a_window_narrower_than_the_default_is_refused_before_any_pose(paper_pair, cli):
    """A narrow window loses contacts: 'contact LOST' or a wrong backlash band, reported as
    the pair's (the paper pair's smaller outer radius is the pinion's, about 62 mm)."""
    line = error_line(cli("mesh-check", paper_pair / "pinion.stl", paper_pair / "wheel.stl", "--window", "2"))
    assert line.startswith("wheelstep: error: --window = 2: must be >= 15."), line
    assert line.endswith("mm (about 0.25 x the smaller outer radius: a narrower window misses contacts)")


def test_blend_10_is_checked_against_the_blended_law_and_written(cli, tmp_path):
    # the pair is cut for the blended law and checked against it, with the design's own
    # default backlash (measured on the blended law the play looked free and the default
    # doubled to 0.52 mm, which cost F'i 17 um). At z = 48 its f'i, measured with the peaks
    # between poses, is above the bound: refused, and the remedy it names, applied, writes
    # the pair within the bounds (issue 13)
    from wheelstep_cli.parts.mesh_bounds import bound_violations

    refused = error_line(cli("gears", "--z", "48", "--blend", "10", "--format", "stl", "--out", tmp_path))
    assert "f'i" in refused and "> 10 um" in refused and "; nothing written; use --z " in refused, refused
    z = refused.rsplit("use --z ", 1)[1]
    assert not (tmp_path / "gears.json").exists()
    result = cli("gears", "--z", z, "--blend", "10", "--format", "stl", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    report = json.loads((tmp_path / "gears.json").read_text())
    meshing = report["meshing"]
    assert report["generated"]["blend_deg"] == 10 and meshing["interference"] is False
    assert report["parameters"]["backlash"] == pytest.approx(0.239)   # as without the blend
    assert "drive flank" in result.stdout and "coast flank" in result.stdout
    assert bound_violations(meshing) == []
    # the blend itself makes most of the hub speed ripple: the law alone has it too, and the
    # run warns of it (the mover's speed varies that much however exact the teeth)
    assert meshing["law_hub_speed_ripple_pct"] > 5.0
    assert result.stderr == (f"WARNING: the law the teeth follow itself ripples "
                             f"{meshing['law_hub_speed_ripple_pct']:.2f} % (however exact the teeth, "
                             "the output speed varies that much; the teeth add the figures above)\n")
    as_json = cli("gears", "--z", z, "--blend", "10", "--format", "stl", "--dry-run", "--json", "--out", tmp_path)
    assert as_json.stderr.splitlines()[0].endswith("the teeth add the report's meshing.drive and meshing.coast)")
    assert json.loads(as_json.stdout)["meshing"]["law_hub_speed_ripple_pct"] > 5.0
    # each flank's line says what the teeth add beyond it, the figure the bound is on
    for side in ("drive", "coast"):
        own, whole = meshing["law_hub_speed_ripple_pct"], meshing[side]["hub_speed_ripple_pct"]
        assert (f"{side} flank:" in result.stdout and f"{max(0.0, whole - own):.2f} % beyond the law's own "
                f"{own:.2f} %" in result.stdout), result.stdout
    pin, wheel = tmp_path / "pinion.stl", tmp_path / "wheel.stl"
    same = cli("mesh-check", pin, wheel, "--blend", "10", "--json")
    assert same.exit_code == 0, same.stderr
    measured = json.loads(same.stdout)
    assert measured["law"]["blend_deg"] == 10
    assert measured["drive"]["F_i_total_um"] == pytest.approx(meshing["drive"]["F_i_total_um"],
                                                              rel=1e-6)
    # against the unblended law the same files jam at the handovers
    assert cli("mesh-check", pin, wheel, "--samples", "384").exit_code == 1
