"""The meshing check's plot (SPEC §10): transfer function, its rate, the position error
e(theta) of both flanks (um) and the output (hub) speed, as PNG.

matplotlib (Agg) is imported lazily. Angles in the report in radians; degrees on the axes,
position errors in micrometres.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from wheelstep_cli.gears.meshing import MeshingReport


def meshing_plot_png(report: MeshingReport, title: str, speed: str = "hub speed") -> bytes:
    """A PNG for people: transfer function (law vs drive contact), its rate, e(theta) of both
    flanks (um, SPEC §10) and the pointwise output speed (a diagnostic). ``speed``: what that
    speed is, as the text reports say it (a law CSV's gears drive no hub: "output speed")."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deg = np.degrees
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
    for side, flank, colour in (("drive", report.drive, "r-"), ("coast", report.coast, "b-")):
        ax.plot(theta, flank.error_um, colour, lw=0.8,
                label=f"{side} flank: F'i {flank.total_um:.1f} um, f'i {flank.tooth_um:.1f} um, "
                      f"ripple {100 * flank.ripple:.2f} % (3 tooth harmonics)")
    _shade(ax, theta, report.interference)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_ylabel("e on wheel pitch curve (um)")
    ax.legend(loc="upper left", fontsize=8)
    ax = axes[3]
    mean = float(np.mean(rate_law))
    ax.plot(theta, 100.0 * (rate_law / mean - 1.0), "k-", lw=1.5, label="law")
    ax.plot(theta, 100.0 * (report.hub_speed / mean - 1.0), "r-", lw=0.7,
            label=f"drive contact, pointwise (diagnostic: {100 * report.hub_speed_ripple:.2f} %, "
                  "grows with the sampling)")
    _shade(ax, theta, report.interference)
    if report.interferes and report.clear.any():
        clear = 100.0 * (report.hub_speed[report.clear] / mean - 1.0)
        lo, hi = float(np.min(clear)), float(np.max(clear))
        pad = max(hi - lo, 1.0)
        ax.set_ylim(lo - pad, hi + pad)
        ax.set_title("spikes where the teeth interfere are clipped", fontsize=9)
    ax.set_ylabel(f"{speed} - mean (% of mean)")
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
