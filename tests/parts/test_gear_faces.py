"""Shaft holes, timing marks and the assembly phase of the gear pair (issue 12 items 1-2)."""

import numpy as np
import pytest
import shapely
from shapely import affinity

from wheelstep_cli.config.profiles import load_printer_profile
from wheelstep_cli.config.specs import GearPairSpec
from wheelstep_cli.gears.meshing.outlines import rotate
from wheelstep_cli.geometry.mesh_checks import Part
from wheelstep_cli.geometry.solids import (circle, extrude_gear, manifold_of, section_outline,
                                           section_rings, solid_from_polygons)
from wheelstep_cli.parts.gear_faces import GearFace, gear_faces, pair_law, shaft_hole
from wheelstep_cli.parts.gear_pair import build_gear_pair, gear_pair_report
from wheelstep_cli.parts.kinds import KINDS, printed_spec
from wheelstep_cli.parts.mesh_check import check_outlines

SHAPES = ("round", "d-flat", "keyway", "hex")


def nominal_shaft(spec, angle: float) -> np.ndarray:
    """The shaft of nominal size (mm) with its key/flat along ``angle`` rad, built with
    shapely independently of the part's hole code (round parts inscribed, finely)."""
    r = spec.bore / 2.0
    disc = shapely.Point(0.0, 0.0).buffer(r, quad_segs=256)
    if spec.bore_shape == "d-flat":
        shaft = disc.intersection(shapely.box(-2 * r, -2 * r, r - spec.flat_depth, 2 * r))
    elif spec.bore_shape == "keyway":
        key = shapely.box(0.0, -spec.key_width / 2.0, r + spec.key_depth, spec.key_width / 2.0)
        shaft = disc.union(key)
    elif spec.bore_shape == "hex":
        t = np.pi / 6.0 + np.arange(6) * np.pi / 3.0
        shaft = shapely.Polygon(r / np.cos(np.pi / 6.0) * np.column_stack([np.cos(t), np.sin(t)]))
    else:
        shaft = disc
    shaft = affinity.rotate(shaft, angle, origin=(0.0, 0.0), use_radians=True)
    return np.asarray(shapely.geometry.polygon.orient(shaft, 1.0).exterior.coords)[:-1]


def shaft_solid(ring: np.ndarray):
    """The shaft as a manifold3d solid from z = -5 to 15 mm (through a 10 mm plate)."""
    part = solid_from_polygons("shaft", [ring], 20.0, 0.0)
    return manifold_of(Part("shaft", part.vertices - [0.0, 0.0, 5.0], part.faces, 0.0))


def overlap(plate, ring: np.ndarray) -> float:
    return (manifold_of(plate) ^ shaft_solid(ring)).volume()


@pytest.mark.parametrize("shape", SHAPES)
def test_nominal_shaft_fits_the_compensated_hole_with_clearance_and_not_turned(shape):
    printer = load_printer_profile("fdm-0.4-pla")
    assert printer.hole_compensation > 0
    angle = 0.0 if shape == "round" else 30.0     # a round bore has nothing to orient
    design = GearPairSpec(bore_shape=shape, bore=8, key_angle=angle)
    printed = printed_spec(KINDS["gear-pair"], design, printer)
    mark = 0.7                                   # the mark's direction in the gear frame, rad
    plate = extrude_gear("pinion", circle(30.0, 256), 10.0, shaft_hole(printed, mark), [], 0.0)
    key = mark + np.radians(angle)
    shaft = nominal_shaft(design, key)
    assert overlap(plate, shaft) == pytest.approx(0.0, abs=1e-9)
    # positive clearance: a shaft 0.04 mm fatter all round still fits (compensation 0.2 mm
    # on the diameter leaves 0.1 mm)
    fat = shapely.geometry.polygon.orient(shapely.Polygon(shaft).buffer(0.04, join_style="mitre"), 1.0)
    assert overlap(plate, np.asarray(fat.exterior.coords)[:-1]) == pytest.approx(0.0, abs=1e-9)
    turned = nominal_shaft(design, key + (np.pi / 6.0 if shape == "hex" else np.pi / 2.0))
    if shape == "round":
        assert overlap(plate, turned) == pytest.approx(0.0, abs=1e-9)  # carries no phase
    else:
        assert overlap(plate, turned) > 0.05


@pytest.mark.parametrize("shape, bore", [("keyway", 12.0), ("d-flat", 8.0), ("hex", 8.0),
                                         ("round", 5.0), ("round", 8.0)])
def test_a_set_screw_through_a_hub_leaves_a_printable_part_at_every_key_angle(shape, bore):
    # the screw hole runs along the key angle: where it met a corner of the hub's or the
    # bore's polygon edge-on, the cut left edges shorter than float32 resolves
    from wheelstep_cli.geometry.mesh_checks import require_printable
    from wheelstep_cli.parts.gear_faces import _set_screw

    mark = 0.0
    for angle in range(0, 360, 15):
        design = GearPairSpec(bore_shape=shape, bore=bore, key_angle=angle, hub_d=28, set_screw="M3")
        plate = extrude_gear("pinion", circle(38.0, 512), 10.0, shaft_hole(design, mark), [], 0.0,
                             hub=design.hub_mm, set_screw=_set_screw(design, mark))
        require_printable(plate)


@pytest.fixture(scope="module")
def keyed_pair():
    return build_gear_pair(GearPairSpec(bore_shape="keyway", key_angle=40))


def test_gear_faces_are_data_in_the_gear_frame(keyed_pair):
    faces = gear_faces(keyed_pair)
    assert set(faces) == {"pinion", "wheel"}
    for name, face in faces.items():
        assert isinstance(face, GearFace) and face.name == name
        assert face.outline.shape[1] == 2 and len(face.holes) == 1 and len(face.marks) == 1
    # the wheel's mark carries the carrier's crossbar: more points than the pinion's arrow
    assert len(faces["wheel"].marks[0]) > len(faces["pinion"].marks[0])


def test_marks_are_engraved_in_the_top_face_and_the_part_stays_one_body(keyed_pair):
    phase = gear_pair_report(keyed_pair)["phase"]["carrier_zero"]
    for part, deg in ((keyed_pair.pinion, phase["pinion_deg"]), (keyed_pair.wheel, phase["wheel_deg"])):
        assert len(manifold_of(part).decompose()) == 1
        assert keyed_pair.checks[part.name].watertight
        mid, top = section_rings(part, 5.0), section_rings(part, 9.75)
        assert len(top) == len(mid) + 1                   # the mark's groove
        groove = min(top, key=lambda r: abs(shapely.Polygon(r).area) if
                     np.min(np.hypot(*r.T)) > 5.5 else np.inf)
        centre = groove.mean(axis=0)
        assert np.degrees(np.arctan2(centre[1], centre[0])) % 360 == pytest.approx(deg % 360, abs=2)
        assert len(section_rings(part, 9.0)) == len(mid)  # 0.5 mm deep: gone 1 mm below the top


def keyway_direction(part) -> float:
    """Direction (rad) of the keyway measured on the mesh: the hole's points beyond the bore."""
    hole = min(section_rings(part, 5.0), key=lambda r: abs(shapely.Polygon(r).area))
    far = hole[np.hypot(*hole.T) > 4.5]
    return float(np.arctan2(far[:, 1].mean(), far[:, 0].mean()))


def test_keyed_parts_on_keyed_shafts_mesh_in_phase_and_a_tooth_off_does_not(keyed_pair):
    phase = gear_pair_report(keyed_pair)["phase"]
    key = phase["shaft"]["key_angle_deg"]
    outlines = {}
    for part, deg in ((keyed_pair.pinion, phase["carrier_zero"]["pinion_deg"]),
                      (keyed_pair.wheel, phase["carrier_zero"]["wheel_deg"])):
        # the shaft's key as gears.json says, the gear turned until its keyway sits on it
        turn = np.radians(deg + key) - keyway_direction(part)
        outlines[part.name] = rotate(section_outline(part.vertices, part.faces, part.name), turn)
    law, distance = pair_law(keyed_pair), keyed_pair.mounted_distance
    in_phase = check_outlines(outlines["pinion"], outlines["wheel"], law, distance).to_dict()
    assert in_phase["in_phase"] and not in_phase["interference"]
    off = check_outlines(rotate(outlines["pinion"], 2.0 * np.pi / keyed_pair.spec.z), outlines["wheel"],
                         law, distance, samples=96).to_dict()
    assert not off["in_phase"]


def test_lighten_keeps_the_meshing_outlines_and_reports_what_it_saves(keyed_pair):
    light = build_gear_pair(GearPairSpec(bore_shape="keyway", key_angle=40, lighten=True))
    record = gear_pair_report(light)["lighten"]
    assert record["density_g_cm3"] == 1.24 and "PLA" in record["density_from"]
    for name in ("pinion", "wheel"):
        full, cut = getattr(keyed_pair, name), getattr(light, name)
        # the meshing check sections the outer boundary: the teeth are the same points
        assert np.array_equal(section_outline(full.vertices, full.faces, name),
                              section_outline(cut.vertices, cut.faces, name))
        saved = keyed_pair.checks[name].volume - light.checks[name].volume
        assert record[name]["pockets"] == 5
        assert saved / 1000.0 == pytest.approx(record[name]["volume_saved_cm3"], rel=1e-6)
        assert len(manifold_of(cut).decompose()) == 1
    # the rim: every pocket point at least 2.5 modules under the wheel's root
    faces = gear_faces(light)
    root = np.min(np.hypot(*light.wheel_outline.T))
    module = light.generated.module
    for pocket in faces["wheel"].holes[1:]:
        assert np.max(np.hypot(*pocket.T)) <= root - 2.5 * module + 1e-6
    assert record["wheel"]["volume_saved_cm3"] > 100.0       # the 285 cm3 disc loses over a third


def test_a_hex_shaft_puts_the_gear_in_phase_in_as_many_of_its_six_ways_as_gears_json_says(keyed_pair):
    from wheelstep_cli.parts.gear_phase import in_phase_positions

    law = pair_law(keyed_pair)
    for outline, periods in ((keyed_pair.pinion_outline, law.pinion_periods),
                             (keyed_pair.wheel_outline, law.wheel_periods)):
        ring = shapely.Polygon(outline)
        # a gear turned by a sixth of a turn k times is in phase when its teeth land on themselves
        landed = sum(1 for k in range(6)
                     if ring.hausdorff_distance(affinity.rotate(ring, 60.0 * k, origin=(0, 0))) < 1e-3)
        assert landed == in_phase_positions(6, periods) < 6
    assert in_phase_positions(1, law.pinion_periods) == 1          # a key fits one way: in phase
