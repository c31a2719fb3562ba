"""The non-circular gear pair as printable parts: design -> outlines -> solids -> files."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from wheelstep_cli.errors import require
from wheelstep_cli.gears.paper_teeth import ToothForm, check_tooth_form, pinion_outline, wheel_outline
from wheelstep_cli.gears.pitch import CrankLaw
from wheelstep_cli.gears.sectors import SectorPartition, sector_partition, sectors_per_quarter
from wheelstep_cli.geometry.solids import MeshReport, Part, extrude_plate, require_printable
from wheelstep_cli.io.jsonio import json_bytes
from wheelstep_cli.io.stl import stl_bytes
from wheelstep_cli.io.threemf import PlateObject, threemf_bytes

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

    @property
    def backlash_mm(self) -> float:
        return 0.25 * self.module if self.backlash is None else self.backlash

    def law(self) -> CrankLaw:
        return CrankLaw(self.a, self.b, self.c, self.center_distance, self.turns)

    def tooth_form(self) -> ToothForm:
        return ToothForm(self.module, self.backlash_mm)


#: Option names a gear-pair profile section or batch entry may set.
SPEC_KEYS = tuple(GearPairSpec.__dataclass_fields__)


@dataclass(frozen=True)
class GearPair:
    """A built gear pair: the law, its sector partition, outlines and checked parts."""

    spec: GearPairSpec
    law: CrankLaw
    partition: SectorPartition
    pinion_outline: np.ndarray
    wheel_outline: np.ndarray
    pinion: Part
    wheel: Part
    checks: dict[str, MeshReport] = field(default_factory=dict)


def build_gear_pair(spec: GearPairSpec) -> GearPair:
    """Compute, extrude and check both gears; raises DesignError for impossible designs."""
    law = spec.law()
    count = sectors_per_quarter(spec.z, spec.turns)
    require(spec.install_distance >= spec.center_distance, "install-distance", spec.install_distance,
            f"must be >= center-distance {spec.center_distance:g} mm")
    require(spec.install_distance <= spec.center_distance + spec.module, "install-distance",
            spec.install_distance,
            f"must be <= center-distance + module = {spec.center_distance + spec.module:g} mm "
            "(farther apart the teeth lose contact)")
    partition = sector_partition(law, count)
    form = spec.tooth_form()
    check_tooth_form(partition, form)
    p_outline = pinion_outline(partition, form)
    w_outline = wheel_outline(partition, form)
    pinion = extrude_plate("pinion", p_outline, spec.thickness, spec.bore)
    wheel = extrude_plate("wheel", w_outline, spec.thickness, spec.bore)
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    return GearPair(spec, law, partition, p_outline, w_outline, pinion, wheel, checks)


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
        parts[part.name] = {
            "teeth": pair.spec.z if part.name == "pinion" else pair.spec.z * pair.spec.turns,
            "volume_mm3": check.volume,
            "bounding_box_mm": part.bounds,
            "triangles": check.triangles,
            "checks": {"manifold": True, "watertight": check.watertight,
                       "winding_consistent": check.winding_consistent,
                       "volume_matches_outline": check.volume_error < 1e-3},
        }
    return {
        "tool": "wheelstep gears",
        "parameters": spec,
        "u": pair.law.u,
        "arc_mm": pair.partition.arc,
        "sectors": partition_rows(pair.partition),
        "parts": parts,
        **({"meshing": meshing} if meshing is not None else {}),
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
