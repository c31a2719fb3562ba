"""The support shoe as a printable part: design -> side outline -> solid with socket -> files.

The shoe's side outline (the sole curve of SPEC §2 below, a flat top above) lies in the
XY plane and is extruded along Z by the width across the track, so the sole curve is
printed in the plane of the layers (accurate). Part frame, mm: x along the track with
the strut axis at x = 0, y up from the sole's lowest point (y = c - Y of the shoe
frame), z across the track (0..width). The strut socket is a round hole along +y,
open at the top face, centred at x = 0, z = width/2.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from wheelstep_cli.config.specs import ShoeSpec
from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.geometry.planar import check_outline, signed_area
from wheelstep_cli.geometry.mesh_checks import MeshReport, Part, part_record, require_printable
from wheelstep_cli.geometry.solids import bore_segments, circle, extrude_with_socket
from wheelstep_cli.formats.dxf import polyline_dxf_bytes
from wheelstep_cli.formats.jsonio import csv_bytes, json_bytes
from wheelstep_cli.formats.stl import stl_bytes
from wheelstep_cli.parts.plate_layout import (bed_plates, default_printer_said, design_metadata, plate_files,
                                             require_on_bed)
from wheelstep_cli.mechanism.crank import CrankMechanism
from wheelstep_cli.mechanism.sole import sole_curvature_radius
from wheelstep_cli.parts.shoe_socket import check_socket, sole_and_top

#: The socket cutter sticks out of the top face by this much, so no skin is left, mm.
CUT_OVERSHOOT = 1.0
FORMATS = ("stl", "3mf", "both")
SPEC_KEYS = tuple(ShoeSpec.model_fields)


@dataclass(frozen=True)
class Shoe:
    """A built shoe: sizing, the sole (shoe frame), the side outline and the checked part."""

    spec: ShoeSpec
    design: CrankMechanism
    phi: np.ndarray
    profile: np.ndarray   # (N, 2) sole in the shoe frame, mm
    outline: np.ndarray   # closed side outline in the part frame, mm (CCW)
    body_height: float    # y of the top face, mm
    socket_floor: float   # least plastic between the socket and the sole, mm
    parts: list[Part]
    checks: dict[str, MeshReport] = field(default_factory=dict)
    printing: object = None   # parts.kinds.Printing when drawn for a printer (spec: the printed one)
    design_profile: dict | None = None  # the design profile it was made from (config.profiles.profile_record)

    @property
    def part(self) -> Part:
        return self.parts[0]


def side_outline(sole_part: np.ndarray, top: float) -> np.ndarray:
    """Closed side outline: the sole (part frame, x increasing) then up to a flat top at y = ``top``."""
    corners = np.array([[sole_part[-1, 0], top], [sole_part[0, 0], top]])
    return np.vstack([sole_part, corners])


def shoe_solid(spec: ShoeSpec, outline: np.ndarray, top: float) -> Part:
    """Extrude the checked side outline by the width and cut the strut socket from the top face."""
    segments = bore_segments(spec.strut_diameter)
    # circumscribed polygon: its flats touch the nominal circle, so the strut fits
    ring = circle(spec.strut_diameter / 2.0 / np.cos(np.pi / segments), segments)
    expected = signed_area(outline) * spec.width - signed_area(ring) * spec.socket_depth
    return extrude_with_socket("shoe", outline, spec.width, ring, top - spec.socket_depth,
                               spec.socket_depth + CUT_OVERSHOOT, expected)


def build_shoe(spec: ShoeSpec) -> Shoe:
    """Size the mechanism, build and check the shoe; raises DesignError for impossible designs."""
    design, phi, profile, sole_part, top = sole_and_top(spec)
    floor = check_socket(spec, sole_part, top)
    outline = check_outline(side_outline(sole_part, top), "shoe")
    part = shoe_solid(spec, outline, top)
    checks = {part.name: require_printable(part)}
    return Shoe(spec, design, phi, profile, outline, top, floor, [part], checks)


def sizing(design: CrankMechanism) -> dict:
    """Link sizing and hub motion per shoe cycle (SPEC §2), mm and per cent."""
    return {
        "a_mm": design.a, "b_mm": design.b, "c_mm": design.c, "r_min_mm": design.r_min,
        "hub_height_mm": design.hub_height, "x_walk_mm": design.x_walk,
        "x_roll_mm": design.x_roll, "x_cycle_mm": design.x_cycle,
        "roll_share_pct": 100.0 * design.roll_share,
        "r_max_mm": float(sole_curvature_radius(design, np.pi / 4.0)),
    }


def resolved_parameters(shoe: Shoe) -> dict[str, float]:
    """The spec with the strut resolved (both c and r_min given), all as floats in mm."""
    values = shoe.spec.model_dump()
    values["c"], values["r_min"] = shoe.design.c, shoe.design.r_min
    return {k: float(v) for k, v in values.items()}


def shoe_report(shoe: Shoe) -> dict:
    """Inputs, sizing, the sole (shoe frame) and the part with its checks, as plain data
    (with the printer and the printed parameters when drawn for one)."""
    from wheelstep_cli.parts.kinds import made_from

    part = shoe.part
    check = shoe.checks[part.name]
    return {
        "tool": "wheelstep shoe",
        **made_from(shoe),
        "parameters": resolved_parameters(shoe),
        **_printing(shoe),
        **sizing(shoe.design),
        "profile_frame": "shoe frame: origin at the strut pivot, Y along the strut towards the ground",
        "profile": shoe.profile,
        "part": {
            "frame": "x along the track (strut axis at x = 0), y up from the sole's lowest point "
                     "(y = c - Y), z across the track; socket along +y from the top face",
            "sole_length_mm": float(shoe.profile[-1, 0] - shoe.profile[0, 0]),
            "body_height_mm": shoe.body_height,
            "socket_floor_mm": shoe.socket_floor,
            **part_record(part, check),
        },
    }


def _printing(shoe: Shoe) -> dict:
    """The printer and the design's and printed parameters (strut resolved, mm) when drawn for one."""
    from wheelstep_cli.parts.kinds import printing_record

    record = printing_record(shoe.printing, shoe.spec)
    if record:
        printed = resolved_parameters(shoe)
        given = {k: float(v) for k, v in record["parameters"].items() if v is not None}
        record.update(parameters={**printed, **given}, printed_parameters=printed)
    return record


def require_shoe_on_bed(shoe: Shoe, printer) -> Shoe:
    """``shoe``, refused (DesignError naming the input that sizes it) when its part is taller
    than ``printer`` (config.printers.Printer) prints or larger than its bed."""
    from wheelstep_cli.parts.kinds import height_inputs

    spec = shoe.spec
    require_on_bed([shoe.part], printer, "width", spec.width, {
        "a": spec.a, "b": spec.b, "c": spec.c, "r_min": spec.r_min, "rim": spec.rim},
        lowers=height_inputs("shoe", spec))
    return shoe


def shoe_files(shoe: Shoe, out: Path, fmt: str = "both", printer=None) -> dict[Path, bytes]:
    """File name -> contents: shoe.stl / shoe.3mf (on ``printer``'s bed, a config.printers.Printer;
    default the printer the shoe was drawn for, else the fdm-0.4-pla preset), shoe.json,
    shoe-profile.csv and .dxf. A shoe larger or taller than the bed is refused (DesignError)
    before anything is made, when a plate is written or a printer was chosen."""
    from wheelstep_cli.config.profiles import load_printer

    require(fmt in FORMATS, "format", fmt, f"must be one of {', '.join(FORMATS)}")
    chosen = printer or (shoe.printing.printer if shoe.printing is not None else None)
    printer = chosen or load_printer()
    part = shoe.part
    if chosen is not None or fmt in ("3mf", "both"):
        try:
            require_shoe_on_bed(shoe, printer)
        except DesignError as err:
            if chosen is not None:
                raise
            raise default_printer_said(err) from None
    files: dict[Path, bytes] = {}
    if fmt in ("stl", "both"):
        files[out / "shoe.stl"] = stl_bytes(part.vertices, part.faces, "wheelstep shoe")
    if fmt in ("3mf", "both"):
        meta = {"part": "shoe", **design_metadata(resolved_parameters(shoe))}
        plates = bed_plates([part], printer, [meta])
        for name, data in plate_files("shoe", plates, printer, "wheelstep support shoe",
                                          shoe.printing is not None).items():
            files[out / name] = data
    files[out / "shoe.json"] = json_bytes(shoe_report(shoe))
    files[out / "shoe-profile.csv"] = csv_bytes(["x_mm", "y_mm"], shoe.profile)
    files[out / "shoe-profile.dxf"] = polyline_dxf_bytes(shoe.profile)
    return files
