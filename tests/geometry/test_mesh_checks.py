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
