"""3MF plates: parts in their own frames placed by build-item transforms, their design in
3MF 1.2 object metadata, PrusaSlicer's configuration inside; read back strictly by lib3mf."""

import zipfile

import numpy as np
import pytest

from tests.helpers.meshcheck import read_3mf_strict
from wheelstep_cli.formats.mesh_read import read_3mf_objects
from wheelstep_cli.formats.slicer_config import slic3r_config_bytes, slicer_ini_bytes
from wheelstep_cli.formats.threemf import (SLICER_CONFIG, item_transform, placed_object,
                                           placed_vertices, threemf_bytes)

CUBE_V = np.array([[x, y, z] for x in (0, 10) for y in (0, 20) for z in (0, 5)], dtype=float) - [5, 10, 0]
CUBE_F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                   [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])


def test_transform_is_a_turn_about_z_then_a_shift_in_row_vector_form():
    assert item_transform(0.0, (1, 2, 3)) == "1 0 0 0 1 0 0 0 1 1.00000 2.00000 3.00000"
    text = item_transform(np.pi / 2, (7, 8, 0))
    m = np.array([float(t) for t in text.split()]).reshape(4, 3)
    # a point on +x goes to +y (counter-clockwise), then is shifted
    assert np.allclose(np.array([1.0, 0.0, 0.0, 1.0]) @ m, [7.0, 9.0, 0.0])
    assert text.startswith("0 1 0 -1 0 0 0 0 1 ")


@pytest.mark.parametrize("rotated", [False, True])
def test_placed_object_puts_the_box_corner_where_asked_and_keeps_the_frame(rotated):
    obj = placed_object("cube", CUBE_V, CUBE_F, (30.0, 40.0), rotated, {"part": "pinion"})
    assert obj.vertices is CUBE_V                      # the frame is not touched
    placed = placed_vertices(obj)
    assert np.allclose(placed.min(axis=0), [30.0, 40.0, 0.0])
    size = placed.max(axis=0) - placed.min(axis=0)
    assert np.allclose(size, [20, 10, 5] if rotated else [10, 20, 5])


def test_plate_reads_back_strict_with_frames_transforms_metadata_and_slicer_config(tmp_path):
    objects = [placed_object("a pinion", CUBE_V, CUBE_F, (5.0, 5.0), False,
                             {"part": "pinion", "pair": "p/1", "install_distance": "72.125"}),
               placed_object("a wheel", CUBE_V, CUBE_F, (30.0, 5.0), True,
                             {"part": "wheel", "pair": "p/1", "install_distance": "72.125"})]
    config = slic3r_config_bytes({"bed_shape": "0x0,200x0,200x200,0x200", "skirts": 1}, "test")
    path = tmp_path / "plate.3mf"
    path.write_bytes(threemf_bytes(objects, {"Title": "t"}, config))
    strict = read_3mf_strict(path)
    assert strict["warnings"] == [] and strict["build_items"] == 2
    with zipfile.ZipFile(path) as zf:
        text = zf.read(SLICER_CONFIG).decode()
    assert "; bed_shape = 0x0,200x0,200x200,0x200\n" in text and "; skirts = 1\n" in text
    read = read_3mf_objects(path, "pinion")
    assert [o.name for o in read] == ["a pinion", "a wheel"]
    assert np.allclose(read[1].vertices, CUBE_V)        # own frame, transform not applied
    assert np.allclose(read[1].transform[:3, :2], [[0, 1], [-1, 0], [0, 0]])
    assert read[0].metadata == {"part": "pinion", "pair": "p/1", "install_distance": "72.125"}


def test_ini_has_the_same_settings_without_comment_marks():
    settings = {"layer_height": 0.2, "fill_density": "30%", "skirts": 1}
    ini = slicer_ini_bytes(settings, "x").decode().splitlines()[1:]
    cfg = slic3r_config_bytes(settings, "x").decode().splitlines()[1:]
    assert ini == [line[2:] for line in cfg] == ["fill_density = 30%", "layer_height = 0.2", "skirts = 1"]
