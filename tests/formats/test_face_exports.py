"""Gear face DXF/SVG/STEP writers: units set, closed outlines read back within 1 um, a
browser-grade renderer draws the SVG, deterministic bytes."""

import io
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from wheelstep_cli.formats.dxf import face_dxf_bytes
from wheelstep_cli.formats.svg import face_svg_bytes
from wheelstep_cli.parts.gear_faces import GearFace


def _face() -> GearFace:
    """A 12-lobed star (radius 20..25 mm, CCW) with a 6 mm square-ish hole (CW) and a mark."""
    t = np.linspace(0.0, 2.0 * np.pi, 240, endpoint=False)
    r = 22.5 + 2.5 * np.cos(12 * t)
    outline = np.column_stack([r * np.cos(t), r * np.sin(t)])
    hole = np.array([[3.0, 3.0], [3.0, -3.0], [-3.0, -3.0], [-3.0, 3.0]])
    mark = np.array([[10.0, -0.5], [16.0, -0.5], [16.0, 0.5], [10.0, 0.5]])
    return GearFace("pinion", outline, [hole], [mark])


def _read_dxf(data: bytes):
    import ezdxf

    return ezdxf.read(io.StringIO(data.decode("utf-8")))


def test_dxf_passes_audit_in_mm_and_reads_back_within_a_micron():
    face = _face()
    doc = _read_dxf(face_dxf_bytes(face))
    auditor = doc.audit()
    assert not auditor.has_errors and not auditor.has_fixes
    assert doc.header["$INSUNITS"] == 4
    layers = {}
    for e in doc.modelspace().query("LWPOLYLINE"):
        assert e.closed
        layers.setdefault(e.dxf.layer, []).append(np.array([p[:2] for p in e.get_points("xy")]))
    assert sorted(layers) == ["HOLES", "MARKS", "OUTLINE"]
    for got, want in ((layers["OUTLINE"][0], face.outline), (layers["HOLES"][0], face.holes[0]),
                      (layers["MARKS"][0], face.marks[0])):
        assert got.shape == want.shape and np.abs(got - want).max() < 1e-3


def test_dxf_and_svg_bytes_are_the_same_on_rerun():
    assert face_dxf_bytes(_face()) == face_dxf_bytes(_face())
    assert face_svg_bytes(_face()) == face_svg_bytes(_face())


def test_svg_is_sized_in_mm_and_renders_the_face_with_its_hole():
    cairosvg = pytest.importorskip("cairosvg")
    from PIL import Image

    data = face_svg_bytes(_face())
    root = ET.fromstring(data)
    assert root.get("width") == "54.0000mm" and root.get("height").endswith("mm")
    x0, y0, w, h = (float(v) for v in root.get("viewBox").split())
    assert (x0, w) == pytest.approx((-27.0, 54.0)) and h == pytest.approx(2 * (25 * np.sin(np.pi / 2) + 2), abs=0.1)
    # 1 user unit = 1 mm: at 254 dpi, 10 px per mm
    png = cairosvg.svg2png(bytestring=data, dpi=254)
    image = Image.open(io.BytesIO(png)).convert("RGBA")
    assert image.size == (540, round(10 * h))
    cx, cy = image.size[0] // 2, image.size[1] // 2
    assert image.getpixel((cx, cy))[3] == 0                  # the hole is cut (transparent)
    assert image.getpixel((cx + 100, cy))[3] == 255          # the face at 10 mm is filled
    assert image.getpixel((cx + 60, cy))[:3] == (0xd9, 0xd9, 0xd9)
    assert image.getpixel((2, 2))[3] == 0                    # outside the outline


def test_step_is_the_extruded_face_and_deterministic(tmp_path):
    pytest.importorskip("build123d")
    from build123d import import_step

    from tests.helpers.cad import step_volume
    from wheelstep_cli.formats.step import face_step_bytes
    from wheelstep_cli.geometry.planar import signed_area
    from wheelstep_cli.geometry.spline_fit import FitSettings

    face = _face()
    data = face_step_bytes(face, 8.0)
    assert data == face_step_bytes(face, 8.0)
    assert b"FILE_SCHEMA" in data and b"SI_UNIT(.MILLI.,.METRE.)" in data
    path = tmp_path / "pinion.step"
    path.write_bytes(data)
    solid = import_step(path)
    area = signed_area(face.outline) + signed_area(face.holes[0])
    # the outline as fitted B-splines strays up to the fit's tolerance from the polygon
    perimeter = sum(np.linalg.norm(np.diff(ring, axis=0, append=ring[:1]), axis=1).sum()
                    for ring in [face.outline, *face.holes])
    assert abs(step_volume(solid) - 8.0 * area) <= perimeter * FitSettings().tolerance * 8.0
    box = solid.bounding_box()
    assert (box.min.Z, box.max.Z) == pytest.approx((0.0, 8.0), abs=1e-6)   # plus its tolerance gap
    assert box.max.X == pytest.approx(25.0, abs=FitSettings().tolerance)


def test_step_edges_keep_knots_closer_than_a_micro_unit():
    """Four knots within 1e-6 (a C-1 join a cubic cannot have if merged, and a shift if two
    are): the edge is the spline itself, each knot where it was."""
    pytest.importorskip("build123d")
    from OCP.BRep import BRep_Tool
    from scipy.interpolate import splev

    from wheelstep_cli.formats.step import _edge
    from wheelstep_cli.geometry.spline_fit import BSpline

    knots = np.array([0, 0, 0, 0, 0.3, 0.3 + 4e-7, 0.3 + 8e-7, 0.6, 1, 1, 1, 1.0])
    poles = np.array([[0, 0], [1, 2], [2, -1], [3, 2], [4, 0], [5, 3], [6, 1], [7, 0.0]])
    edge = _edge(BSpline(knots=knots, poles=poles, degree=3))
    curve = BRep_Tool.Curve_s(edge.wrapped, 0.0, 1.0)
    assert curve.NbKnots() == 6 and curve.NbPoles() == 8
    for u in np.linspace(0.0, 1.0, 41):
        p = curve.Value(float(u))
        x, y = splev(u, (knots, [poles[:, 0], poles[:, 1]], 3))
        assert (p.X(), p.Y(), p.Z()) == pytest.approx((float(x), float(y), 0.0), abs=1e-12)
