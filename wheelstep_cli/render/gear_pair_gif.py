"""Animation of the gear pair turning through a shoe handover (a law CSV's first corner)
as a GIF: the whole pair and a close-up of the mesh, the drive contact point, and the
meshing check's transmission error (um) and output (hub) speed on every frame.

The poses are the meshing check's own (SPEC §10): the wheel stands where the drive flank
touches (phi_drive). mm and radians inside; degrees, um and % only in the labels.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from wheelstep_cli.render.gif import animation_gif
from wheelstep_cli.render.gear_pair_plot import (PairDrawing, draw_pair, handover_angle, pair_limits, posed,
                                                 set_pose)

GIF_FRAMES = 60


def handover_poses(report, law, frames: int = GIF_FRAMES, pitches: float = 1.0) -> np.ndarray:
    """Indices of the check's poses (at most ``frames``, in turning order, no repeats)
    spanning ``pitches`` pinion tooth pitches either side of the first shoe handover."""
    theta_c = float(law.pinion_angle(np.array([handover_angle(law)]))[0])
    half = pitches * 2.0 * np.pi / report.teeth
    wanted = theta_c + np.linspace(-half, half, frames)
    step = report.period / len(report.theta)
    index = np.rint((wanted - report.theta[0]) / step).astype(int) % len(report.theta)
    _, first = np.unique(index, return_index=True)
    return index[np.sort(first)]


def contact_point(drawing: PairDrawing, theta: float, phi: float, reach: float) -> np.ndarray:
    """The world point (mm) where the posed outlines come closest near the pitch point:
    the midpoint of the nearest pinion/wheel vertex pair within ``reach`` mm of the line
    of centres' crossing of the pitch curves."""
    p = posed("pinion", drawing.faces["pinion"].outline, theta, phi, drawing.distance)
    w = posed("wheel", drawing.faces["wheel"].outline, theta, phi, drawing.distance)
    rate = float(np.asarray(drawing.law.ratio(np.array([phi])))[0])
    centre = np.array([drawing.distance / (1.0 + rate), 0.0])
    p = p[np.hypot(*(p - centre).T) < reach]
    w = w[np.hypot(*(w - centre).T) < reach]
    if len(p) == 0 or len(w) == 0:
        return centre
    gap = np.hypot(p[:, None, 0] - w[None, :, 0], p[:, None, 1] - w[None, :, 1])
    i, j = np.unravel_index(int(np.argmin(gap)), gap.shape)
    return 0.5 * (p[i] + w[j])


def turning_through(law, speed: str = "hub speed") -> str:
    """What the animation turns the pair through (:func:`handover_poses`): a shoe handover for
    the crank law (``speed`` "hub speed"), a law CSV's first corner (its gears carry no shoes),
    the start of the period of a law without corners."""
    if not (tuple(law.corners) or tuple(getattr(law, "blended_corners", ()))):
        return "the start of the law's period"
    return "a shoe handover" if speed == "hub speed" else "the law's first corner"


def _readout(report, k: int, speed: str = "hub speed") -> str:
    """The text of pose ``k``: angles, the drive flank's TE and the output speed (``speed``:
    what it is, "hub speed" for the crank law)."""
    error = report.drive.error_um[k]
    mean = float(np.mean(report.hub_speed_law))
    change = 100.0 * (report.hub_speed[k] / mean - 1.0)
    law_speed = 100.0 * (report.hub_speed_law[k] / mean - 1.0)
    te = "no contact" if not np.isfinite(error) else f"{error:+.1f} um"
    hub = "n/a" if not np.isfinite(change) else f"{change:+.2f} %"
    driven = "carrier" if speed == "hub speed" else "wheel"     # a law CSV drives no carrier
    return (f"pinion {np.degrees(report.theta[k]):7.2f} deg   {driven} {np.degrees(report.phi_law[k]):7.2f} deg\n"
            f"TE (drive flank, on the wheel pitch curve) {te}\n"
            f"{speed} {hub} of the mean (law {law_speed:+.2f} %)"
            + ("   INTERFERENCE" if report.interference[k] else ""))


def pair_gif(drawing: PairDrawing, report, frames: int = GIF_FRAMES,
             progress: Callable[[int, int], None] | None = None) -> bytes:
    """GIF bytes of the pair turning through the first shoe handover (a law CSV's first
    corner; a law without one: the start of its period) over the poses of
    :func:`handover_poses`, ``progress(done, total)`` after each frame. The readout's speed
    is the hub's for the crank law (``drawing.crank``), else the law's output speed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    speed = "hub speed" if drawing.crank else "output speed"
    poses = handover_poses(report, drawing.law, frames)
    reach = 4.0 * drawing.module
    fig, (whole, close) = plt.subplots(1, 2, figsize=(10, 5), dpi=72,
                                       gridspec_kw={"width_ratios": [1.5, 1]})
    fig.subplots_adjust(left=0.05, right=0.98, bottom=0.06, top=0.8, wspace=0.15)
    drawn = {ax: draw_pair(ax, drawing, 0.0, 0.0, pitch=ax is whole) for ax in (whole, close)}
    dots = {ax: ax.plot([], [], "o", color="red", ms=5 if ax is whole else 8)[0] for ax in drawn}
    pair_limits(whole, drawing)
    whole.set_aspect("equal")
    close.set_aspect("equal")
    whole.set_title(f"pair turning through {turning_through(drawing.law, speed)}", fontsize=9)
    close.set_title("mesh close-up: red = drive contact", fontsize=9)
    text = fig.text(0.02, 0.97, "", fontsize=9, family="monospace", va="top")

    def frame(n: int):
        k = int(poses[n])
        theta = float(report.theta[k])
        phi = float(report.phi_drive[k]) if np.isfinite(report.phi_drive[k]) else float(report.phi_law[k])
        point = contact_point(drawing, theta, phi, reach)
        for ax, artists in drawn.items():
            set_pose(ax, artists, theta, phi, drawing.distance)
            dots[ax].set_data([point[0]], [point[1]])
        # the close-up follows the pitch point on the line of centres (not the contact, which jumps)
        centre = drawing.distance / (1.0 + float(np.asarray(drawing.law.ratio(np.array([phi])))[0]))
        close.set_xlim(centre - reach, centre + reach)
        close.set_ylim(-reach, reach)
        text.set_text(_readout(report, k, speed))
        if progress is not None:
            progress(n + 1, len(poses))
        return []

    return animation_gif(fig, frame, len(poses), fps=12, metadata={})
