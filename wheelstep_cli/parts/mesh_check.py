"""Meshing check of a gear pair (SPEC §10): law -> check -> report and text.

Shared by ``wheelstep mesh-check`` and ``wheelstep gears`` (which checks what it writes).
The plot is :func:`wheelstep_cli.render.meshing_plot.meshing_plot_png`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial
from typing import Callable

import numpy as np

from wheelstep_cli.gears import pitch
from wheelstep_cli.gears.law import PitchLaw
from wheelstep_cli.gears.meshing import MeshingReport, MeshingSettings, check_meshing
from wheelstep_cli.gears.pitch import CrankLaw
from wheelstep_cli.gears.transmission import TransmissionLaw


@dataclass(frozen=True)
class _AdaptedLaw:
    """Today's CrankLaw or PitchLaw as a TransmissionLaw (until the law classes replace both)."""

    phi_period: float
    theta_period: float
    corners: tuple[float, ...]
    ratio: Callable[[np.ndarray], np.ndarray]
    pinion_angle: Callable[[np.ndarray], np.ndarray]
    carrier_angle: Callable[[np.ndarray], np.ndarray]
    hub_speed_factor: Callable[[np.ndarray], np.ndarray]


def _ones(phi: np.ndarray) -> np.ndarray:
    """The hub speed factor of a law with no mechanism behind it."""
    return np.ones_like(np.asarray(phi, dtype=float))


def as_transmission_law(law: CrankLaw | PitchLaw) -> TransmissionLaw:
    """The crank law (period n*pi/2 of the pinion, f = dX01/dphi) or a tabulated law as the
    TransmissionLaw the check takes."""
    if isinstance(law, CrankLaw):
        return _AdaptedLaw(np.pi / 2.0, law.turns * np.pi / 2.0,
                           (np.pi / 4.0,) if law.b > 0 else (), partial(pitch.ratio, law),
                           partial(pitch.pinion_angle, law), partial(pitch.carrier_angle, law),
                           partial(pitch.hub_speed_analogue, law))
    return _AdaptedLaw(law.phi_period, law.theta_period, law.corners, law.ratio,
                       law.pinion_angle, law.carrier_angle, law.hub_factor or _ones)


def check_crank_pair(pinion: np.ndarray, wheel: np.ndarray, law: CrankLaw, distance: float,
                     samples: int = MeshingSettings.samples, window: float | None = None,
                     progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Run the meshing check of two outlines (mm, own frames) over one period of the law:
    ``samples`` poses, mesh window half-height ``window`` mm (None: the settings' default)."""
    settings = replace(MeshingSettings(), samples=samples, window=window)
    return check_meshing(pinion, wheel, as_transmission_law(law), distance, settings,
                         progress=progress)


def check_gear_pair(pair, settings: MeshingSettings = MeshingSettings(),
                    progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Meshing check of a built :class:`~wheelstep_cli.parts.gear_pair.GearPair` as it will be
    written: both meshes are sectioned at mid-thickness (SPEC §10) and checked at the
    installed centre distance over one period of the law."""
    from wheelstep_cli.formats.mesh_read import section_outline

    pinion = section_outline(pair.pinion.vertices, pair.pinion.faces, "pinion")
    wheel = section_outline(pair.wheel.vertices, pair.wheel.faces, "wheel")
    generated = getattr(pair, "generated", None)
    law = generated.law if generated is not None and pair.law is None else pair.law
    return check_meshing(pinion, wheel, as_transmission_law(law), pair.spec.install_distance,
                         settings, progress=progress)


def meshing_record(report: MeshingReport) -> dict:
    """The summary stored in gears.json, saying what was checked."""
    return {"source": "mid-thickness sections of the written meshes (SPEC §10)",
            **report.to_dict()}


def _fmt(value, spec: str) -> str:
    return "n/a" if value is None else format(value, spec)


def meshing_lines(summary: dict) -> list[str]:
    """Human-readable lines of a meshing summary (``MeshingReport.to_dict()``)."""
    lines = []
    if summary["interference"]:
        lines.append(f"interference: YES at {summary['interfering_poses']} of {summary['samples']} "
                     f"poses (max overlap {summary['max_overlap_area_mm2']:.3f} mm2, "
                     f"penetration {summary['max_penetration_mm']:.3f} mm)")
    else:
        lines.append("interference: none")
    if summary["contact_lost"]:
        lines.append("contact: LOST at some poses (teeth out of mesh in the drive direction)")
    lines.append(f"backlash: {_fmt(summary['backlash_min_mm'], '.3f')} .. "
                 f"{_fmt(summary['backlash_max_mm'], '.3f')} mm on the wheel pitch curve "
                 f"({_fmt(summary['backlash_min_arcmin'], '.1f')}' .. "
                 f"{_fmt(summary['backlash_max_arcmin'], '.1f')}' at the wheel)")
    lines.append(f"transmission error: {_fmt(summary['te_peak_to_peak_arcmin'], '.2f')}' "
                 f"peak-to-peak (largest step between poses "
                 f"{_fmt(summary['te_max_step_arcmin'], '.2f')}')")
    lines.append(f"hub speed ripple: {_fmt(summary['hub_speed_ripple_pct'], '.2f')} % "
                 f"(the law alone, same sampling: {summary['law_hub_speed_ripple_pct']:.2f} %)")
    if summary["interference"]:
        lines.append(f"hub speed ripple where the teeth do not interfere "
                     f"({summary['clear_poses']} poses): "
                     f"{_fmt(summary['hub_speed_ripple_clear_pct'], '.2f')} %")
    return lines
