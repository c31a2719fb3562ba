"""Reading gear meshes back: the mid-thickness section equals the outline that was extruded."""

import numpy as np
import pytest
import shapely

from wheelstep_cli.errors import DesignError
from wheelstep_cli.formats.mesh_read import read_mesh, read_outline, split_mesh_spec
from wheelstep_cli.geometry.solids import section_outline


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    from wheelstep_cli.formats.atomic import write_files_atomic
    from wheelstep_cli.parts.gear_pair import GearPairSpec, build_gear_pair, gear_pair_files

    from dataclasses import replace

    from wheelstep_cli.config.profiles import load_printer

    out = tmp_path_factory.mktemp("pair")
    pair = build_gear_pair(GearPairSpec())
    # a bed that takes both full-scale gears, so gears.3mf holds the two objects
    big_bed = replace(load_printer(), bed=(400.0, 300.0))
    write_files_atomic(gear_pair_files(pair, out, "both", printer=big_bed))
    return pair, out


def _same_outline(a: np.ndarray, b: np.ndarray, tol: float) -> None:
    pa, pb = shapely.Polygon(a), shapely.Polygon(b)
    assert shapely.hausdorff_distance(pa.exterior, pb.exterior) < tol
    assert shapely.symmetric_difference(pa, pb).area < tol * pa.length


@pytest.mark.parametrize("name", ["pinion", "wheel"])
def test_stl_section_is_the_extruded_outline(written, name):
    pair, out = written
    outline = read_outline(str(out / f"{name}.stl"), name)
    assert shapely.Polygon(outline).exterior.is_ccw
    _same_outline(outline, getattr(pair, f"{name}_outline"), 1e-4)


@pytest.mark.parametrize("name", ["pinion", "wheel"])
def test_3mf_object_section_is_the_extruded_outline_in_its_own_frame(written, name):
    pair, out = written
    # by explicit name, and by the default name when the package holds several objects
    for spec, default in ((f"{out / 'gears.3mf'}:{name}", None), (str(out / "gears.3mf"), name)):
        outline = read_outline(spec, name, default)
        _same_outline(outline, getattr(pair, f"{name}_outline"), 1e-4)


def test_section_drops_the_bore_and_orients_ccw():
    import manifold3d as m3d

    ring = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], dtype=float) - 5
    hole = (0.5 * ring)[::-1]
    solid = m3d.Manifold.extrude(m3d.CrossSection([ring, hole], m3d.FillRule.Positive), 4.0)
    mesh = solid.to_mesh()
    outline = section_outline(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts), "x")
    assert shapely.Polygon(outline).area == pytest.approx(100.0)
    assert shapely.Polygon(outline).exterior.is_ccw


def test_split_mesh_spec():
    assert split_mesh_spec("out/gears.3mf:wheel") == (__import__("pathlib").Path("out/gears.3mf"), "wheel")
    assert split_mesh_spec("out/wheel.stl")[1] is None
    assert split_mesh_spec("gears.3mf")[1] is None


def test_bad_files_raise_design_errors(written, tmp_path):
    _, out = written
    junk = tmp_path / "junk.stl"
    junk.write_bytes(b"not an stl at all")
    cases = [(tmp_path / "missing.stl", "no such file"), (junk, "cannot be read"),
             (f"{out / 'gears.3mf'}:gear", "name one of its objects"),
             (out / "gears.json", "must be an .stl or .3mf")]
    for spec, message in cases:
        with pytest.raises(DesignError) as err:
            read_mesh(str(spec), "pinion")
        assert err.value.param == "pinion" and message in err.value.limit
    open_box = tmp_path / "open.stl"
    open_box.write_text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                        "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n")
    with pytest.raises(DesignError) as err:
        read_outline(str(open_box), "wheel")
    assert err.value.param == "wheel"


def test_a_binary_stl_cut_short_is_called_truncated(tmp_path):
    import trimesh

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.formats.mesh_read import read_mesh

    whole = tmp_path / "whole.stl"
    trimesh.creation.icosphere(subdivisions=3).export(whole)
    cut = tmp_path / "cut.stl"
    cut.write_bytes(whole.read_bytes()[:84 + 50 * 100 + 7])
    with pytest.raises(DesignError) as err:
        read_mesh(str(cut), "pinion")
    assert err.value.param == "pinion" and "truncated: declares 1280 triangles, holds 100" in err.value.limit
    assert len(read_mesh(str(whole), "pinion")[1]) == 1280
