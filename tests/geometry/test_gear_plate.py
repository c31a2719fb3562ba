"""geometry.solids.extrude_gear: chamfered edges, engraved marks, pockets as one closed body."""

import numpy as np
import pytest

from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.bore_shapes import arrow_mark, keyway_hole
from wheelstep_cli.geometry.mesh_checks import require_printable
from wheelstep_cli.geometry.planar import signed_area
from wheelstep_cli.geometry.solids import extrude_gear, manifold_of, section_outline, section_rings


def toothed(teeth: int = 24, r: float = 30.0, h: float = 2.0) -> np.ndarray:
    """A crude toothed ring (mm, CCW): square-ish teeth on a circle."""
    t = np.linspace(0.0, 2.0 * np.pi, teeth * 16, endpoint=False)
    bump = (np.mod(t * teeth / (2.0 * np.pi), 1.0) < 0.5).astype(float)
    radius = r + h * bump
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)])


def plate(chamfer: float):
    hole = keyway_hole(8.0, 2.0, 1.0, 0.3, 64)
    marks = [arrow_mark(7.0, 25.0, 0.3, bar=True)]
    return extrude_gear("wheel", toothed(), 10.0, hole, marks, 0.5, chamfer=chamfer)


def test_chamfer_keeps_one_closed_body_and_the_mid_section():
    plain, cut = plate(0.0), plate(0.5)
    report = require_printable(cut)                    # watertight, volume matches the outline math
    assert report.watertight and len(manifold_of(cut).decompose()) == 1
    assert np.array_equal(section_outline(plain.vertices, plain.faces, "p"),
                          section_outline(cut.vertices, cut.faces, "c"))
    # 0.05 mm above the bed the outline is drawn in by about 0.45 mm
    low = max(section_rings(cut, 0.05), key=lambda r: abs(signed_area(r)))
    mid = max(section_rings(cut, 5.0), key=lambda r: abs(signed_area(r)))
    lost = (abs(signed_area(mid)) - abs(signed_area(low))) / np.sum(np.hypot(*np.diff(
        np.vstack([mid, mid[:1]]), axis=0).T))
    assert 0.35 < lost < 0.5


def test_chamfer_must_leave_a_middle():
    with pytest.raises(DesignError, match="chamfer"):
        plate(5.0)


def test_hub_stands_on_the_top_face_round_the_hole_as_one_body():
    hole = keyway_hole(8.0, 2.0, 1.0, 0.3, 64)
    part = extrude_gear("pinion", toothed(), 10.0, hole, [arrow_mark(12.0, 25.0, 0.3)], 0.5,
                        hub=(20.0, 6.0))
    assert require_printable(part).watertight and len(manifold_of(part).decompose()) == 1
    assert part.bounds[1, 2] == pytest.approx(16.0)
    above = section_rings(part, 13.0)                 # hub ring: outer circle and the keyway
    assert len(above) == 2
    outer = max(above, key=lambda r: abs(signed_area(r)))
    assert np.max(np.hypot(*outer.T)) == pytest.approx(10.0, abs=0.01)
    with pytest.raises(DesignError, match="hub_d"):
        extrude_gear("pinion", toothed(), 10.0, hole, [], 0.5, hub=(60.0, 6.0))


def test_set_screw_opens_the_hub_wall_and_a_nut_slot_from_the_top():
    from wheelstep_cli.gears.bore_shapes import PRINT_PLAY, SET_SCREWS, d_flat_hole, teardrop

    hole = d_flat_hole(8.0, 0.8, 0.0, 64)
    d, flats, height = SET_SCREWS["M3"]
    screw = ("M3", 0.0, teardrop(d), flats + PRINT_PLAY, height + PRINT_PLAY)
    plain = extrude_gear("pinion", toothed(), 10.0, hole, [], 0.5, hub=(22.0, 10.0))
    part = extrude_gear("pinion", toothed(), 10.0, hole, [], 0.5, hub=(22.0, 10.0), set_screw=screw)
    assert require_printable(part).watertight and len(manifold_of(part).decompose()) == 1
    assert part.expected_volume < plain.expected_volume
    # at the screw's axis (z = 15) the hub ring is cut open along +x: one ring, not two
    assert len(section_rings(plain, 15.0)) == 2 and len(section_rings(part, 15.0)) == 1
    assert len(section_rings(part, 5.0)) == len(section_rings(plain, 5.0))   # plate untouched
    with pytest.raises(DesignError, match="set_screw"):
        extrude_gear("pinion", toothed(), 10.0, hole, [], 0.5, hub=(14.0, 10.0), set_screw=screw)


def test_chamfer_with_a_hub_keeps_the_teeth_chamfered_and_the_bore_straight_into_the_hub():
    hole = keyway_hole(8.0, 2.0, 1.0, 0.3, 64)
    marks = [arrow_mark(12.0, 25.0, 0.3)]
    part = extrude_gear("pinion", toothed(), 10.0, hole, marks, 0.5, chamfer=0.5, hub=(20.0, 6.0))
    plain = extrude_gear("pinion", toothed(), 10.0, hole, marks, 0.5, hub=(20.0, 6.0))
    # one closed body whose volume is the one summed from the 2D sections
    assert require_printable(part).watertight and len(manifold_of(part).decompose()) == 1
    assert part.bounds[1, 2] == pytest.approx(16.0)

    def rings(z):
        """Areas (mm2) of the outer ring and of the shaft hole (the ring nearest the axis)."""
        found = section_rings(part, z)
        outer = max(found, key=lambda r: abs(signed_area(r)))
        hole = min(found, key=lambda r: np.max(np.hypot(*r.T)))
        return abs(signed_area(outer)), abs(signed_area(hole))

    teeth_mid, bore = rings(5.0)
    teeth_top, bore_top = rings(9.95)
    teeth_bottom, bore_bottom = rings(0.05)
    assert teeth_top < teeth_mid - 5.0 and teeth_bottom < teeth_mid - 5.0   # teeth chamfered
    assert bore_top == pytest.approx(bore, rel=1e-6)     # the hub fills the bore's top chamfer
    assert bore_bottom > bore + 5.0                        # its bottom edge keeps the chamfer
    # the same hub and hole on the plain plate: only the teeth's chamfers differ
    assert section_outline(plain.vertices, plain.faces, "p").shape == \
        section_outline(part.vertices, part.faces, "c").shape
