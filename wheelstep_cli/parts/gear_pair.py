"""The non-circular gear pair as printable parts: design -> outlines -> solids -> files."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from wheelstep_cli.config.specs import MIN_MODULE, PAPER_BACKLASH_PER_MODULE, GearPairSpec
from wheelstep_cli.gears.paper_teeth import check_tooth_form, pinion_outline, wheel_outline
from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.gears.sectors import SectorPartition, sector_partition, sectors_per_quarter
from wheelstep_cli.geometry.mesh_checks import MeshReport, Part, part_record, require_printable
from wheelstep_cli.formats.jsonio import json_bytes
from wheelstep_cli.formats.stl import stl_bytes
from wheelstep_cli.parts.gear_phase import phase_report
from wheelstep_cli.parts.gear_laws import (design_backlash, design_law, distance_record,  # noqa: F401
                                           generated_backlash, generation_law, installed_distance,
                                           law_csv_metadata, rolling_distance)
from wheelstep_cli.parts.plate_layout import bed_plates, design_metadata, plate_files, require_on_bed

FORMATS = ("stl", "3mf", "both")


#: Option names a gear-pair profile section or batch entry may set.
SPEC_KEYS = tuple(GearPairSpec.model_fields)


@dataclass(frozen=True)
class GearPair:
    """A built gear pair: the law, its sector partition, outlines and checked parts."""

    spec: GearPairSpec
    law: CrankLaw | None
    partition: SectorPartition | None
    pinion_outline: np.ndarray
    wheel_outline: np.ndarray
    pinion: Part
    wheel: Part
    checks: dict[str, MeshReport] = field(default_factory=dict)
    generated: object = None   # gears.generated.GeneratedPair for generated teeth
    printing: object = None    # parts.kinds.Printing when drawn for a printer (spec: the printed one)
    installed: float | None = None  # mm, generated teeth: parts.gear_laws.installed_distance
    inset: float = 0.0         # mm both tooth outlines are drawn smaller along their normals (a fit)
    asked: object = None       # the spec before the build filled in a default (generated teeth' backlash)
    design_profile: dict | None = None  # the design profile it was made from (config.profiles.profile_record)
    chamfer_from: str | None = None     # what gave the edge chamfer (the option, the profile), as a report says it

    @property
    def as_asked(self) -> GearPairSpec:
        """The spec as the user gave it: before a printer's compensation and before the build
        filled in a default (a remedy leaves such a default to follow what it changes)."""
        if self.printing is not None:
            return self.printing.design
        return self.asked if self.asked is not None else self.spec

    @property
    def mounted_distance(self) -> float:
        """Centre distance (mm) the pair is mounted and checked at: --install-distance, else
        generated teeth where they roll, paper teeth L_p + 0.5 mm."""
        if self.installed is not None:
            return float(self.installed)
        return self.spec.paper_distances[1]

    @property
    def design_distance(self) -> float:
        """Centre distance (mm) the pitch curves roll at: generated teeth the one they were
        generated for (--center-distance, the installed one, or the one --module fits),
        paper teeth the sectors' L_p."""
        if self.generated is not None:
            return float(self.generated.center_distance)
        return self.spec.paper_distances[0]

    @property
    def opening(self) -> float:
        """How much farther (mm) the pair is mounted than its pitch curves roll (< 0: closer)."""
        return self.mounted_distance - self.design_distance

    @property
    def wheel_teeth(self) -> int:
        if self.generated is not None:
            return self.generated.wheel_teeth
        return self.spec.z * self.spec.turns


def build_gear_pair(spec: GearPairSpec) -> GearPair:
    """Compute, extrude and check both gears; raises DesignError for impossible designs (its
    rule also stated for the inputs that size the pair, so it names the one the user gave)."""
    from wheelstep_cli.errors import DesignError

    try:
        return _build(spec)
    except DesignError as err:
        raise err.tied_to(footprint(spec)) from None


def _build(spec: GearPairSpec) -> GearPair:
    from wheelstep_cli.parts.gear_faces import require_hub_round_hole

    require_hub_round_hole(spec)   # before the teeth are made: what does not fit round the bore
    if spec.teeth == "generated":
        return _build_generated(spec)
    law = spec.law()
    count = sectors_per_quarter(spec.z, spec.turns)
    partition = sector_partition(law, count, spec.paper_distances[0])
    form = spec.tooth_form()
    check_paper_teeth(partition, form, spec)
    p_outline = pinion_outline(partition, form)
    w_outline = wheel_outline(partition, form)
    pinion, wheel = _plates(spec, law, p_outline, w_outline, spec.paper_module)
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    return GearPair(spec, law, partition, p_outline, w_outline, pinion, wheel, checks)


def footprint(spec: GearPairSpec) -> dict[str, object]:
    """The inputs that set the gears' size and height on the bed (name -> value, None: not set)."""
    return {**spec.sizing(), "hub_length": spec.hub_length}


def require_pair_on_bed(pair: GearPair, printer) -> GearPair:
    """``pair``, refused (DesignError naming the input the user gave that sizes it) when a gear
    is taller than ``printer`` prints or larger than its bed."""
    from wheelstep_cli.parts.kinds import height_inputs

    require_on_bed([pair.pinion, pair.wheel], printer, "thickness", pair.spec.thickness, footprint(pair.spec),
                   height_only=("hub_length",), lowers=height_inputs("gear-pair", pair.spec))
    return pair


def check_paper_teeth(partition: SectorPartition, form, spec: GearPairSpec) -> None:
    """The sector-involute teeth's form check (module against tooth pitch), its refusal also
    stated for the backlash and the inputs that size the pair (the tooth thickness and
    pitch), so it names the one the user gave (``teeth`` checks it outside a build)."""
    from wheelstep_cli.errors import NONE_GIVEN, DesignError

    try:
        check_tooth_form(partition, form, least_module=MIN_MODULE,
                         backlash_per_module=PAPER_BACKLASH_PER_MODULE if spec.backlash is None else None)
    except DesignError as err:
        if err.param == "module" and spec.module is None:
            # a module nobody gave is said to be the default, not as if the user had set it
            err = err._with_extras(DesignError("module", err.value, f"the paper teeth's default module "
                                               f"{NONE_GIVEN}: {err.limit}", err.alternatives))
        # the tooth count and backlash first: the remedy's own levers, named before the mechanism
        raise err.tied_to({"z": spec.z, "backlash": form.backlash, **spec.sizing()}) from None


def _plates(spec: GearPairSpec, law, p_outline: np.ndarray, w_outline: np.ndarray,
            module: float):
    """Pinion and wheel plates: shaft holes keyed to and timing marks on the assembly phase,
    pockets with --lighten (``module`` mm sizes their rim)."""
    from wheelstep_cli.parts.gear_faces import faces_for, gear_part

    faces = faces_for(spec, law, p_outline, w_outline, module)
    return gear_part(faces["pinion"], spec), gear_part(faces["wheel"], spec)


def law_record(spec: GearPairSpec, law) -> dict:
    """What a report says of the law (mm, deg): the mechanism and ratio constant, or the CSV."""
    if spec.law_csv is not None:
        return {"csv": spec.law_csv, "driving_period_deg": float(np.degrees(law.theta_period)),
                "driven_period_deg": float(np.degrees(law.phi_period))}
    m = law.mechanism
    return {"a": m.a, "b": m.b, "c": m.c, "turns": law.turns, "u": law.u}


def generation_settings(spec: GearPairSpec):
    """The generator's settings (gears.generation.GenerationSettings) for ``spec``."""
    from wheelstep_cli.gears.generation import GenerationSettings

    return replace(GenerationSettings(), tilt=spec.tilt)


def _build_generated(spec: GearPairSpec) -> GearPair:
    """Generated teeth (SPEC §9): pitch curves rolling at the installed distance."""
    from wheelstep_cli.gears.generation import generate_pair, simplify_outline
    from wheelstep_cli.parts.gear_laws import require_law_periods

    designed, law = generation_law(spec)
    require_law_periods(spec, designed)
    settings = generation_settings(spec)
    distance = rolling_distance(spec, law)
    asked = spec
    if spec.backlash is None:
        spec = spec.model_copy(update={"backlash": generated_backlash(spec, law, distance, settings)})
    gen = generate_pair(law, spec.z, spec.cutter(), corner=spec.corner, settings=settings,
                        center_distance=distance)
    # the pinion is written as it carved the wheel; the wheel's ray map is thinned only by a
    # fraction of a micron (coarser facets make real speed ripple: a 0.2 mm facet on a
    # curved flank kinks the hub speed by about 1 %)
    p_outline = gen.pinion_outline
    w_outline = simplify_outline(gen.wheel_outline, gen.settings.wheel_tolerance)
    pinion, wheel = _plates(spec, gen.law, p_outline, w_outline, gen.module)
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    crank = spec.law() if spec.law_csv is None else None
    return GearPair(spec, crank, None, p_outline, w_outline, pinion, wheel, checks, gen,
                    installed=installed_distance(spec, law), asked=asked)


def inset_gear_pair(pair: GearPair, inset: float) -> GearPair:
    """``pair`` with both tooth outlines drawn ``inset`` mm smaller along their normals (an
    exact polygon offset; larger when < 0): a fit's print compensation (SPEC §11: a printer
    lays outlines down offset along their normals, so the fit takes its clearance there too).
    The plates are rebuilt round the new outlines and checked; a printer's bed-side
    compensation is not applied here (parts.fit does, as for any part drawn for a printer)."""
    from wheelstep_cli.geometry.planar import offset_outline

    gen = pair.generated
    law = gen.law if gen is not None else pair.law
    module = gen.module if gen is not None else pair.spec.paper_module
    # thinned as the written outlines are (their Douglas-Peucker tolerance)
    thin = generation_settings(pair.spec).at_module(module).wheel_tolerance
    p_outline = offset_outline(pair.pinion_outline, -inset, "pinion", thin=thin)
    w_outline = offset_outline(pair.wheel_outline, -inset, "wheel", thin=thin)
    pinion, wheel = _plates(pair.spec, law, p_outline, w_outline, module)
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    return replace(pair, pinion_outline=p_outline, wheel_outline=w_outline, pinion=pinion,
                   wheel=wheel, checks=checks, printing=None, inset=pair.inset + float(inset))


def partition_rows(partition: SectorPartition) -> list[dict]:
    """The sector table in degrees and mm, one dict per sector."""
    deg = np.degrees
    return [
        {"i": i + 1, "phi_deg": deg(partition.phi[i]), "dphi_deg": deg(partition.dphi[i]),
         "r_wheel_mm": partition.r_wheel[i], "theta_deg": deg(partition.theta[i]),
         "dtheta_deg": deg(partition.dtheta[i]), "r_pinion_mm": partition.r_pinion[i]}
        for i in range(partition.count)
    ]


def gear_pair_report(pair: GearPair, meshing: dict | None = None) -> dict:
    """Everything about the pair a person or a machine may want: inputs, partition, parts,
    and the meshing check of the written meshes when given."""
    from wheelstep_cli.parts.kinds import made_from

    spec = {**pair.spec.model_dump(), **_distances(pair)}
    spec["backlash"] = pair.spec.backlash_mm
    if pair.spec.hub_d is not None:
        spec["hub_length"] = pair.spec.hub_mm[1]      # the length built (8 mm when none is given)
    parts = {}
    for part in (pair.pinion, pair.wheel):
        check = pair.checks[part.name]
        parts[part.name] = {"teeth": pair.spec.z if part.name == "pinion" else pair.wheel_teeth,
                            **part_record(part, check)}
    report = {"tool": "wheelstep gears", **made_from(pair), "parameters": spec, **_printing(pair),
              "parts": parts, "chamfer": chamfer_report(pair)}
    if pair.law is not None:
        report["u"] = pair.law.u
    if pair.partition is not None:
        report["arc_mm"] = pair.partition.arc
        report["sectors"] = partition_rows(pair.partition)
    if pair.generated is not None:
        report["generated"] = generated_report(pair)
    if pair.inset:
        report["outline_inset_mm"] = {
            "inset_mm": pair.inset, "how": "both tooth outlines drawn this much smaller along their "
            "normals after generation (a fit's print compensation, meshing.tolerance.fit)"}
    report["phase"] = phase_report(pair)
    if pair.spec.lighten:
        from wheelstep_cli.parts.gear_faces import gear_faces, lighten_record

        printer = pair.printing.printer if pair.printing is not None else None
        report["lighten"] = lighten_record(gear_faces(pair), pair.spec, printer)
    if meshing is not None:
        report["meshing"] = meshing
    return report


def _distances(pair: GearPair) -> dict[str, float]:
    """The distances (mm) the pair rolls and is mounted at, as the parameters report them."""
    return {"center_distance": pair.design_distance, "install_distance": pair.mounted_distance}


def chamfer_report(pair: GearPair) -> dict:
    """The edge chamfer drawn (mm), where it came from, what became of the elephant foot."""
    from wheelstep_cli.parts.kinds import chamfer_record

    printing = pair.printing
    if printing is None:
        return chamfer_record(pair.spec, pair.spec, None, pair.chamfer_from)
    design = printing.design if printing.design is not None else pair.spec
    return chamfer_record(design, pair.spec, printing.printer, pair.chamfer_from)


def _printing(pair: GearPair) -> dict:
    """The printer and the design's parameters (backlash resolved, mm) when drawn for a printer."""
    from wheelstep_cli.parts.kinds import printing_record

    record = printing_record(pair.printing, pair.spec)
    if record:
        # the design's backlash: what is drawn less the printer's tooth clearance
        record["parameters"]["backlash"] = pair.spec.backlash_mm - pair.printing.printer.tooth_clearance
        record["printed_parameters"]["backlash"] = pair.spec.backlash_mm
        for name in ("parameters", "printed_parameters"):
            if record[name] is not None:
                record[name].update(_distances(pair))
    return record


def _rolling_source(spec: GearPairSpec) -> str:
    """What chose the distance generated teeth roll at."""
    if spec.module is not None:
        return "the module (SPEC §9)"
    if spec.center_distance is not None:
        return "--center-distance"
    return "the installed distance"


def _metadata_distances(pair: GearPair) -> dict[str, float]:
    """The distances a plate's metadata stores (parts.gear_laws.distance_record)."""
    if pair.generated is None:
        return distance_record(pair.spec)
    return {"install_distance": pair.mounted_distance,
            **({} if pair.spec.module is not None else {"center_distance": pair.design_distance})}


def generated_report(pair: GearPair) -> dict:
    """Generated-teeth figures: pitch, module, backlash budget, undercut and tip-land margins."""
    gen = pair.generated
    alpha = gen.cutter.pressure_angle
    opening = pair.opening
    return {
        "method": "pinion cut by a rolling rack with teeth tilted towards the radius (pivoting "
                  "at pitch-curve corners); wheel carved by the pinion moving along the exact law, "
                  "widened by a constant angular backlash",
        "tilt": pair.spec.tilt,
        "rolling_center_distance_mm": gen.center_distance,
        "installed_center_distance_mm": pair.mounted_distance,
        "center_distance_chosen_by": _rolling_source(pair.spec),
        "pitch_mm": gen.pitch,
        "module_mm": gen.module,
        "pinion_teeth": gen.pinion_teeth,
        "wheel_teeth": gen.wheel_teeth,
        "corner": gen.corner,
        "blend_deg": pair.spec.blend,
        "backlash": {
            "normal_backlash_mm": gen.cutter.backlash,
            "wheel_angular_play_arcmin": float(np.degrees(gen.play) * 60.0 * 2.0),
            "center_distance_opening_mm": opening,
            "opening_adds_normal_mm": 2.0 * opening * float(np.sin(alpha)),
            "note": "backlash by thinning (pinion teeth by j_n/2, wheel by a constant angular "
                    "play worth j_n/2 at its mean pitch radius); mounting the pair farther than "
                    "it rolls (the opening) adds about 2 x opening x sin(alpha) of normal "
                    "backlash, but off the rolling distance the pitch curves no longer roll, "
                    "so the meshing check at the installed distance decides",
        },
        "tip_clearance": {
            "pinion_spaces_mm": gen.cutter.pinion_clearance * gen.module,
            "wheel_spaces_mm": gen.cutter.clearance * gen.module,
            "note": "below the other gear's tips on the line of centres; the wheel is carved by "
                    "the pinion's shaper (its teeth cut by the same rack the clearance taller) and "
                    "its tips and roots within 1.25 pitches of each handover notch are lowered "
                    "by the clearance; how much closer the pair may be mounted: "
                    "meshing.mounting.closer_mm",
        },
        "undercut_limit_mm": gen.undercut_limit,
        "pitch_curve_min_convex_radius_mm": gen.min_curvature_radius,
        "pinion_min_tip_land_mm": gen.pinion_tip_land,
        "wheel_min_tip_land_mm": gen.wheel_tip_land,
        "topped_teeth": {name: {"count": count, "height_removed_mm": drop}
                         for name, (count, drop) in gen.topping.items()},
    }


def gear_pair_files(pair: GearPair, out: Path, fmt: str = "both", meshing: dict | None = None,
                    printer=None) -> dict[Path, bytes]:
    """File name -> contents for the pair: STL per gear, the 3MF plate(s) laid out on
    ``printer``'s bed (a config.printers.Printer; default the printer the pair was drawn for,
    else the fdm-0.4-pla preset) as
    gears.3mf, or gears-1.3mf and gears-2.3mf when both do not fit on one, and gears.json.
    A gear larger or taller than the bed is refused (DesignError) before anything is made,
    when a plate is written or a printer was chosen (plain STL for no printer in particular
    is not held to the default bed)."""
    from wheelstep_cli.config.profiles import load_printer

    chosen = printer or (pair.printing.printer if pair.printing is not None else None)
    printer = chosen or load_printer()
    files: dict[Path, bytes] = {}
    parts = [pair.pinion, pair.wheel]
    if chosen is not None or fmt in ("3mf", "both"):
        require_pair_on_bed(pair, printer)
    if fmt in ("stl", "both"):
        for part in parts:
            files[out / f"{part.name}.stl"] = stl_bytes(part.vertices, part.faces, f"wheelstep {part.name}")
    if fmt in ("3mf", "both"):
        inset = {"outline_inset": float(pair.inset)} if pair.inset else {}
        meta = {**design_metadata({**pair.spec.model_dump(), **_metadata_distances(pair), **inset}),
                **law_csv_metadata(pair.spec)}
        plates = bed_plates(parts, printer, [{"part": p.name, "pair": "gears", **meta} for p in parts])
        for name, data in plate_files("gears", plates, printer, "wheelstep gear pair",
                                          pair.printing is not None).items():
            files[out / name] = data
    files[out / "gears.json"] = json_bytes(gear_pair_report(pair, meshing))
    return files
