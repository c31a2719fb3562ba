"""The tables ``wheelstep pitch`` and ``wheelstep teeth`` print: sector partition and tooth
points of a gear pair spec, as plain data in degrees and mm."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.paper_teeth import pinion_flanks, wheel_flanks
from wheelstep_cli.gears.sectors import sector_partition, sectors_per_quarter
from wheelstep_cli.parts.gear_pair import GearPairSpec, check_paper_teeth, partition_rows

#: gear -> the name of its angle in the tooth table.
FLANK_ANGLES = {"pinion": "theta", "wheel": "phi"}


def pitch_report(spec: GearPairSpec) -> dict:
    """The equal-arc sector partition of one carrier quarter (SPEC §4): ``u``, the common arc
    (mm) and one row per sector (degrees and mm)."""
    law = spec.law()
    part = sector_partition(law, sectors_per_quarter(spec.z, spec.turns), spec.paper_distances[0])
    return {"u": law.u, "arc_mm": part.arc, "sectors": partition_rows(part)}


def _flank_rows(flanks, angle: str) -> list[dict]:
    """One dict per sector: its points j = 1.. with both flank angles (deg) and radius (mm)."""
    return [
        {"i": i + 1, "points": [
            {"j": j + 1, f"{angle}_deg": np.degrees(flanks.left[i, j]),
             f"{angle}_s_deg": np.degrees(flanks.right[i, j]), "r_mm": flanks.radius[i, j]}
            for j in range(flanks.left.shape[1])]}
        for i in range(flanks.left.shape[0])
    ]


def teeth_report(spec: GearPairSpec) -> dict:
    """The sector-involute tooth points of both gears (SPEC §5): ``{"pinion": [...],
    "wheel": [...]}``; raises DesignError for teeth that cannot be formed."""
    part = sector_partition(spec.law(), sectors_per_quarter(spec.z, spec.turns), spec.paper_distances[0])
    form = spec.tooth_form()
    check_paper_teeth(part, form, spec)
    flanks = {"pinion": pinion_flanks(part, form), "wheel": wheel_flanks(part, form)}
    return {gear: _flank_rows(flanks[gear], angle) for gear, angle in FLANK_ANGLES.items()}
