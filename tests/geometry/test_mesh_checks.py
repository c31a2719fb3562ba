"""The pre-write mesh check tells closed, consistently wound meshes from broken ones."""

import numpy as np
import pytest
import trimesh

from wheelstep_cli.geometry.mesh_checks import Part, check_part
from wheelstep_cli.geometry.solids import circle, extrude_plate


@pytest.fixture(scope="module")
def plate():
    return extrude_plate("plate", circle(20.0, 96) * [1.5, 1.0], 5.0, 8.0)


def _check(plate, faces):
    return check_part(Part("plate", plate.vertices, faces, plate.expected_volume))


def test_a_closed_extrusion_passes_as_trimesh_sees_it(plate):
    report = check_part(plate)
    mesh = trimesh.Trimesh(plate.vertices, plate.faces, process=False)
    assert report.ok and report.triangles == len(plate.faces)
    assert report.watertight == mesh.is_watertight and report.winding_consistent == mesh.is_winding_consistent
    assert report.volume == pytest.approx(mesh.volume, rel=1e-12)


def test_a_missing_triangle_is_not_watertight(plate):
    report = _check(plate, plate.faces[1:])
    assert not report.watertight and not report.winding_consistent and not report.ok


def test_a_flipped_triangle_is_watertight_but_inconsistently_wound(plate):
    faces = plate.faces.copy()
    faces[7] = faces[7, ::-1]
    report = _check(plate, faces)
    assert report.watertight and not report.winding_consistent and not report.ok


def test_a_duplicated_triangle_is_refused(plate):
    report = _check(plate, np.vstack([plate.faces, plate.faces[:1]]))
    assert not report.watertight and not report.ok


def test_vertices_that_coincide_once_written_are_merged_as_a_strict_reader_merges(plate):
    """A vertex moved onto its neighbour once written (float32, as the STL stores it) makes
    the triangles between them zero-area: the check reads the mesh as written and fails it,
    while the same mesh with every vertex doubled (split but coincident) passes."""
    far = Part("plate", plate.vertices + 100.0, plate.faces, plate.expected_volume)
    assert check_part(far).watertight
    a, b = plate.faces[0][:2]
    collapsed = far.vertices.copy()
    collapsed[b] = collapsed[a]
    assert not check_part(Part("plate", collapsed, far.faces, far.expected_volume)).watertight
    n = len(far.vertices)
    doubled_faces = far.faces.copy()
    doubled_faces[::2] += n
    doubled = Part("plate", np.vstack([far.vertices, far.vertices]), doubled_faces, far.expected_volume)
    assert check_part(doubled).watertight and check_part(doubled).winding_consistent
