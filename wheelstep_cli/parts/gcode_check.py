"""The meshing check of what PrusaSlicer will print (SPEC §11): a gear pair read back from
its G-code.

Of each G-code file the layer half-way up each gear's tooth zone is taken (where
``mesh-check`` sections a gear mesh, measured from the mesh's lowest point: the slicer lays
that on the bed); its external perimeters, offset outward by half their extrusion width (an
exact polygon offset), are the printed outlines. The G-code carries no design, so the design
is the pair on the wheelstep plate(s) the G-code was sliced from (3MF metadata: law,
installed distance), or the two meshes it was sliced from with the design the options give.
Each designed gear is found among the printed parts by its section area, then laid back
into its own frame by the rigid motion that best fits the printed outline to the designed
one (the slicer or its user may have moved and turned the parts on the bed): a part that
fits no designed gear is refused, so a file of another pair, or one part, is named as
such; so is a part printed taller or lower than its gear (a pair of alike sections at another
thickness). The printed outlines are then checked at the installed distance, in phase,
as ``mesh-check`` checks written meshes. Lengths in mm, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from wheelstep_cli.errors import DesignError
from wheelstep_cli.geometry.planar import points_inside, prepared_polygon, signed_area
from wheelstep_cli.geometry.registration import Registration, register
from wheelstep_cli.parts.gcode_layers import PrintedPart, printed_parts, read_gcode_file, require_height

#: A printed part is taken for a designed gear when their section areas differ by less than
#: this share: the band's +-0.1 mm changes a gear's area by about 1 %, another tooth count
#: or design of a similar size by more than the fit below accepts anyway.
AREA_SHARE = 0.1
#: After the best rigid fit, a printed outline must follow the designed one to this rms
#: (mm) and never depart by more than LARGEST (mm) from its mean offset: a printer's
#: outline wobbles by tenths of a millimetre at most, a tooth of another pair by its height.
RMS = 0.1
LARGEST = 0.5


@dataclass(frozen=True)
class PrintedGear:
    """A designed gear found in the G-code: the printed part, its outline in the gear's own
    frame (mm) and the fit that put it there."""

    part: PrintedPart
    outline: np.ndarray
    fit: Registration


def find_gear(parts: list[PrintedPart], design: np.ndarray, gear: str, pair: str,
              taken: list) -> PrintedGear:
    """The printed part that is ``design`` (the gear's outer ring half-way up its teeth, own frame):
    nearest in the area its outer outline bounds (holes and pockets aside), then fitted;
    DesignError naming the G-code when none is."""
    want = signed_area(design)

    def outer(part):
        return signed_area(part.outline)

    near = sorted((p for p in parts if not any(p is t for t in taken)
                   and abs(outer(p) / want - 1.0) < AREA_SHARE), key=lambda p: abs(outer(p) - want))
    where = " + ".join(sorted({p.source for p in parts})) or "the G-code"
    if not near:
        found = ", ".join(f"{outer(p):.0f}" for p in parts) or "none"
        raise DesignError("gcode", where, f"has no printed part the size of the {gear} of pair "
                                          f"'{pair}' (section {want:.0f} mm2; {len(parts)} printed "
                                          f"part(s) half-way up the teeth: {found} mm2): slice both gears of "
                                          "this pair (one plate, or the files of both plates)")
    best = None
    for part in near:       # nearest in area first; a plate may hold gears of other pairs
        fit = register(part.outline, design)
        if fit.rms <= RMS and fit.largest <= LARGEST:
            return PrintedGear(part, fit.apply(part.outline), fit)
        best = best or (part, fit)
    part, fit = best
    raise DesignError("gcode", part.source, f"its part of {outer(part):.0f} mm2 is not the {gear} "
                                            f"of pair '{pair}': after the best fit it departs by "
                                            f"{fit.largest:.2f} mm (rms {fit.rms:.3f} mm; a print "
                                            f"stays within {LARGEST:g}): another design")


def gear_record(gear: PrintedGear, design_hole: float | None) -> dict:
    """What the report says of one printed gear (mm): where it was read, how it fits the
    design, and the printed bore (area-equivalent diameter) against the designed one."""
    bore = None
    for hole in gear.part.holes:      # the bore holds the axis (pockets of --lighten do not)
        placed = gear.fit.apply(hole)
        if points_inside(prepared_polygon(placed), np.zeros((1, 2)))[0]:
            bore = float(np.sqrt(4.0 * abs(signed_area(placed)) / np.pi))
    return {"gcode": gear.part.source, "layer_z_mm": gear.part.z,
            "extrusion_width_mm": gear.part.width, "printed_area_mm2": gear.part.area,
            "outline_offset_mm": gear.fit.offset, "outline_rms_mm": gear.fit.rms,
            "outline_largest_mm": gear.fit.largest,
            "bore_printed_mm": bore, "bore_drawn_mm": design_hole,
            "bore_shrink_mm": None if bore is None or design_hole is None else design_hole - bore}


def design_sections(pair) -> dict:
    """Per gear of a pair (parts.plate_pairs.PlatePair, MeshPair): (outer ring, area-equivalent
    bore diameter or None, own frame; the section's height above the mesh's lowest point), mm,
    half-way up the gear's tooth zone as ``mesh-check`` sections a mesh; DesignError naming
    the gear's file when it cannot be sectioned."""
    from wheelstep_cli.geometry.mesh_checks import tooth_zone_middle
    from wheelstep_cli.geometry.solids import section_outline, section_rings

    out = {}
    for gear, obj, file in zip(("pinion", "wheel"), (pair.pinion, pair.wheel), pair.files):
        mid = tooth_zone_middle(obj.vertices)
        try:
            outline = section_outline(obj.vertices, obj.faces, gear, mid)
        except DesignError as err:          # named by the gear's file, as given, not "mesh"
            raise DesignError(gear, file, err.limit) from None
        holes = [abs(signed_area(r)) for r in section_rings(obj, mid) if signed_area(r) < 0]
        out[gear] = (outline, float(np.sqrt(4.0 * max(holes) / np.pi)) if holes else None,
                     mid - float(np.min(obj.vertices[:, 2])))
    return out


def printed_pair(gcode_files: list[Path], pair, designs: dict) -> tuple[dict, dict]:
    """The pinion and wheel of ``pair`` (its :func:`design_sections` ``designs``) as printed
    by the G-code files: ({gear: PrintedGear}, {gear: record})."""
    read = [(str(path), read_gcode_file(path)) for path in gcode_files]
    parts_at: dict[float, list[PrintedPart]] = {}
    found, records = {}, {}
    for gear in ("wheel", "pinion"):         # the larger first: its area is the surer
        height = designs[gear][2]
        if height not in parts_at:          # one list per height: a part taken stays taken
            parts_at[height] = [part for source, layers in read
                                for part in printed_parts(layers, source, height)]
        found[gear] = find_gear(parts_at[height], designs[gear][0], gear, pair.pair,
                                [g.part for g in found.values()])
        vertices, fit = getattr(pair, gear).vertices, found[gear].fit
        require_height(found[gear].part, dict(read)[found[gear].part.source], fit.undo(np.zeros((1, 2)))[0],
                       float(np.ptp(vertices[:, 2])), gear, pair.pair)
        records[gear] = gear_record(found[gear], designs[gear][1])
    return found, records


@dataclass(frozen=True)
class MeshPair:
    """Two gear meshes named on the command line and the design they were drawn for: the
    stand-in of a plate pair (parts.plate_pairs.PlatePair) for STL files."""

    pair: str
    pinion: object      # formats.mesh_read.MeshObject, own frame
    wheel: object
    spec: object
    files: tuple[str, str]      # the two meshes as named
    sections: dict | None = None    # their design_sections, once taken


def mesh_pair(pinion: str, wheel: str, spec, samples: int | None, window: float | None) -> MeshPair:
    """Read the two meshes (FILE.stl, FILE.3mf[:NAME]) the G-code was sliced from; refused
    (DesignError) as ``mesh-check PINION WHEEL`` refuses them (e.g. not a pair at the
    design's distance), before any G-code is read."""
    from wheelstep_cli.formats.mesh_read import MeshObject, read_mesh
    from wheelstep_cli.parts.gear_pair import design_law
    from wheelstep_cli.parts.mesh_check_files import WrittenPairCheck, require_written_pair

    check = WrittenPairCheck(pinion, wheel, spec, samples, window)
    law = design_law(spec)
    check.validate()
    objects = [MeshObject(gear, *read_mesh(given, gear, default_name=gear), np.eye(4, 3), {})
               for gear, given in (("pinion", pinion), ("wheel", wheel))]
    pair = MeshPair(f"{Path(pinion).name} + {Path(wheel).name}", objects[0], objects[1], spec,
                    (pinion, wheel))
    designs = design_sections(pair)
    require_written_pair(check, (designs["pinion"][0], designs["wheel"][0]), law)
    return replace(pair, sections=designs)     # the read-back takes them from here


def default_plates(gcode_files: list[Path]) -> list[str]:
    """The plates a G-code read-back takes its design from when none is named: FILE.3mf
    beside each FILE.gcode (as ``gears --slice`` and ``prusa-slicer -g FILE.3mf --output
    FILE.gcode`` write)."""
    plates = []
    for path in gcode_files:
        plate = path.with_suffix(".3mf")
        if not plate.is_file():
            raise DesignError("gcode", str(path), f"has no plate {plate.name} beside it to take "
                                                  "the design from: name the plate(s) it was sliced "
                                                  "from (PINION [WHEEL] arguments)")
        if str(plate) not in plates:
            plates.append(str(plate))
    return plates


@dataclass(frozen=True)
class GcodeCheck:
    """A pair read back from G-code: the designed and printed sections (tolerance.SectionedPair,
    the printed starting in the designed pair's play), the designed pair's meshing report,
    the meshing settings and the per gear read-back records."""

    design: object
    printed: object
    nominal: object
    settings: object
    records: dict
    sources: tuple


def gcode_sections(gcode_files: list[Path], pair, samples: int | None, window: float | None,
                   progress=None) -> GcodeCheck:
    """Read the pair back from the G-code files and check the designed pair once (its play
    is where the printed pair's poses start: generated teeth may keep their play on one
    side, where the law's own pose touches a flank)."""
    from wheelstep_cli.gears.meshing import MeshingSettings
    from wheelstep_cli.parts.gear_pair import design_law, generation_law, installed_distance
    from wheelstep_cli.parts.tolerance import NOMINAL, SectionedPair, check_case, mid_play

    from wheelstep_cli.gears.meshing.check import pair_teeth
    from wheelstep_cli.parts.mesh_check_files import require_poses_per_tooth

    law = design_law(pair.spec)
    designs = getattr(pair, "sections", None) or design_sections(pair)
    # the designed pinion's own teeth (two meshes named with design options need not have z's)
    require_poses_per_tooth(samples, pair_teeth(designs["pinion"][0], None, law)[0], law)
    found, records = printed_pair(gcode_files, pair, designs)
    _, blended = generation_law(pair.spec)
    settings = replace(MeshingSettings(), samples=samples, window=window)
    design = SectionedPair(designs["pinion"][0], designs["wheel"][0], blended,
                           installed_distance(pair.spec, blended), int(pair.spec.z))
    nominal = check_case(design, NOMINAL, settings)
    # a print's teeth are each its own: it is checked over the whole cycle, not one period
    printed = mid_play(replace(design, pinion=found["pinion"].outline, wheel=found["wheel"].outline,
                               whole_cycle=True), nominal)
    return GcodeCheck(design, printed, nominal, settings, records,
                      (found["pinion"].part.source, found["wheel"].part.source))


def run_gcode_check(gcode_files: list[Path], pair, samples: int | None, window: float | None,
                    progress=None):
    """The meshing check of plate pair ``pair`` as the G-code files print it: (report,
    summary with the per gear read-back under ``gcode``, the GcodeCheck)."""
    from wheelstep_cli.parts.gear_pair import generation_law, law_record
    from wheelstep_cli.parts.tolerance import NOMINAL, check_case

    read = gcode_sections(gcode_files, pair, samples, window)
    report = check_case(read.printed, NOMINAL, read.settings)
    law, _ = generation_law(pair.spec)
    source = ("external perimeters of the layer half-way up the teeth, offset outward by half their "
              "extrusion width, fitted into each gear's frame; poses start in the middle of the "
              "designed pair's play (SPEC §11)")
    summary = {"pair": pair.pair, "distance_mm": read.design.distance,
               "pinion": f"{read.sources[0]}:pinion", "wheel": f"{read.sources[1]}:wheel",
               "law": {**law_record(pair.spec, law), "blend_deg": pair.spec.blend}, **report.to_dict(),
               "cycle": cycle_record(read.printed.law),
               "gcode": {"source": source, "pinion": read.records["pinion"],
                         "wheel": read.records["wheel"]}}
    summary["meshes"] = not (report.interferes or report.contact_lost)
    from wheelstep_cli.parts.bound_figures import bounds_verdict

    # the design's bounds on the print: how far from the drawing it runs (FDM prints read
    # tens of um of F'i), said as every other check says it
    summary["bounds"] = {**bounds_verdict(summary), "judged_on": "the printed outlines, the printer's "
                         "deviations included (the bounds are the design's: an FDM print's F'i is tens of um)"}
    return report, summary, read


def cycle_record(law) -> dict:
    """What the read-back's poses span: the whole cycle of ``law`` (gears.cycle.WholeCycle),
    in which every printed pinion tooth meets every wheel tooth it will meet."""
    from wheelstep_cli.gears.cycle import WholeCycle

    cycle = WholeCycle(law)
    return {"law_periods": cycle.periods, "pinion_turns": cycle.pinion_turns,
            "wheel_turns": cycle.wheel_turns}


def cycle_words(cycle: dict) -> str:
    """A :func:`cycle_record` in words, for the text report."""
    turns = "one wheel turn" if cycle["wheel_turns"] == 1 else f"{cycle['wheel_turns']} wheel turns"
    return f"{turns}, {cycle['law_periods']} law periods: every printed tooth meets all it will meet"


def band_prediction(read: GcodeCheck, printer, progress=None) -> dict:
    """The band check (SPEC §11) of the designed pair on ``printer``'s band, and the range of
    least backlash (mm) it predicts for a print: the tight corner's to the loose corner's."""
    from wheelstep_cli.parts.tolerance import band_record

    record = band_record(read.design, printer.band, printer.name, read.nominal, read.settings)
    record["least_backlash_range_mm"] = least_backlash_range(record)
    return record


def least_backlash_range(band: dict) -> list | None:
    """The least backlash (mm) a band record predicts for a print: its cases' lowest to highest,
    a case that jams counted as 0 (its backlash figure is an estimate where rigid teeth cannot
    go: several mm below zero)."""
    least = [0.0 if c["jams"] else c["backlash_min_mm"] for c in band.get("cases", [])
             if c["jams"] or c["backlash_min_mm"] is not None]
    return [min(least), max(least)] if least else None


def within_band(summary: dict, band: dict) -> bool | None:
    """Whether the printed pair's least backlash lies in the range the band predicts."""
    span, least = band.get("least_backlash_range_mm"), summary.get("backlash_min_mm")
    if span is None or least is None:
        return None
    return bool(span[0] <= least <= span[1])


def gcode_lines(summary: dict) -> list[str]:
    """Text lines of the read-back: per gear where it was read and how it follows the
    drawing, and (with a band) whether the print's least backlash is where the band says."""
    lines = []
    for gear in ("pinion", "wheel"):
        r = summary["gcode"][gear]
        # both across by area: a teardrop drawn for a printer is wider than its round size
        bore = ("" if r["bore_printed_mm"] is None else f", bore {r['bore_printed_mm']:.3f} mm across by area"
                + ("" if r["bore_drawn_mm"] is None else f" (drawn {r['bore_drawn_mm']:.3f})"))
        lines.append(f"printed {gear}: {Path(r['gcode']).name} layer z {r['layer_z_mm']:g} mm, "
                     f"width {r['extrusion_width_mm']:.3f} mm; outline {r['outline_offset_mm']:+.3f} mm "
                     f"from the drawn one (rms {r['outline_rms_mm']:.3f}, largest "
                     f"{r['outline_largest_mm']:.3f}){bore}")
    band = summary.get("tolerance")
    if band and band.get("least_backlash_range_mm") and summary["backlash_min_mm"] is not None:
        lo, hi = band["least_backlash_range_mm"]
        inside = summary["gcode"].get("inside_band")
        low = "0 (jams)" if band.get("jams") and lo == 0.0 else f"{lo:.3f}"
        lines.append(f"printed least backlash {summary['backlash_min_mm']:.3f} mm: "
                     + ("inside" if inside else "OUTSIDE")
                     + f" the band's prediction {low}..{hi:.3f} mm (tight to loose corner)")
    return lines
