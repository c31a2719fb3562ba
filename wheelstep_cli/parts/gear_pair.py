"""The non-circular gear pair as printable parts: design -> outlines -> solids -> files."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from wheelstep_cli.errors import require
from wheelstep_cli.gears.paper_teeth import ToothForm, check_tooth_form, pinion_outline, wheel_outline
from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.mechanism.crank import CrankMechanism
from wheelstep_cli.gears.sectors import SectorPartition, sector_partition, sectors_per_quarter
from wheelstep_cli.geometry.mesh_checks import MeshReport, Part, part_record, require_printable
from wheelstep_cli.geometry.solids import extrude_plate
from wheelstep_cli.formats.jsonio import json_bytes
from wheelstep_cli.formats.stl import stl_bytes
from wheelstep_cli.formats.threemf import PlateObject, threemf_bytes

#: Gap between parts on the plate, mm.
PLATE_GAP = 5.0
FORMATS = ("stl", "3mf", "both")


@dataclass(frozen=True)
class GearPairSpec:
    """Everything that defines a printed gear pair. Lengths in mm.

    Defaults are the source design (BNTU prototype, profiles/bntu-2024.yaml).
    """

    a: float = 60.0
    b: float = 100.0
    c: float = 360.0
    z: int = 48
    turns: int = 2
    center_distance: float = 143.5
    install_distance: float = 144.0
    module: float = 2.0
    backlash: float | None = None  # None: 0.25 * module
    thickness: float = 10.0
    bore: float = 8.0
    teeth: str = "generated"         # "generated" (SPEC §9) or "paper" (SPEC §5)
    pressure_angle: float = 20.0     # deg, generated teeth
    addendum: float = 1.0            # x module, generated teeth
    dedendum: float = 1.25           # x module, generated teeth
    fillet: float = 0.25             # cutter tip radius x module, generated teeth
    blend: float = 0.0               # deg of carrier angle: ratio blend half-width at handovers
    corner: str = "space"            # pinion "space" or "tooth" centred on each pitch-curve corner
    tilt: float = 0.6                # rack-tooth tilt towards the radius (fraction of mu), generated
    law_csv: str | None = None       # driving/driven angle samples (deg) replacing the crank law

    @property
    def backlash_mm(self) -> float:
        return 0.25 * self.module if self.backlash is None else self.backlash

    def mechanism(self) -> CrankMechanism:
        return CrankMechanism(self.a, self.b, self.c)

    def law(self) -> CrankLaw:
        return CrankLaw(self.mechanism(), self.turns)

    def tooth_form(self) -> ToothForm:
        return ToothForm(self.module, self.backlash_mm)

    def cutter(self):
        from wheelstep_cli.gears.generation import RackCutter

        return RackCutter(np.radians(self.pressure_angle), self.addendum, self.dedendum,
                          self.fillet, self.backlash_mm)


#: Option names a gear-pair profile section or batch entry may set.
SPEC_KEYS = tuple(GearPairSpec.__dataclass_fields__)


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
    generated: object = None   # gears.generation.GeneratedPair for generated teeth

    @property
    def wheel_teeth(self) -> int:
        if self.generated is not None:
            return self.generated.wheel_teeth
        return self.spec.z * self.spec.turns


def build_gear_pair(spec: GearPairSpec) -> GearPair:
    """Compute, extrude and check both gears; raises DesignError for impossible designs."""
    require(spec.teeth in ("generated", "paper"), "teeth", spec.teeth, "must be 'generated' or 'paper'")
    if spec.teeth == "generated":
        return _build_generated(spec)
    require(spec.law_csv is None, "law-csv", spec.law_csv, "needs --teeth generated")
    law = spec.law()
    count = sectors_per_quarter(spec.z, spec.turns)
    require(spec.install_distance >= spec.center_distance, "install-distance", spec.install_distance,
            f"must be >= center-distance {spec.center_distance:g} mm")
    require(spec.install_distance <= spec.center_distance + spec.module, "install-distance",
            spec.install_distance,
            f"must be <= center-distance + module = {spec.center_distance + spec.module:g} mm "
            "(farther apart the teeth lose contact)")
    partition = sector_partition(law, count, spec.center_distance)
    form = spec.tooth_form()
    check_tooth_form(partition, form)
    p_outline = pinion_outline(partition, form)
    w_outline = wheel_outline(partition, form)
    pinion = extrude_plate("pinion", p_outline, spec.thickness, spec.bore)
    wheel = extrude_plate("wheel", w_outline, spec.thickness, spec.bore)
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    return GearPair(spec, law, partition, p_outline, w_outline, pinion, wheel, checks)


def generation_law(spec: GearPairSpec):
    """The law the generated teeth follow (crank law or --law-csv) and its blended form."""
    from wheelstep_cli.formats.law_csv import read_law_csv
    from wheelstep_cli.gears.laws import blended_law

    law = read_law_csv(spec.law_csv) if spec.law_csv is not None else spec.law()
    require(0.0 <= spec.blend <= 20.0, "blend", spec.blend, "must be 0..20 deg")
    return law, blended_law(law, np.radians(spec.blend))


def _build_generated(spec: GearPairSpec) -> GearPair:
    """Generated teeth (SPEC §9): pitch curves rolling at the installed distance."""
    from wheelstep_cli.gears.generation import GenerationSettings, generate_pair, simplify_outline

    require(spec.install_distance >= spec.center_distance, "install-distance", spec.install_distance,
            f"must be >= center-distance {spec.center_distance:g} mm")
    _, law = generation_law(spec)
    require(0.0 <= spec.tilt <= 1.5, "tilt", spec.tilt, "must be 0..1.5")
    settings = replace(GenerationSettings(), tilt=spec.tilt)
    gen = generate_pair(law, spec.z, spec.cutter(), corner=spec.corner, settings=settings,
                        center_distance=spec.install_distance)
    # the pinion is written as it carved the wheel; the wheel's ray map is thinned only by a
    # fraction of a micron (coarser facets make real speed ripple: a 0.2 mm facet on a
    # curved flank kinks the hub speed by about 1 %)
    p_outline = gen.pinion_outline
    w_outline = simplify_outline(gen.wheel_outline, settings.wheel_tolerance)
    pinion = extrude_plate("pinion", p_outline, spec.thickness, spec.bore)
    wheel = extrude_plate("wheel", w_outline, spec.thickness, spec.bore)
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    crank = spec.law() if spec.law_csv is None else None
    return GearPair(spec, crank, None, p_outline, w_outline, pinion, wheel, checks, gen)


def plate_layout(parts: list[Part]) -> list[tuple[float, float, float]]:
    """Translations (mm) putting parts side by side along X on the bed, all at z >= 0."""
    shifts = []
    x = PLATE_GAP
    height = max(p.bounds[1, 1] - p.bounds[0, 1] for p in parts)
    for part in parts:
        lo, hi = part.bounds
        shifts.append((x - lo[0], PLATE_GAP + (height - (hi[1] - lo[1])) / 2 - lo[1], -lo[2]))
        x += hi[0] - lo[0] + PLATE_GAP
    return shifts


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
    spec = asdict(pair.spec)
    spec["backlash"] = pair.spec.backlash_mm
    parts = {}
    for part in (pair.pinion, pair.wheel):
        check = pair.checks[part.name]
        parts[part.name] = {"teeth": pair.spec.z if part.name == "pinion" else pair.wheel_teeth,
                            **part_record(part, check)}
    report = {"tool": "wheelstep gears", "parameters": spec, "parts": parts}
    if pair.law is not None:
        report["u"] = pair.law.u
    if pair.partition is not None:
        report["arc_mm"] = pair.partition.arc
        report["sectors"] = partition_rows(pair.partition)
    if pair.generated is not None:
        report["generated"] = generated_report(pair)
    if meshing is not None:
        report["meshing"] = meshing
    return report


def generated_report(pair: GearPair) -> dict:
    """Generated-teeth figures: pitch, module, backlash budget, undercut and tip-land margins."""
    gen = pair.generated
    alpha = gen.cutter.pressure_angle
    opening = pair.spec.install_distance - pair.spec.center_distance
    return {
        "method": "pinion cut by a rolling rack with teeth tilted towards the radius (pivoting "
                  "at pitch-curve corners); wheel carved by the pinion moving along the exact law, "
                  "widened by a constant angular backlash",
        "tilt": pair.spec.tilt,
        "rolling_center_distance_mm": gen.center_distance,
        "pitch_mm": gen.pitch,
        "module_mm": gen.module,
        "pinion_teeth": gen.pinion_teeth,
        "wheel_teeth": gen.wheel_teeth,
        "corner": gen.corner,
        "blend_deg": pair.spec.blend,
        "backlash": {
            "normal_backlash_mm": gen.cutter.backlash,
            "wheel_angular_play_arcmin": float(np.degrees(gen.play) * 60.0 * 2.0),
            "center_distance_opening_mm": 0.0,
            "opening_would_add_normal_mm": 2.0 * opening * float(np.sin(alpha)),
            "note": "teeth generated for the installed distance; backlash by thinning (pinion "
                    "teeth by j_n/2, wheel by a constant angular play worth j_n/2 at its mean "
                    "pitch radius), none by opening the centre distance",
        },
        "undercut_limit_mm": gen.undercut_limit,
        "pitch_curve_min_convex_radius_mm": gen.min_curvature_radius,
        "pinion_min_tip_land_mm": gen.pinion_tip_land,
        "wheel_min_tip_land_mm": gen.wheel_tip_land,
        "topped_teeth": {name: {"count": count, "height_removed_mm": drop}
                         for name, (count, drop) in gen.topping.items()},
    }


def gear_pair_files(pair: GearPair, out: Path, fmt: str = "both",
                    meshing: dict | None = None) -> dict[Path, bytes]:
    """File name -> contents for the pair: STL per gear, a 3MF plate, and gears.json."""
    files: dict[Path, bytes] = {}
    parts = [pair.pinion, pair.wheel]
    if fmt in ("stl", "both"):
        for part in parts:
            files[out / f"{part.name}.stl"] = stl_bytes(part.vertices, part.faces, f"wheelstep {part.name}")
    if fmt in ("3mf", "both"):
        meta = {k: f"{v:g}" if isinstance(v, float) else str(v)
                for k, v in asdict(pair.spec).items() if v is not None}
        objects = [PlateObject(part.name, part.vertices, part.faces, shift, meta)
                   for part, shift in zip(parts, plate_layout(parts))]
        files[out / "gears.3mf"] = threemf_bytes(
            objects, {"Title": "wheelstep gear pair", "Application": "wheelstep"})
    files[out / "gears.json"] = json_bytes(gear_pair_report(pair, meshing))
    return files
