"""Meshing check of a gear pair (SPEC §10): law -> check -> report and text.

Shared by ``wheelstep mesh-check`` and ``wheelstep gears`` (which checks what it writes).
The plot is :func:`wheelstep_cli.render.meshing_plot.meshing_plot_png`.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Callable

import numpy as np

from wheelstep_cli.gears.meshing import MeshingReport, MeshingSettings, check_meshing
from wheelstep_cli.gears.transmission import TransmissionLaw


def check_outlines(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                   samples: int | None = None, window: float | None = None,
                   progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Run the meshing check of two outlines (mm, own frames) over one period of any law:
    ``samples`` poses (None: 16 in the shortest tooth pitch, at least 1536), mesh window half-height
    ``window`` mm (None: the settings' default)."""
    settings = replace(MeshingSettings(), samples=samples, window=window)
    report = check_meshing(pinion, wheel, law, distance, settings, progress=progress)
    return replace(report, mounting=mounting_record(pinion, wheel, law, distance))


def check_gear_pair(pair, settings: MeshingSettings = MeshingSettings(),
                    progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Meshing check of a built :class:`~wheelstep_cli.parts.gear_pair.GearPair` as it will be
    written: both meshes are sectioned at mid-thickness (SPEC §10) and checked at the
    installed centre distance over one period of the law the teeth were generated for (the
    blended law with ``--blend``)."""
    from wheelstep_cli.geometry.solids import section_outline

    # the plate's mid-thickness (the parts stand on z = 0), not the mesh's: a hub is higher
    mid = 0.5 * float(pair.spec.thickness)
    pinion = section_outline(pair.pinion.vertices, pair.pinion.faces, "pinion", mid)
    wheel = section_outline(pair.wheel.vertices, pair.wheel.faces, "wheel", mid)
    # generated teeth are checked against the law they were cut for (blended when --blend)
    generated = getattr(pair, "generated", None)
    law = generated.law if generated is not None else pair.law
    report = check_meshing(pinion, wheel, law, pair.mounted_distance, settings, progress=progress,
                           teeth=pair.spec.z)
    return replace(report, mounting=mounting_record(pinion, wheel, law, pair.mounted_distance, generated,
                                                    float(getattr(pair, "inset", 0.0))))


def mounting_record(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                    generated=None, inset: float = 0.0) -> dict:
    """How much closer than ``distance`` (mm) the outlines (mm, own frames) may be mounted:
    their least separation over the law's poses (a wheel moved that little toward the
    pinion cannot reach it), and for generated teeth the tip clearances cut for it (mm): the
    pinion's spaces below the wheel's tips, the wheel's below the pinion's, and the smaller,
    each grown by 2 ``inset`` for outlines a fit drew ``inset`` mm smaller (each tip moves in
    by it, each space deepens by it)."""
    from wheelstep_cli.gears.meshing.mounting import least_separation

    samples = 192
    gap, theta = least_separation(pinion, wheel, law, distance, samples)
    record = {"closer_mm": gap, "at_pinion_deg": float(np.degrees(theta)), "samples": samples, "refined": 24,
              "how": "least separation of the two outlines over the law's poses: mounted up to "
                     "that much closer, no point of one can reach the other"}
    if generated is not None:
        pinion = float(generated.cutter.pinion_clearance * generated.module) + 2.0 * inset
        wheel = float(generated.cutter.clearance * generated.module) + 2.0 * inset
        record.update(tip_clearance_mm=min(pinion, wheel), pinion_spaces_mm=pinion, wheel_spaces_mm=wheel)
    return record


def mounting_line(mounting: dict) -> str:
    """One line saying how much closer the pair may be mounted (mm) and, for generated teeth,
    each gear's tip clearance (the wheel's is the one --clearance sets)."""
    from wheelstep_cli.gears.meshing.mounting import THIN

    if mounting["closer_mm"] <= 0.0:
        # the figure is a lower bound less the thinning's error: 0 is a gap within that error
        line = (f"mounting: the outlines come within {2 * THIN:.3f} mm or overlap at pinion angle "
                f"{mounting['at_pinion_deg']:.1f} deg: not known to be clear mounted any closer")
    else:
        line = (f"mounting: clear when mounted up to {mounting['closer_mm']:.3f} mm closer (least gap "
                f"between the outlines, at pinion angle {mounting['at_pinion_deg']:.1f} deg)")
    if "wheel_spaces_mm" in mounting:
        line += (f"; tip clearance {mounting['pinion_spaces_mm']:.3f} mm in the pinion's spaces, "
                 f"{mounting['wheel_spaces_mm']:.3f} mm in the wheel's (the wheel's set by --clearance)")
    return line


def meshing_record(report: MeshingReport) -> dict:
    """The summary stored in gears.json, saying what was checked."""
    return {"source": "mid-thickness sections of the written meshes (SPEC §10)",
            **report.to_dict()}


def figure_text(value, spec: str) -> str:
    """A figure formatted by ``spec``, or "n/a" when it was not measured (None)."""
    return "n/a" if value is None else format(value, spec)


def flank_line(side: str, flank: dict, own: float = 0.0, speed: str = "hub speed", note: str = "") -> str:
    """One line of a flank side's figures of merit (SPEC §10), ``flank`` from ``to_dict``;
    ``own``: the law's own output-speed ripple (%), which the bound leaves out: what the teeth
    add beyond it is said too when the law has one (a law CSV, a blend). ``speed``: what the
    ripple is of (a law CSV's gears drive no hub: their output speed); ``note``: said after
    the flank's name (what outlines the figures are of)."""
    ripple = flank["hub_speed_ripple_pct"]
    beyond = (f"; {max(0.0, ripple - own):.2f} % beyond the law's own {own:.2f} %"
              if ripple is not None and own > 0.01 else "")
    return (f"{side} flank{note}: F'i {figure_text(flank['F_i_total_um'], '.1f')} um, "
            f"f'i {figure_text(flank['f_i_tooth_um'], '.1f')} um, {speed} ripple "
            f"{figure_text(ripple, '.2f')} % (3 tooth harmonics{beyond}), "
            f"largest TE step {figure_text(flank['te_max_step_um'], '.1f')} um")


def _out_of_phase_cause(summary: dict) -> str:
    """Why a pair is out of phase, from what its summary found."""
    causes = [cause for found, cause in ((summary["interference"], "the teeth interfere"),
                                         (summary["contact_lost"], "the teeth lose contact (mounted too far apart?)"))
              if found]
    if causes:
        return "; ".join(causes)
    if summary["drive"]["F_i_total_um"] is None:
        return "its transmission error could not be measured"
    return "it runs about a tooth pitch off the law (assembled a tooth off?)"


def speed_words(law_csv: bool) -> str:
    """What a pair's speed ripple is of: a law CSV's gears (``law_csv``) drive no hub, so
    their output speed; the crank law's, the mover's hub speed."""
    return "output speed" if law_csv else "hub speed"


def meshing_lines(summary: dict) -> list[str]:
    """Human-readable lines of a meshing summary (``MeshingReport.to_dict()``, with the
    ``law`` record of the pair checked when there is one)."""
    speed = speed_words("csv" in (summary.get("law") or {}))
    lines = []
    if summary["interference"]:
        lines.append(f"interference: YES at {summary['interfering_poses']} of {summary['samples']} "
                     f"poses (max overlap {summary['max_overlap_area_mm2']:.3f} mm2, "
                     f"penetration {summary['max_penetration_mm']:.3f} mm)")
    else:
        lines.append("interference: none")
    if summary["contact_lost"]:
        lines.append("contact: LOST at some poses (teeth out of mesh in the drive direction)")
    lines.append("phase: in phase with the law" if summary["in_phase"] else
                 f"phase: OUT OF PHASE (the pair does not follow its law: {_out_of_phase_cause(summary)})")
    lines.append(f"backlash: {figure_text(summary['backlash_min_mm'], '.3f')} .. "
                 f"{figure_text(summary['backlash_max_mm'], '.3f')} mm on the wheel pitch curve "
                 f"({figure_text(summary['backlash_min_arcmin'], '.1f')}' .. "
                 f"{figure_text(summary['backlash_max_arcmin'], '.1f')}' at the wheel)")
    for side in ("drive", "coast"):
        lines.append(flank_line(side, summary[side], summary.get("law_hub_speed_ripple_pct", 0.0), speed))
    if "mounting" in summary:
        lines.append(mounting_line(summary["mounting"]))
    if "bounds" in summary:
        from wheelstep_cli.parts.bound_figures import bounds_line

        lines.append(bounds_line(summary["bounds"]))
    lines.append(f"diagnostic: pointwise {speed} ripple {figure_text(summary['diagnostic_pointwise_ripple_pct'], '.2f')} % "
                 f"(drive side, grows with the sampling; the law alone: "
                 f"{summary['law_hub_speed_ripple_pct']:.2f} %)")
    if summary["interference"]:
        lines.append(f"diagnostic: pointwise {speed} ripple where the teeth do not interfere "
                     f"({summary['clear_poses']} poses): "
                     f"{figure_text(summary['diagnostic_pointwise_ripple_clear_pct'], '.2f')} %")
    return lines
