"""`wheelstep gears --plot/--gif/--dxf/--svg/--step`: the files, their formats and sizes,
outlines as built; bad paths and a missing extra refused in one line, nothing written."""

import io
import json
from dataclasses import replace

import numpy as np
import pytest
from PIL import Image

from tests.helpers.cad import step_volume
from tests.helpers.clicheck import error_line


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    from wheelstep_cli.cli import run

    root = tmp_path_factory.mktemp("exports")
    out = root / "out"
    args = ["gears", "--format", "stl", "--out", str(out), "--plot", str(root / "pair.png"),
            "--gif", str(root / "pair.gif"), "--dxf", "--svg", "-q"]
    assert run(args) == 0
    return root


@pytest.fixture(scope="module")
def faces():
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.gear_faces import gear_faces
    from wheelstep_cli.parts.gear_pair import build_gear_pair

    return gear_faces(build_gear_pair(gear_pair_spec(None)))


def test_exports_are_owned_files_of_the_output_folder(exported):
    out = exported / "out"
    names = sorted(p.name for p in out.iterdir())
    assert names == [".wheelstep-gears.json", "gears.json", "pinion.dxf", "pinion.stl", "pinion.svg",
                     "wheel.dxf", "wheel.stl", "wheel.svg"]
    record = (out / ".wheelstep-gears.json").read_text()
    for name in ("pinion.dxf", "wheel.svg"):
        assert name in record


def test_dxf_outlines_are_the_built_ones_within_a_micron(exported, faces):
    import ezdxf

    for name, face in faces.items():
        doc = ezdxf.readfile(exported / "out" / f"{name}.dxf")
        auditor = doc.audit()
        assert not auditor.has_errors and doc.header["$INSUNITS"] == 4
        rings = {e.dxf.layer: np.array([p[:2] for p in e.get_points("xy")])
                 for e in doc.modelspace().query("LWPOLYLINE")}
        assert rings["OUTLINE"].shape == face.outline.shape
        assert np.abs(rings["OUTLINE"] - face.outline).max() < 1e-3
        assert np.abs(rings["HOLES"] - face.holes[0]).max() < 1e-3
        r = np.hypot(*rings["HOLES"].T)
        assert r.min() >= 4.0 - 1e-9                        # the 8 mm bore, circumscribed


def test_svg_renders_at_the_gears_size_in_mm(exported, faces):
    cairosvg = pytest.importorskip("cairosvg")
    data = (exported / "out" / "wheel.svg").read_bytes()
    image = Image.open(io.BytesIO(cairosvg.svg2png(bytestring=data, dpi=25.4)))  # 1 px per mm
    tip = np.hypot(*faces["wheel"].outline.T).max()
    assert image.size[0] == pytest.approx(2 * tip + 4, abs=1.5)
    rgba = image.convert("RGBA")
    assert rgba.getpixel((image.size[0] // 2 + 50, image.size[1] // 2))[3] == 255


def test_plot_is_a_png_of_the_pair(exported):
    image = Image.open(exported / "pair.png")
    assert image.format == "PNG" and image.size[0] >= 1000 and image.size[1] >= 700
    # mostly white paper with the two filled gears on it: both face colours are present
    colours = {c for _, c in image.convert("RGB").getcolors(1 << 20)}
    assert (0x9e, 0xca, 0xe1) in colours and (0xfd, 0xd0, 0xa2) in colours


def test_gif_turns_through_a_handover_in_bounded_frames(exported):
    image = Image.open(exported / "pair.gif")
    assert image.format == "GIF" and image.size == (720, 360)
    assert 40 <= image.n_frames <= 60
    first = np.asarray(image.convert("RGB"))
    image.seek(image.n_frames - 1)
    assert not np.array_equal(first, np.asarray(image.convert("RGB")))    # the gears turned


def test_a_dry_run_writes_no_picture(cli, tmp_path):
    result = cli("gears", "--plot", tmp_path / "pair.svg", "--dry-run", "--format", "stl",
                 "--out", tmp_path / "out", "-q")
    assert result.exit_code == 0 and not any(tmp_path.iterdir())


@pytest.mark.parametrize("args, flag, limit", [
    (["--plot", "pair.jpg"], "--plot", "must end in .png or .svg"),
    (["--gif", "pair.png"], "--gif", "must end in .gif"),
])
def test_other_extensions_are_refused(cli, tmp_path, args, flag, limit):
    result = cli("gears", *[str(tmp_path / a) if "." in a else a for a in args], "--out", tmp_path / "out")
    line = error_line(result)
    assert line.startswith(f"wheelstep: error: {flag} = ") and limit in line
    assert not any(tmp_path.iterdir())


def test_step_without_the_extra_is_refused_naming_it(cli, tmp_path, monkeypatch):
    import wheelstep_cli.formats.step as step

    monkeypatch.setattr(step, "step_available", lambda: False)
    line = error_line(cli("gears", "--step", "--out", tmp_path / "out"))
    assert line == "wheelstep: error: --step = on: needs the optional CAD extra: pip install wheelstep[cad]"
    assert not any(tmp_path.iterdir())


def edge_points(edge, spacing: float = 0.005) -> np.ndarray:
    """Points (N, 2) mm of a B-spline edge as OpenCASCADE read it: every knot (its creases
    included) and points between, about ``spacing`` mm apart, so the polyline through them
    strays from the curve by far less than a micrometre."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    curve = BRepAdaptor_Curve(edge.wrapped)
    spline = curve.BSpline()
    knots = [spline.Knot(i) for i in range(1, spline.NbKnots() + 1)]
    ends = [curve.Value(k) for k in knots]
    u = [np.linspace(a, b, 4 + int(p.Distance(q) / spacing), endpoint=False)
         for a, b, p, q in zip(knots[:-1], knots[1:], ends[:-1], ends[1:])]
    return np.array([(p.X(), p.Y()) for p in map(curve.Value, np.concatenate(u + [knots[-1:]]))])


def distances(points: np.ndarray, polylines: list[np.ndarray]) -> np.ndarray:
    """Distance (mm) of each point to the nearest segment of the polylines."""
    import shapely

    segments = shapely.linestrings(np.concatenate([np.stack([line[:-1], line[1:]], 1) for line in polylines]))
    tree = shapely.STRtree(segments)
    _, distance = tree.query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    return distance


def assert_step_is_the_mesh_within_the_fit(step_file, stl_file):
    """The STEP reads back as one valid solid whose bottom edges lie within the fit tolerance
    of the written mesh's mid-height section, both ways; its volume is the mesh's within that
    tolerance times perimeter and thickness; its box is the mesh's. Returns the solid."""
    import trimesh
    from build123d import import_step

    from wheelstep_cli.geometry.spline_fit import FitSettings

    fit = FitSettings()
    solid, mesh = import_step(step_file), trimesh.load(stl_file)
    assert len(solid.solids()) == 1 and solid.is_valid
    assert len(solid.faces()) <= 2 + 2 * fit.max_edges
    section = mesh.section(plane_origin=[0, 0, mesh.bounds[1, 2] / 2], plane_normal=[0, 0, 1])
    printed = [np.asarray(line[:, :2]) for line in section.discrete]
    fitted = [edge_points(e) for e in solid.edges() if abs(e.center().Z) < 1e-9]
    slack = 1e-5                                    # the STL's float32 vertices
    assert distances(np.vstack(fitted), printed).max() <= fit.tolerance + slack
    assert distances(np.vstack(printed), fitted).max() <= fit.tolerance + slack
    perimeter = sum(np.linalg.norm(np.diff(line, axis=0), axis=1).sum() for line in printed)
    assert abs(step_volume(solid) - mesh.volume) <= perimeter * fit.tolerance * mesh.bounds[1, 2]
    box = solid.bounding_box()
    assert [box.min.X, box.min.Y, box.min.Z, box.max.X, box.max.Y, box.max.Z] == \
        pytest.approx(mesh.bounds.ravel().tolist(), abs=fit.tolerance + slack)
    return solid


def test_step_of_a_paper_pair_is_its_mesh_within_the_fit(cli, tmp_path):
    """`gears --step` of the desk demonstrator's paper teeth (5 points a flank, sharp joins).
    No marks, so the meshes are the extruded faces exactly."""
    pytest.importorskip("build123d")
    out = tmp_path / "step"
    result = cli("gears", "--profile", "desk-demo", "--teeth", "paper", "--allow-interference",
                 "--z", "12", "--mark-depth", "0", "--format", "stl", "--step", "--out", out, "-q")
    assert result.exit_code == 0, result.stderr
    for name in ("pinion", "wheel"):
        solid = assert_step_is_the_mesh_within_the_fit(out / f"{name}.step", out / f"{name}.stl")
        assert solid.bounding_box().max.Z == pytest.approx(6.0)     # the desk pair's thickness


def test_step_of_the_generated_pair_is_its_mesh_within_the_fit(cli, tmp_path):
    """`gears --step` of the default generated pair (5 000 and 18 000 outline points, as
    B-spline edges: a file of a few MB a gear that OpenCASCADE reads in seconds)."""
    pytest.importorskip("build123d")
    out = tmp_path / "step"
    result = cli("gears", "--mark-depth", "0", "--format", "stl", "--step", "--out", out, "-q")
    assert result.exit_code == 0, result.stderr
    for name in ("pinion", "wheel"):
        assert (out / f"{name}.step").stat().st_size < 10e6
        assert_step_is_the_mesh_within_the_fit(out / f"{name}.step", out / f"{name}.stl")


def test_pictures_are_the_same_bytes_on_rerun(faces):
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.gear_exports import pair_drawing
    from wheelstep_cli.parts.gear_pair import build_gear_pair
    from wheelstep_cli.render.gear_pair_plot import pair_picture

    drawing = pair_drawing(build_gear_pair(gear_pair_spec(None)))
    for fmt in ("png", "svg"):
        assert pair_picture(drawing, fmt) == pair_picture(drawing, fmt)
    import xml.etree.ElementTree as ET

    svg = ET.fromstring(pair_picture(drawing, "svg"))
    assert svg.tag == "{http://www.w3.org/2000/svg}svg"
    assert "assembly phase" in pair_picture(drawing, "svg").decode()   # text kept as text
    assert json.dumps(sorted(drawing.teeth.items())) == '[["pinion", 48], ["wheel", 96]]'
    # the crank law's zero is a shoe in mid-stance, its corners handovers; a law CSV has no shoes
    assert drawing.crank and "shoe handovers" in pair_picture(drawing, "svg").decode()
    csv_words = pair_picture(replace(drawing, crank=False), "svg").decode()
    assert "shoe" not in csv_words and "the law's driven angle at 0" in csv_words


def test_paper_pair_is_drawn_with_its_tooth_module():
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.gear_exports import pair_drawing
    from wheelstep_cli.parts.gear_pair import build_gear_pair

    drawing = pair_drawing(build_gear_pair(gear_pair_spec(None, teeth="paper")))
    assert drawing.module == 2.0 and drawing.teeth == {"pinion": 48, "wheel": 96}
    assert drawing.law.corners == (pytest.approx(np.pi / 4),)
