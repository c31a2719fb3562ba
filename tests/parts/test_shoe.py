"""Support shoe (SPEC §2): sizing, the sole, and the printable part written by `wheelstep shoe`."""

import io
import json
import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.helpers.strategies import r_min_designs

from tests.helpers.clicheck import error_line
from tests.helpers.meshcheck import assert_printable_stl, read_3mf_strict
from wheelstep_cli.config.profiles import load_printer
from wheelstep_cli.mechanism.crank import CrankMechanism
from wheelstep_cli.mechanism.sole import contact_angles, sole_polar, sole_profile
from wheelstep_cli.parts.shoe import ShoeSpec, build_shoe, shoe_files

FILES = ("shoe.stl", "shoe.3mf", "shoe.json", "shoe-profile.csv", "shoe-profile.dxf")

designs = r_min_designs()


def expected_point(a, b, c, phi):
    """SPEC §2 sole point, written out with scalar math (independent of the numpy code)."""
    y1 = 4 * b * math.cos(phi) - a
    y2 = a - 2 * b * (1 + math.cos(phi) ** 2) + c
    return y2 * math.sin(phi), y1 + y2 * math.cos(phi)


def numerical_curvature_radius(points, phi):
    """Curvature radius of a curve sampled at equally spaced parameters ``phi`` (central differences).

    Also returns the part of the error due to rounding the points to +-``eps``: the second
    difference is off by up to 4 eps / h^2, and since |dP/dphi| = R on this sole (SPEC §2),
    R is off by about the same absolute amount in mm.
    """
    h = phi[1] - phi[0]
    d1 = (points[2:] - points[:-2]) / (2 * h)
    d2 = (points[2:] - 2 * points[1:-1] + points[:-2]) / h**2
    cross = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    return np.hypot(d1[:, 0], d1[:, 1]) ** 3 / cross


def rounding_error_bound(phi, eps):
    h = phi[1] - phi[0]
    return 4 * eps / h**2


def curvature_radius_formula(a, b, c, phi):
    return a + c - b * (6 * np.cos(phi) ** 2 - 2)


def read_csv(data: bytes) -> np.ndarray:
    text = data.decode()
    assert text.splitlines()[0] == "x_mm,y_mm"
    return np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)


@pytest.fixture(scope="module")
def default_shoe(tmp_path_factory):
    out = tmp_path_factory.mktemp("shoe")
    from wheelstep_cli.cli import run

    assert run(["shoe", "--out", str(out)]) == 0
    return out


# ---- reference (SPEC §2) --------------------------------------------------------------

def test_reference_sizing_json(cli):
    result = cli("shoe", "--json", "--dry-run")
    assert result.exit_code == 0, result.stderr
    report = json.loads(result.stdout)
    assert report["a_mm"] == 60 and report["b_mm"] == 100
    assert report["r_min_mm"] == pytest.approx(20.0)
    assert round(report["c_mm"], 1) == 360.0
    assert round(report["x_walk_mm"], 1) == 600.0
    assert round(report["x_roll_mm"], 1) == 202.7
    assert round(report["x_cycle_mm"], 1) == 802.7
    assert round(report["roll_share_pct"], 2) == 25.25
    assert report["hub_height_mm"] == pytest.approx(320.0)
    profile = np.array(report["profile"])
    assert profile.shape[0] >= 200 and profile.shape[1] == 2
    # phi = -pi/4 .. pi/4: ends symmetric, lowest point (Y = c) on the strut axis
    assert profile[0] == pytest.approx([-84.8528, 307.6955], abs=1e-4)
    assert profile[-1] == pytest.approx([84.8528, 307.6955], abs=1e-4)
    assert profile[:, 1].max() == pytest.approx(360.0)
    assert report["written"] == []


def test_reference_sizing_table(cli):
    result = cli("shoe", "--dry-run")
    assert result.exit_code == 0, result.stderr
    text = result.stdout
    for piece in ("c = 360.0", "R_min = 20.0", "Y01 = a - b + c = 320.0", "X_I = 600.0",
                  "X_II = 202.7", "X01 = 802.7", "25.25 %",
                  # sole rows phi, X, Y, rho, alpha, R: lowest point on the strut axis at Y = c, R = R_min;
                  # phi = 30 deg: Y2 = 60 - 200 (1 + 3/4) + 360 = 70, X = 70 sin 30 = 35, R = 420 - 250 = 170
                  "0.0     0.00   360.00   360.00      0.00   20.00",
                  "30.0    35.00   347.03   348.79      5.76  170.00"):
        assert piece in text, piece


def test_strut_given_as_c_or_rmin_agrees(cli):
    by_c = json.loads(cli("shoe", "--c", "360", "--json", "--dry-run").stdout)
    by_rmin = json.loads(cli("shoe", "--rmin", "20", "--json", "--dry-run").stdout)
    both = cli("shoe", "--rmin", "20", "--c", "360", "--json", "--dry-run")
    assert both.exit_code == 0
    assert by_c["profile"] == by_rmin["profile"] == json.loads(both.stdout)["profile"]
    other = json.loads(cli("shoe", "--a", "50", "--b", "80", "--rmin", "30", "--json", "--dry-run").stdout)
    assert other["c_mm"] == pytest.approx(30 - 50 + 4 * 80)


# ---- properties over random valid designs --------------------------------------------

@settings(max_examples=60, deadline=None)
@given(designs, st.lists(st.floats(-math.pi / 4, math.pi / 4), min_size=1, max_size=20))
def test_profile_and_sizing_match_spec_formulas(design_args, phis):
    a, b, r_min = design_args
    design = CrankMechanism.from_r_min(a, b, r_min)
    c = r_min - a + 4 * b
    assert design.c == pytest.approx(c)
    assert design.r_min == pytest.approx(r_min)
    phi = np.array(phis)
    xy = sole_profile(design, phi)
    expected = np.array([expected_point(a, b, c, p) for p in phis])
    assert np.allclose(xy, expected, rtol=1e-12, atol=1e-9 * (a + b + c))
    rho, alpha = sole_polar(design, phi)
    assert np.allclose(rho * np.sin(alpha), expected[:, 0], atol=1e-9 * (a + b + c))
    assert np.allclose(rho * np.cos(alpha), expected[:, 1], atol=1e-9 * (a + b + c))
    assert design.hub_height == pytest.approx(a - b + c)
    assert design.x_walk == pytest.approx(6 * b)
    assert design.x_cycle == pytest.approx((a - b + c) * math.pi / 2 + 3 * b)
    assert design.x_roll == pytest.approx(3 * b * (math.pi / 2 - 1) + r_min * math.pi / 2)
    assert design.roll_share == pytest.approx(design.x_roll / design.x_cycle)


@settings(max_examples=60, deadline=None)
@given(designs)
def test_sole_arc_length_is_the_rolling_part(design_args):
    design = CrankMechanism.from_r_min(*design_args)
    dense = sole_profile(design, contact_angles(200_001))
    length = np.linalg.norm(np.diff(dense, axis=0), axis=1).sum()
    assert length == pytest.approx(design.x_roll, rel=1e-7)


# shoes big enough to hold a 6 mm socket: b >= 5, R_min >= 5 (sole length sqrt(2) (R_min + b))
part_designs = r_min_designs(min_b=5.0, min_r_min=5.0)


@settings(max_examples=12, deadline=None)
@given(part_designs)
def test_written_profile_has_the_spec_curvature_and_the_part_is_printable(design_args):
    a, b, r_min = design_args
    spec = ShoeSpec(a=a, b=b, r_min=r_min, strut_diameter=6.0, socket_depth=10.0, rim=15.0)
    shoe = build_shoe(spec)
    assert shoe.checks["shoe"].ok
    # contents in memory, nothing written; a bed that takes every drawn size
    files = shoe_files(shoe, Path("out"), "stl", printer=replace(load_printer(), bed=(2000.0, 2000.0)))
    written = {p.name: data for p, data in files.items()}
    csv = read_csv(written["shoe-profile.csv"])
    report = json.loads(written["shoe.json"])
    points = np.array(report["profile"])
    assert np.allclose(csv, points, atol=6e-7)
    c = report["c_mm"]
    phi = np.linspace(-math.pi / 4, math.pi / 4, len(csv))  # the documented sampling
    expected = np.array([expected_point(a, b, c, p) for p in phi])
    assert np.allclose(csv, expected, atol=6e-7)
    formula = curvature_radius_formula(a, b, c, phi[1:-1])
    # rtol: truncation of the central differences; atol: the files' rounding (6 and 9 decimals)
    for sampled, eps in ((csv, 5e-7), (points, 5e-10)):
        numeric = numerical_curvature_radius(sampled, phi)
        assert np.allclose(numeric, formula, rtol=2e-3, atol=1.5 * rounding_error_bound(phi, eps))
    assert numerical_curvature_radius(points, phi).min() == pytest.approx(r_min, rel=2e-3)
    import trimesh

    mesh = trimesh.load(io.BytesIO(written["shoe.stl"]), file_type="stl", force="mesh")
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    assert mesh.volume == pytest.approx(report["part"]["volume_mm3"], rel=1e-4)
    # the part's sole is the written profile (part frame y = c - Y): every point is a mesh vertex
    # on the face z = 0, and no vertex lies below the sole
    from scipy.spatial import cKDTree

    vertices = shoe.part.vertices
    face = vertices[vertices[:, 2] == 0.0][:, :2]
    sole = np.column_stack([csv[:, 0], c - csv[:, 1]])
    distance, _ = cKDTree(face).query(sole)
    assert distance.max() < 1e-4 * (1 + c)  # manifold3d keeps float32 vertices
    below = vertices[:, 1] - np.interp(vertices[:, 0], sole[:, 0], sole[:, 1])
    assert below.min() > -1e-4 * (1 + c)


# ---- the written part -----------------------------------------------------------------

def test_writes_printable_shoe_and_report(default_shoe):
    assert sorted(p.name for p in default_shoe.iterdir()) == sorted(FILES + (".wheelstep-shoe.json",))
    report = json.loads((default_shoe / "shoe.json").read_text())
    mesh = assert_printable_stl(default_shoe / "shoe.stl")
    part = report["part"]
    assert mesh.volume == pytest.approx(part["volume_mm3"], rel=1e-4)
    assert np.allclose(mesh.bounds, part["bounding_box_mm"], atol=1e-3)
    assert all(part["checks"].values())
    # printed on its side: the width along z, the sole's lowest point at y = 0, top face at y = sag + rim
    profile = np.array(report["profile"])
    sag = profile[:, 1].max() - profile[0, 1]
    assert mesh.bounds[:, 2] == pytest.approx([0.0, 40.0])
    assert mesh.bounds[:, 1] == pytest.approx([0.0, sag + 15.0], abs=1e-4)
    assert mesh.bounds[:, 0] == pytest.approx([profile[0, 0], profile[-1, 0]], abs=1e-4)
    # volume from an independent outline: the sole from the CSV, a flat top, minus the socket
    import shapely

    csv = read_csv((default_shoe / "shoe-profile.csv").read_bytes())
    sole = np.column_stack([csv[:, 0], report["c_mm"] - csv[:, 1]])
    top = sole[0, 1] + 15.0
    side = shapely.Polygon(np.vstack([sole, [[sole[-1, 0], top], [sole[0, 0], top]]]))
    socket = math.pi * 6.0**2 * 25.0
    solid = side.area * 40.0
    assert solid - 1.01 * socket < mesh.volume < solid - socket


def test_socket_is_a_hole_along_the_strut(default_shoe):
    import shapely

    mesh = assert_printable_stl(default_shoe / "shoe.stl")
    top = mesh.bounds[1, 1]
    # across the socket (a plane y = const): the body's section with one round hole of the strut's size
    for y in (top - 1.0, top - 24.0):
        loops = [shapely.Polygon(loop[:, [0, 2]]) for loop in mesh.section(plane_normal=[0, 1, 0], plane_origin=[0, y, 0]).discrete]
        holes = [p for p in loops if p.area < 1000]
        assert len(loops) == 2 and len(holes) == 1
        hole = holes[0]
        assert hole.centroid.x == pytest.approx(0.0, abs=1e-3)
        assert hole.centroid.y == pytest.approx(20.0, abs=1e-3)
        assert math.pi * 36.0 <= hole.area <= 1.01 * math.pi * 36.0
        # a 12 mm strut fits: the hole's flats touch the nominal circle from outside
        assert hole.exterior.distance(hole.centroid) == pytest.approx(6.0, abs=0.01)
    # below the socket bottom the section is solid
    loops = mesh.section(plane_normal=[0, 1, 0], plane_origin=[0, top - 26.0, 0]).discrete
    assert len(loops) == 1


def test_3mf_reads_back_strict(default_shoe):
    info = read_3mf_strict(default_shoe / "shoe.3mf")
    assert info["warnings"] == []
    assert info["build_items"] == 1 and info["unit"] == 1  # millimetre
    report = json.loads((default_shoe / "shoe.json").read_text())
    assert info["objects"]["shoe"] == pytest.approx(report["part"]["volume_mm3"], rel=1e-4)


def test_dxf_holds_the_sole_as_one_polyline(default_shoe):
    import ezdxf

    doc = ezdxf.readfile(default_shoe / "shoe-profile.dxf")
    entities = list(doc.modelspace())
    assert len(entities) == 1 and entities[0].dxftype() == "LWPOLYLINE"
    assert not entities[0].closed
    points = np.array(entities[0].get_points("xy"))
    csv = read_csv((default_shoe / "shoe-profile.csv").read_bytes())
    assert points.shape == csv.shape
    assert np.allclose(points, csv, atol=2e-6)
    assert doc.header["$INSUNITS"] == 4  # millimetres


def test_same_inputs_give_identical_files(default_shoe, tmp_path):
    # a separate process with another hash seed, so nothing cached or set-ordered can make them equal
    env = {"PYTHONHASHSEED": "12345"}
    import os

    subprocess.run([sys.executable, "-m", "wheelstep_cli", "shoe", "--out", str(tmp_path)],
                   check=True, capture_output=True, env={**os.environ, **env})
    for name in FILES:
        assert (tmp_path / name).read_bytes() == (default_shoe / name).read_bytes(), name


def test_profile_reproduces_defaults_and_cli_overrides(cli, tmp_path, default_shoe):
    assert cli("shoe", "--profile", "bntu-2024", "--out", tmp_path / "p").exit_code == 0
    for name in FILES:
        if name == "shoe.json":     # the same report, besides the design profile it records
            report = json.loads((tmp_path / "p" / name).read_text())
            assert report.pop("design_profile")["file"] == "bntu-2024.yaml"
            assert report == json.loads((default_shoe / name).read_text())
            continue
        assert (tmp_path / "p" / name).read_bytes() == (default_shoe / name).read_bytes(), name
    result = cli("shoe", "--profile", "bntu-2024", "--width", "30", "--rmin", "40", "--format", "stl",
                 "--out", tmp_path / "q")
    assert result.exit_code == 0, result.stderr
    mesh = assert_printable_stl(tmp_path / "q" / "shoe.stl")
    assert mesh.bounds[1, 2] == pytest.approx(30.0)
    report = json.loads((tmp_path / "q" / "shoe.json").read_text())
    assert report["c_mm"] == pytest.approx(380.0)  # --rmin replaces the profile's c
    assert not (tmp_path / "q" / "shoe.3mf").exists()


@pytest.mark.parametrize("args, param", [
    (["--rmin", "0"], "--rmin ="),                          # cusp
    (["--rmin", "-5"], "--rmin ="),                         # loop
    (["--c", "300"], "--c ="),                              # R_min = a - 4b + c < 0
    (["--a", "-60"], "--a ="),
    (["--b", "-1"], "--b ="),
    (["--rmin", "30", "--c", "360"], "--rmin ="),           # contradicts c
    (["--rmin", "20", "--c", "300"], "--rmin = 20: contradicts"),   # before c's own limit
    (["--strut-diameter", "40"], "--strut-diameter ="),     # socket wider than the body
    (["--strut-diameter", "-3"], "--strut-diameter ="),
    (["--socket-depth", "80"], "--socket-depth ="),         # deeper than the body
    (["--width", "0"], "--width ="),
    (["--rim", "-1"], "--rim ="),
    (["--width", "abc"], "--width = abc: must be a number"),
    (["--profile", "no-such-design"], "--profile ="),
])
def test_bad_input_one_line_exit_2_nothing_written(cli, tmp_path, args, param):
    out = tmp_path / "out"
    result = cli("shoe", *args, "--out", out)
    assert param in error_line(result), result.stderr
    assert "Traceback" not in result.stderr
    assert not out.exists()


def test_deepest_socket_keeps_two_mm_of_plastic_to_the_sole(cli, tmp_path):
    import re

    import shapely

    refused = cli("shoe", "--socket-depth", "90", "--dry-run")
    assert refused.exit_code == 2
    limit = float(re.search(r"must be <= ([0-9.]+) mm", refused.stderr).group(1))
    assert cli("shoe", "--socket-depth", limit + 0.02, "--dry-run").exit_code == 2
    ok = cli("shoe", "--socket-depth", limit - 0.01, "--format", "stl", "--out", tmp_path)
    assert ok.exit_code == 0, ok.stderr
    mesh = assert_printable_stl(tmp_path / "shoe.stl")
    top = mesh.bounds[1, 1]
    report = json.loads((tmp_path / "shoe.json").read_text())
    csv = read_csv((tmp_path / "shoe-profile.csv").read_bytes())
    sole = shapely.LineString(np.column_stack([csv[:, 0], report["c_mm"] - csv[:, 1]]))
    socket = shapely.box(-6.0, top - (limit - 0.01), 6.0, top)
    assert 2.0 <= sole.distance(socket) < 2.02
    # the hole really reaches that deep: just above its bottom the section still has it
    loops = mesh.section(plane_normal=[0, 1, 0], plane_origin=[0, top - limit + 0.1, 0]).discrete
    assert len(loops) == 2


@pytest.mark.parametrize("args, named", [
    (["--a", "0.001", "--b", "5"], "--a = 0.001: with it, socket-depth = 25 (the default) fails: "),
    (["--socket-depth", "80"], "--socket-depth = 80: "),
])
def test_a_socket_deeper_than_the_body_names_what_the_user_gave(cli, tmp_path, args, named):
    """The default depth does not fit a small mechanism's body: the line names the option the
    user gave, and its limit is a depth that fits."""
    line = error_line(cli("shoe", *args, "--out", tmp_path / "out"))
    assert line.startswith(f"wheelstep: error: {named}must be <= "), line
    assert line.endswith("mm (socket deeper than the body: keep 2 mm of plastic between it and the sole)")
    limit = line.split("must be <= ")[1].split(" mm")[0]
    assert cli("shoe", *args[:4 if args[0] == "--a" else 0], "--socket-depth", limit, "--out",
               tmp_path / "ok", "-q").exit_code == 0
    assert not (tmp_path / "out").exists()


def test_a_strut_wider_than_a_small_mechanisms_body_names_what_the_user_gave(cli, tmp_path):
    line = error_line(cli("shoe", "--rmin", "0.5", "--a", "5", "--b", "5", "--out", tmp_path / "out"))
    assert line.startswith("wheelstep: error: --a = 5: with it, strut-diameter = 12 (the default) fails: must be <= "), line
    limit = line.split("must be <= ")[1].split(" mm")[0]
    assert cli("shoe", "--rmin", "0.5", "--a", "5", "--b", "5", "--strut-diameter", limit, "--socket-depth",
               "1", "--rim", "30", "--out", tmp_path / "ok", "-q").exit_code == 0


def test_a_mechanism_typed_in_metres_is_told_lengths_are_millimetres(cli, tmp_path):
    """--a 0.06 --b 0.1 --rmin 0.02 (metres for 60, 100, 20 mm) draw a sole a fifth of a
    millimetre long: no socket fits, said so (not 'must be <= -3.84 mm'), with the unit."""
    from tests.helpers.clicheck import error_line

    line = error_line(cli("shoe", "--a", "0.06", "--b", "0.1", "--rmin", "0.02", "--out", tmp_path / "o"))
    assert line.startswith("wheelstep: error: --a = 0.06: with it, strut-diameter = 12 (the default) fails: fits no socket: "
                           "the body is 0.17 mm across (its sole)"), line
    assert line.endswith("lengths are in millimetres") and "<= -" not in line


def test_a_shoe_too_tall_for_the_printer_is_offered_the_width_it_prints(cli, tmp_path):
    """A shoe stands on its side: too wide to print upright, it is offered the width the
    printer prints (the printer's height), which applied is written."""
    line = error_line(cli("shoe", "--width", "300.04", "--printer", "resin-0.05-standard", "--out", tmp_path / "o"))
    assert line.startswith("wheelstep: error: --width = 300.04: makes part 'shoe' 300.0 mm tall, more than the "
                           "250 mm printer 'resin-0.05-standard' prints; nothing written; use --width 250"), line
    assert not (tmp_path / "o").exists()
    written = cli("shoe", "--width", "250", "--printer", "resin-0.05-standard", "--out", tmp_path / "o", "-q")
    assert written.exit_code == 0, written.stderr
    assert (tmp_path / "o" / "shoe.3mf").exists()
    # a printer too low for any shoe the strut's socket fits in: no width is offered
    profiles = Path(__file__).resolve().parents[2] / "profiles"
    low = tmp_path / "low.yaml"
    low.write_text((profiles / "fdm-0.4-pla.yaml").read_text().replace("max_height: 250", "max_height: 12"))
    line = error_line(cli("shoe", "--printer", low, "--out", tmp_path / "low"))
    assert line.startswith("wheelstep: error: --width = 40 (the default): makes part 'shoe' 40.0 mm tall, more than "
                           "the 12 mm"), line
    assert "; use" not in line and not (tmp_path / "low").exists()


def test_a_shoe_too_large_for_the_default_printers_bed_names_the_size_and_the_way_out(cli, tmp_path):
    """A mechanism ten times the source design's makes a shoe larger than the default
    printer's bed: said of the length given, as the size it makes, with the note that the
    printer is the default one and the smaller shoe as the remedy; --format stl, as the note
    says, writes it."""
    args = ["shoe", "--a", "600", "--b", "1000"]
    line = error_line(cli(*args, "--out", tmp_path / "big"))
    assert line.startswith("wheelstep: error: --a = 600: with it, part 'shoe' is "), line
    assert ", larger than the bed of printer 'fdm-0.4-pla' (256 x 256 mm" in line, line
    assert ("(the default printer; --printer chooses another, --format stl writes no plate); nothing written; "
            "use --a ") in line and "(the mechanism drawn at " in line, line
    assert not (tmp_path / "big").exists()
    named = error_line(cli(*args, "--printer", "fdm-0.4-pla", "--out", tmp_path / "big"))
    assert named.startswith("wheelstep: error: --printer = fdm-0.4-pla: part 'shoe' ") and "default" not in named
    assert cli(*args, "--format", "stl", "--out", tmp_path / "big", "-q").exit_code == 0


def test_a_body_too_narrow_for_any_strut_names_its_width_not_the_strut(cli, tmp_path):
    """--width 4.5 leaves 0.5 mm between the walls, less than the thinnest strut the shoe
    takes (1 mm): the width is the input to change, even beside a strut diameter given."""
    line = error_line(cli("shoe", "--width", "4.5", "--strut-diameter", "1", "--out", tmp_path / "o"))
    assert line.startswith("wheelstep: error: --width = 4.5: must be >= 5.00 mm (socket wider than the body"), line
    assert cli("shoe", "--width", "5", "--strut-diameter", "1", "--out", tmp_path / "o", "-q").exit_code == 0


def test_a_rim_thinner_than_the_shoes_least_wall_is_refused(cli, tmp_path):
    """--rim is the body's height above the sole's ends: 1e-9 mm was written as printable
    (knife-edged ends); it takes the shoe's least wall, as the socket's walls do."""
    from wheelstep_cli.config.specs import MIN_SHOE_WALL

    line = error_line(cli("shoe", "--rim", "1e-9", "--out", tmp_path / "thin"))
    assert line == f"wheelstep: error: --rim = 1e-9: must be >= {MIN_SHOE_WALL:g} mm", line
    assert not (tmp_path / "thin").exists()
    assert cli("shoe", "--rim", f"{MIN_SHOE_WALL:g}", "--out", tmp_path / "least", "-q").exit_code == 0
