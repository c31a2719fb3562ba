"""The 2D faces of the gears (mm, each gear's own frame): teeth ring, shaft hole, timing marks.

The faces are what each gear's top looks like: ``outline`` the teeth ring (CCW), ``holes``
the shaft hole ring(s), ``marks`` the engraved timing marks as closed polylines. The marks
point along the body direction that meets the other gear on the line of centres with the
carrier at 0 (gears.phase); the shaft hole's key, flat or hex flat faces ``--key-angle``
from it, so a keyed shaft puts the pair in phase.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.gears import bore_shapes as shapes
from wheelstep_cli.gears.phase import assembly_phase
from wheelstep_cli.geometry.hole_walls import (MIN_HOLE_WALL, corner_clear_of, hole_reach, require_hub_clears_hole,
                                              require_screw_fits)
from wheelstep_cli.geometry.planar import min_radius, signed_area, spoked_pockets
from wheelstep_cli.geometry.solids import bore_segments, extrude_gear

#: Radial gap (mm) between a mark and the hole or the root.
MARK_GAP = 1.0
#: --lighten: rim under the root (x module), spokes, least web round the hole and spoke
#: width (mm), pocket corner fillet (mm); PLA density (g/cm3) when no printer says.
RIM_MODULES, SPOKES, WEB, SPOKE_WIDTH, POCKET_FILLET, PLA_DENSITY = 2.5, 5, 4.0, 6.0, 2.0, 1.24


@dataclass(frozen=True)
class GearFace:
    """One gear's top face in mm in its own frame."""

    name: str
    outline: np.ndarray            # (N, 2) teeth ring, CCW
    holes: list[np.ndarray]        # shaft hole ring(s), CCW
    marks: list[np.ndarray]        # timing marks, closed polylines (CCW rings)
    direction: float = 0.0         # rad, the mark's direction (the phase's body angle)
    pocket_span: tuple[float, float] = (0.0, 0.0)   # mm, radii the --lighten pockets may span


def shaft_hole(spec, direction: float) -> np.ndarray | None:
    """The shaft hole of ``spec`` (a GearPairSpec, mm) with its key/flat along ``direction``
    + key_angle (rad); None without a bore."""
    if not spec.bore > 0:
        return None
    angle = direction + np.radians(spec.key_angle)
    segments = bore_segments(spec.bore)
    if spec.bore_shape == "d-flat":
        return shapes.d_flat_hole(spec.bore, spec.flat_depth, angle, segments)
    if spec.bore_shape == "keyway":
        return shapes.keyway_hole(spec.bore, spec.key_width, spec.key_depth, angle, segments)
    if spec.bore_shape == "hex":
        return shapes.hex_hole(spec.bore, angle)
    # a set screw's hole runs along the angle
    return shapes.round_hole(spec.bore, segments,
                             0.0 if spec.set_screw is None else corner_clear_of(angle, segments))


def timing_marks(outline: np.ndarray, hole: np.ndarray | None, direction: float,
                 carrier: bool, hub: float = 0.0) -> list[np.ndarray]:
    """The arrow (with the carrier's crossbar on the wheel) between hole (or the ``hub``
    diameter, mm) and root, pointing
    along ``direction`` (rad); none when the web is too narrow for one."""
    inner, outer = _mark_span(outline, hole, hub)
    if outer - inner < MARK_LENGTH:
        return []
    return [shapes.arrow_mark(inner, outer, direction, bar=carrier)]


#: Shortest arrow a timing mark is drawn as (mm): its head and a stem of two widths.
MARK_LENGTH = shapes.HEAD_LENGTH + 2.0 * shapes.MARK_WIDTH


def _mark_span(outline: np.ndarray, hole: np.ndarray | None, hub: float) -> tuple[float, float]:
    """The radii (mm) a timing mark may run between: MARK_GAP clear of the hole or hub
    (``hub`` its diameter, mm) and of the tooth roots."""
    inner = max(hole_reach(hole), hub / 2.0) + MARK_GAP
    return inner, min_radius(outline) - MARK_GAP


def _no_room_for_mark(name: str, outline: np.ndarray, hole, spec, unmarked: bool = True):
    """The refusal (DesignError) of a gear whose web has no room for its timing mark: the pair
    is set in phase by its marks, and a gear left without one could not be. Each input that
    narrows the web and would make room if smaller is stated with the value that does (mm);
    ``unmarked``: the gear as it is would be built without marks (--mark-depth 0 is offered)."""
    from wheelstep_cli.errors import DesignError, rounded_down

    inner, outer = _mark_span(outline, hole, spec.hub_mm[0])
    short = MARK_LENGTH - (outer - inner)
    around = "hub" if spec.hub_d else "bore" if hole is not None else "axis"
    room = (f"leaves the {name} no room for its timing mark ({max(outer - inner, 0.0):.1f} mm of web "
            f"between the {around} and the tooth roots, the mark needs {MARK_LENGTH:.1f} mm)")
    reach = hole_reach(hole)
    limits, hole_room = {}, reach - short
    if spec.hub_d and spec.hub_mm[0] / 2.0 >= reach and spec.hub_mm[0] - 2.0 * short > 0:
        largest_hub = spec.hub_mm[0] - 2.0 * short
        if largest_hub / 2.0 >= reach + MIN_HOLE_WALL:
            limits["hub_d"] = (spec.hub_d, largest_hub)
        else:
            # no hub leaves the mark its web and the hole its wall (a hub_d limit would be
            # refused again as too small for the hole): the hole is what to make smaller
            hole_room = largest_hub / 2.0 - MIN_HOLE_WALL
    if not limits and hole is not None and hole_room > 0:
        for param in (["key_depth"] if spec.bore_shape == "keyway" else []) + ["bore"]:
            largest = _largest_hole(spec, param, hole_room)
            if largest > 0:
                limits[param] = (getattr(spec, param), largest)
    no_marks = "--mark-depth 0 for no marks" if unmarked else ""
    said = {param: (value, f"must be <= {rounded_down(largest)} mm: larger, it {room}"
                           + (f"; or {no_marks}" if no_marks else "")) for param, (value, largest) in limits.items()}
    remedy = ", or ".join([f"--{param.replace('_', '-')} <= {rounded_down(largest)} mm"
                           for param, (_, largest) in limits.items()] + ([no_marks] if no_marks else []))
    # what narrows the web, the most specific first: named when the user gave it
    refused = DesignError("mark_depth", spec.mark_depth, f"{room}: {remedy}", said).tied_to(
        {"key_width": spec.key_width, "bore_shape": spec.bore_shape})
    if no_marks:        # the one value the line offers (the others are limits), for a script
        refused.remedy, refused.remedies = {"mark_depth": 0.0}, [{"mark_depth": 0.0}]
    return refused


def _largest_hole(spec, param: str, reach: float) -> float:
    """The largest ``param`` (bore or key_depth, mm, at most the spec's) whose shaft hole
    reaches at most ``reach`` mm from the axis; 0 when none does. A key or flat the bore's
    defaults gave follows the bore (a smaller bore takes its smaller DIN key), one given is
    kept (smaller DIN keys of a smaller bore only reach less)."""
    from wheelstep_cli.errors import rounded_down

    def changed(value: float):
        return spec.model_copy(update={param: value, **_following(spec, param, value)})

    def fits(value: float) -> bool:
        hole = changed(value)
        # a bore under its key or flat is no hole: those values lie below every one that fits
        return not _valid_hole(hole) or hole_reach(shaft_hole(hole, 0.0)) <= reach

    low, high = 0.0, float(getattr(spec, param))
    for _ in range(40):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if fits(middle) else (low, middle)
    # as the line will print it, and checked there (the polygon's sides change with the bore)
    shown = float(rounded_down(low))
    while shown > 0 and not fits(shown):
        shown = round(shown - 0.01, 2)
    return shown if shown > 0 and _valid_hole(changed(shown)) else 0.0


def _following(spec, param: str, bore: float) -> dict:
    """The key or flat dimensions (name -> mm) that follow ``bore`` when ``param`` is the bore
    and the spec's are its bore's defaults (config.shaft_rules.bore_defaults); none otherwise."""
    if param != "bore":
        return {}
    if spec.bore_shape == "keyway" and (spec.key_width, spec.key_depth) == shapes.din_6885_key(spec.bore):
        return dict(zip(("key_width", "key_depth"), shapes.din_6885_key(bore)))
    if spec.bore_shape == "d-flat" and spec.flat_depth == round(0.1 * spec.bore, 6):
        return {"flat_depth": round(0.1 * bore, 6)}
    return {}


def _valid_hole(spec) -> bool:
    """Whether ``spec``'s shaft hole is one its rules take: a key narrower than the bore, a
    flat shallower than its radius."""
    if spec.bore_shape == "keyway":
        return spec.key_width < spec.bore
    if spec.bore_shape == "d-flat":
        return spec.flat_depth < spec.bore / 2.0
    return True


#: Least radial room (mm) for a pocket: its two corner fillets and 3 mm between them.
POCKET_ROOM = 2.0 * POCKET_FILLET + 3.0


def pocket_span(outline: np.ndarray, hole: np.ndarray | None, spec, module: float) -> tuple[float, float]:
    """Radii (mm) a --lighten pocket may span: from a web round the hole or hub out to a rim
    of RIM_MODULES modules (``module`` mm) under the roots."""
    r_in = max(hole_reach(hole), spec.hub_mm[0] / 2.0) + \
        max(WEB, 0.5 * spec.bore)
    return r_in, min_radius(outline) - RIM_MODULES * module


def pockets(span: tuple[float, float], spec, direction: float) -> list[np.ndarray]:
    """--lighten pockets (CCW rings, mm) between spokes, the first spoke under the mark,
    spanning the radii ``span`` (mm, see :func:`pocket_span`); none if no room."""
    r_in, r_out = span
    if not spec.lighten or r_out - r_in < POCKET_ROOM:
        return []
    width = max(SPOKE_WIDTH, 0.1 * r_out)
    return spoked_pockets(r_in, r_out, SPOKES, width, direction, POCKET_FILLET)


def face_of(name: str, outline: np.ndarray, spec, direction: float, module: float) -> GearFace:
    """The face of gear ``name`` (pinion or wheel) whose mark points along ``direction``;
    ``module`` (mm) sizes the --lighten rim. ``holes``: the shaft hole, then any pockets."""
    hole = shaft_hole(spec, direction)
    marks = timing_marks(outline, hole, direction, carrier=name == "wheel", hub=spec.hub_mm[0])
    span = pocket_span(outline, hole, spec, module)
    cut = pockets(span, spec, direction)
    return GearFace(name, np.asarray(outline, dtype=float), ([] if hole is None else [hole]) + cut,
                    marks, float(direction), span)


def saved(face: GearFace, spec) -> float:
    """Volume (mm3) the --lighten pockets remove from the gear."""
    first = 1 if spec.bore > 0 else 0
    return float(sum(signed_area(p) for p in face.holes[first:]) * spec.thickness)


def lighten_record(faces: dict[str, GearFace], spec, printer) -> dict:
    """Volume (cm3) and mass (g) the pockets save per gear, and the density used."""
    density = printer.density if printer is not None else PLA_DENSITY
    source = (f"printer profile {printer.name}" if printer is not None
              else f"PLA {PLA_DENSITY} g/cm3 (no --printer given)")
    first = 1 if spec.bore > 0 else 0
    return {"density_g_cm3": density, "density_from": source,
            "rim_modules": RIM_MODULES, "spokes": SPOKES,
            **{name: {"pockets": len(face.holes) - first,
                      "volume_saved_cm3": saved(face, spec) / 1000.0,
                      "mass_saved_g": saved(face, spec) / 1000.0 * density}
               for name, face in faces.items()}}


def require_hub_round_hole(spec) -> None:
    """Refuse (DesignError) a hub (--hub-d) or set screw that cannot fit round the shaft hole
    of ``spec`` (a GearPairSpec, mm) whatever the teeth: checked before they are generated
    (the limits the teeth's roots set come with the solids)."""
    reach = hole_reach(shaft_hole(spec, 0.0))
    screw = _set_screw(spec, 0.0)
    if screw is not None:
        # first: its nut needs more hub round the hole than the hole's own wall
        name, _, drop, flats, height = screw
        require_screw_fits(name, reach, spec.hub_mm, float(spec.thickness), flats, height, drop)
    if spec.hub_d is not None:
        require_hub_clears_hole(reach, float(spec.hub_d))


def _set_screw(spec, direction: float):
    """The set screw solids.extrude_gear cuts (along the key/flat), or None."""
    if spec.set_screw is None:
        return None
    diameter, flats, height = shapes.SET_SCREWS[spec.set_screw]
    return (spec.set_screw, direction + np.radians(spec.key_angle), shapes.teardrop(diameter),
            flats + shapes.PRINT_PLAY, height + shapes.PRINT_PLAY)


def gear_part(face: GearFace, spec):
    """The gear's printable plate (geometry.mesh_checks.Part) from its face."""
    hole = face.holes[0] if spec.bore > 0 else None
    cut = face.holes[1 if spec.bore > 0 else 0:]
    param = {"keyway": "key_depth", "d-flat": "bore", "hex": "bore"}.get(spec.bore_shape, "bore")
    value = spec.key_depth if param == "key_depth" else spec.bore
    keyed = (float(spec.bore), float(spec.key_width)) if param == "key_depth" else None
    no_mark = _no_room_for_mark(face.name, face.outline, hole, spec) if not face.marks and spec.mark_depth > 0 \
        else None
    if no_mark is not None and set(no_mark.alternatives) & {"hub_d", "bore", "key_depth"}:
        # before the solid's own checks: a smaller hole or hub making room for the marks is the
        # binding limit (the walls the solid needs are narrower); with no such limit (the gear
        # too small for any mark) the solid's walls are said first, then the marks. Without
        # marks offered only where those walls hold
        if not _walls_hold(face, spec, hole, (param, value, keyed)):
            no_mark = _no_room_for_mark(face.name, face.outline, hole, spec, unmarked=False)
        raise no_mark
    part = extrude_gear(face.name, face.outline, spec.thickness, hole, face.marks,
                        spec.mark_depth, param, value, cut, spec.chamfer_mm, spec.hub_mm,
                        _set_screw(spec, face.direction), keyed)
    if no_mark is not None:
        raise no_mark
    if spec.lighten and face.name == "wheel" and not cut:
        _no_room_for_pockets(face, spec)
    return part


def _walls_hold(face: GearFace, spec, hole, sized: tuple) -> bool:
    """Whether the gear's plate keeps its walls round the shaft ``hole`` (``sized``: the input
    that sizes it, its value and a keyed bore's (bore, key width), as extrusion takes them) and
    the hub: the checks extruding it makes, cheap and before any solid."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.geometry.hole_walls import require_hub_fits, require_wall

    try:
        if hole is not None:
            require_wall(face.name, face.outline, hole, *sized)
        if spec.hub_mm[0] > 0:
            require_hub_fits(face.outline, hole, spec.hub_mm[0])
    except DesignError:
        return False
    return True


def _no_room_for_pockets(face: GearFace, spec) -> None:
    """Refuse (DesignError) --lighten on a pair whose wheel has no room for pockets: the
    option would cut nothing (the pinion, smaller, may go without where it has no room)."""
    from wheelstep_cli.errors import DesignError

    r_in, r_out = face.pocket_span
    around = "hub" if spec.hub_d else "bore" if spec.bore > 0 else "axis"
    room = (f"{max(r_out - r_in, 0.0):.1f} mm between the web round the {around} and a {RIM_MODULES} "
            f"module rim under the roots")
    why = (f"({room}, a pocket needs {POCKET_ROOM:.1f} mm)" if r_out - r_in < POCKET_ROOM
           else f"(its {SPOKES} spokes leave no pocket in the {room})")
    remedies = ["a larger --center-distance"] + [f"a smaller --{name}" for name, given in
                                                 (("hub-d", spec.hub_d), ("bore", spec.bore)) if given]
    raise DesignError("lighten", True,
                      f"leaves no room for pockets in the wheel {why}: {', '.join(remedies)}, or "
                      "print without --lighten"
                      ).tied_to({"hub_d": spec.hub_d, "bore": spec.bore,
                                 "center_distance": getattr(spec, "center_distance", None)})


def faces_for(spec, law, pinion_outline: np.ndarray, wheel_outline: np.ndarray,
              module: float) -> dict[str, GearFace]:
    """Both faces of a pair following ``law`` (gears.transmission law), module in mm."""
    phase = assembly_phase(law)
    return {"pinion": face_of("pinion", pinion_outline, spec, phase.pinion_mark, module),
            "wheel": face_of("wheel", wheel_outline, spec, phase.wheel_mark, module)}


def pair_law(pair):
    """The law the pair's teeth follow (generated: the blended law they were cut for)."""
    generated = getattr(pair, "generated", None)
    return generated.law if generated is not None else pair.law


def gear_faces(pair) -> dict[str, GearFace]:
    """``{"pinion": GearFace, "wheel": GearFace}`` of a built parts.gear_pair.GearPair."""
    return faces_for(pair.spec, pair_law(pair), pair.pinion_outline, pair.wheel_outline,
                     pair_module(pair))


def pair_module(pair) -> float:
    """The pair's module (mm): the generated teeth's, else the paper teeth's."""
    generated = getattr(pair, "generated", None)
    return float(generated.module) if generated is not None else float(pair.spec.paper_module)
