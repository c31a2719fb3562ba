"""Elephant-foot compensation keeps the part one closed shell with its exact volume."""

import numpy as np
import pytest
import trimesh

from wheelstep_cli.errors import DesignError
from wheelstep_cli.geometry.solids import circle, extrude_plate, inset_bottom


@pytest.fixture(scope="module")
def footed():
    plate = extrude_plate("plate", circle(20.0, 96) * [1.5, 1.0], 5.0, 8.0)
    return plate, inset_bottom(plate, 0.2, 0.3)


def test_one_watertight_body_without_degenerate_triangles(footed):
    _, part = footed
    mesh = trimesh.Trimesh(part.vertices, part.faces, process=False)
    assert len(mesh.split(only_watertight=False)) == 1
    merged = trimesh.Trimesh(part.vertices, part.faces)   # what a reader merging vertices sees
    assert merged.is_watertight and merged.is_winding_consistent
    assert len(merged.split(only_watertight=False)) == 1
    assert mesh.area_faces.min() > 1e-6
    # the 3MF writes 5 decimals: no edge shorter than that collapses
    assert mesh.edges_unique_length.min() > 1e-4


def test_volume_is_the_expected_volume_and_the_bottom_is_inset(footed):
    plate, part = footed
    volume = trimesh.Trimesh(part.vertices, part.faces).volume
    assert volume == pytest.approx(part.expected_volume, rel=1e-7)
    assert volume < plate.expected_volume
    bottom = part.vertices[np.isclose(part.vertices[:, 2], 0.0)]
    top = part.vertices[np.isclose(part.vertices[:, 2], 5.0)]
    assert bottom[:, 0].max() == pytest.approx(top[:, 0].max() - 0.3, abs=1e-3)


def test_foot_taller_than_half_the_part_is_refused():
    plate = extrude_plate("plate", circle(20.0, 64), 1.0)
    with pytest.raises(DesignError) as err:
        inset_bottom(plate, 0.6, 0.2)
    assert err.value.param == "elephant_foot_height"
