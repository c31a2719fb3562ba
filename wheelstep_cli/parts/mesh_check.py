"""Meshing check of a crank-law gear pair (SPEC §10): law -> transmission -> report, text, plot.

Shared by ``wheelstep mesh-check`` and ``wheelstep gears`` (which checks what it writes).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from wheelstep_cli.gears.meshing import DEFAULT_SAMPLES, MeshingReport, Transmission, check_meshing
from wheelstep_cli.gears.transmission import TransmissionLaw


def _transmission(law: TransmissionLaw) -> Transmission:
    return Transmission(law.carrier_angle, law.theta_period, law.hub_speed_factor)


def check_crank_pair(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                     samples: int = DEFAULT_SAMPLES, window: float | None = None,
                     progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Run the meshing check of two outlines (mm, own frames) over one period of the law."""
    return check_meshing(pinion, wheel, _transmission(law), distance, samples=samples,
                         window=window, progress=progress)


def check_gear_pair(pair, samples: int = DEFAULT_SAMPLES,
                    progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Meshing check of a built :class:`~wheelstep_cli.parts.gear_pair.GearPair` as it will be
    written: both meshes are sectioned at mid-thickness (SPEC §10) and checked at the
    installed centre distance over one period of the law."""
    from wheelstep_cli.geometry.solids import section_outline

    pinion = section_outline(pair.pinion.vertices, pair.pinion.faces, "pinion")
    wheel = section_outline(pair.wheel.vertices, pair.wheel.faces, "wheel")
    generated = getattr(pair, "generated", None)
    if generated is not None and pair.law is None:        # a --law-csv pair: its own law
        return check_crank_pair(pinion, wheel, generated.law, pair.spec.install_distance, samples,
                                progress=progress)
    return check_crank_pair(pinion, wheel, pair.law, pair.spec.install_distance, samples,
                            progress=progress)


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


def meshing_plot_png(report: MeshingReport, title: str) -> bytes:
    """A PNG for people: transfer function (law vs drive contact), its rate, TE, hub speed."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deg = np.degrees
    arcmin = 60.0 * 180.0 / np.pi
    theta = deg(report.theta)
    rate_law = report.hub_speed_law  # shown relative to its mean below
    fig, axes = plt.subplots(4, 1, figsize=(10, 12), sharex=True)
    ax = axes[0]
    ax.plot(theta, deg(report.phi_law), "k-", lw=1.5, label="law phi(theta)")
    ax.plot(theta, deg(report.phi_drive), "r--", lw=1, label="drive-side contact")
    ax.set_ylabel("wheel angle phi (deg)")
    ax.legend(loc="upper left")
    ax.set_title(title)
    ax = axes[1]
    step = np.gradient(report.theta)
    ax.plot(theta, np.gradient(report.phi_law) / step, "k-", lw=1.5, label="law dphi/dtheta")
    ax.plot(theta, np.gradient(report.phi_drive) / step, "r-", lw=0.7, label="drive contact")
    ax.set_ylabel("transfer ratio dphi/dtheta")
    _clip_axis(ax, np.gradient(report.phi_law) / step)
    ax.legend(loc="upper left")
    ax = axes[2]
    ax.plot(theta, report.transmission_error * arcmin, "r-", lw=0.8, label="drive side (TE)")
    ax.plot(theta, (report.phi_coast - report.phi_law) * arcmin, "b-", lw=0.8, label="coast side")
    _shade(ax, theta, report.interference)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_ylabel("contact - law (arcmin)")
    ax.legend(loc="upper left")
    ax = axes[3]
    mean = float(np.mean(rate_law))
    ax.plot(theta, 100.0 * (rate_law / mean - 1.0), "k-", lw=1.5, label="law")
    ax.plot(theta, 100.0 * (report.hub_speed / mean - 1.0), "r-", lw=0.7,
            label=f"drive contact (ripple {100 * report.hub_speed_ripple:.2f} %)")
    _shade(ax, theta, report.interference)
    if report.interferes and report.clear.any():
        clear = 100.0 * (report.hub_speed[report.clear] / mean - 1.0)
        lo, hi = float(np.min(clear)), float(np.max(clear))
        pad = max(hi - lo, 1.0)
        ax.set_ylim(lo - pad, hi + pad)
        ax.set_title("spikes where the teeth interfere are clipped", fontsize=9)
    ax.set_ylabel("hub speed - mean (% of mean)")
    ax.set_xlabel("pinion angle theta (deg)")
    ax.legend(loc="upper left")
    for ax in axes:
        ax.grid(True, lw=0.3)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def _clip_axis(ax, reference: np.ndarray) -> None:
    """Keep spikes from flattening the curve: y range = reference range widened 5 times."""
    lo, hi = float(np.min(reference)), float(np.max(reference))
    pad = max(2.0 * (hi - lo), 0.05 * abs(hi))
    ax.set_ylim(lo - pad, hi + pad)


def _shade(ax, theta: np.ndarray, mask: np.ndarray) -> None:
    """Shade interfering poses."""
    if mask.any():
        ax.fill_between(theta, 0, 1, where=mask, color="orange", alpha=0.3,
                        transform=ax.get_xaxis_transform(), label="interference")
