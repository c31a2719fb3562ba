"""Picture of the gear pair in assembly phase (PNG or SVG): both faces, pitch curves, the
handover corners, marks, bores and the main dimensions.

Poses follow the meshing check (SPEC §10): the pinion turns about the origin by -theta, the
wheel about (D, 0) by pi + phi. mm and radians inside; degrees only in the labels.
matplotlib (Agg) is imported lazily.
"""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np

PICTURE_FORMATS = ("png", "svg")
PINION_COLOUR, WHEEL_COLOUR = "#9ecae1", "#fdd0a2"


@dataclass(frozen=True)
class PairDrawing:
    """What a picture of the pair needs: ``faces`` (name -> object with ``outline``,
    ``holes``, ``marks``, mm in the gear's own frame), the ``law`` the teeth follow,
    the centre ``distance`` (mm), the ``module`` (mm), tooth counts ``teeth``
    (name -> int) and the face width ``thickness`` (mm)."""

    faces: dict
    law: object
    distance: float
    module: float
    teeth: dict
    thickness: float
    crank: bool = True      # the mover's crank law (its corners are shoe handovers), not a law CSV


def assembly_phase(law) -> tuple[float, float]:
    """Pinion and wheel angles (rad) meeting at the line of centres with the carrier at 0
    (a shoe in mid-stance), as gears.json states them (gears.phase)."""
    from wheelstep_cli.gears.phase import assembly_phase as phase_of

    phase = phase_of(law)
    return phase.pinion_mark, phase.wheel_mark


def handover_angle(law) -> float:
    """Carrier angle (rad) of the first shoe handover (a pitch-curve corner; the blend's
    centre for a blended law; the period's start for a law without one)."""
    corners = tuple(law.corners) or tuple(getattr(law, "blended_corners", ()))
    return float(corners[0]) if corners else float(law.phi_start)


def rotate(points: np.ndarray, angle: float) -> np.ndarray:
    """``points`` (N, 2) turned counter-clockwise by ``angle`` rad about the origin."""
    c, s = np.cos(angle), np.sin(angle)
    return np.asarray(points, dtype=float) @ np.array([[c, s], [-s, c]])


def posed(name: str, points: np.ndarray, theta: float, phi: float, distance: float) -> np.ndarray:
    """``points`` of gear ``name`` (own frame, mm) in the world at pinion angle ``theta``
    and wheel angle ``phi`` (rad), centres at (0, 0) and (``distance``, 0)."""
    if name == "pinion":
        return rotate(points, -theta)
    return rotate(points, np.pi + phi) + np.array([distance, 0.0])


def pitch_curve(name: str, law, distance: float, samples: int = 2048) -> tuple[np.ndarray, np.ndarray]:
    """A gear's whole pitch curve in its own frame (closed (N, 2) mm) and the carrier angles
    (rad) of its points: the pinion's radius r(phi) lies at body angle theta(phi), the
    wheel's r_H = D - r at body angle -phi."""
    periods = law.pinion_periods if name == "pinion" else law.wheel_periods
    phi = law.phi_start + periods * law.phi_period * np.linspace(0.0, 1.0, samples + 1)
    r = distance / (1.0 + np.asarray(law.ratio(phi), dtype=float))
    if name == "pinion":
        angle = np.asarray(law.pinion_angle(phi), dtype=float)
    else:
        r, angle = distance - r, -phi
    return np.column_stack([r * np.cos(angle), r * np.sin(angle)]), phi


def _handovers(name: str, law, distance: float) -> np.ndarray:
    """The shoe handovers on a gear's pitch curve (own frame, (K, 2) mm)."""
    first = handover_angle(law)
    periods = law.pinion_periods if name == "pinion" else law.wheel_periods
    phi = first + law.phi_period * np.arange(periods)
    r = distance / (1.0 + np.asarray(law.ratio(phi), dtype=float))
    if name == "pinion":
        angle = np.asarray(law.pinion_angle(phi), dtype=float)
    else:
        r, angle = distance - r, -phi
    return np.column_stack([r * np.cos(angle), r * np.sin(angle)])


def pose_transform(ax, name: str, theta: float, phi: float, distance: float):
    """The matplotlib transform drawing gear ``name``'s own frame (mm) on ``ax`` at pinion
    angle ``theta`` and wheel angle ``phi`` (rad), as :func:`posed` places points."""
    from matplotlib.transforms import Affine2D

    if name == "pinion":
        return Affine2D().rotate(-theta) + ax.transData
    return Affine2D().rotate(np.pi + phi).translate(distance, 0.0) + ax.transData


def draw_pair(ax, drawing: PairDrawing, theta: float, phi: float, pitch: bool = True) -> dict:
    """Both faces (filled, bores cut, marks drawn) at ``theta``/``phi`` rad on ``ax``, with
    their pitch curves and handovers when ``pitch``; each gear drawn in its own frame under
    a :func:`pose_transform`, so a new pose only sets the transforms. Returns name -> artists."""
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path

    artists = {}
    for name, colour in (("pinion", PINION_COLOUR), ("wheel", WHEEL_COLOUR)):
        face = drawing.faces[name]
        rings = [np.asarray(ring, dtype=float) for ring in (face.outline, *face.holes)]
        codes = [np.r_[Path.MOVETO, np.full(len(v) - 1, Path.LINETO), Path.CLOSEPOLY] for v in rings]
        path = Path(np.concatenate([np.vstack([v, v[:1]]) for v in rings]), np.concatenate(codes))
        own = [ax.add_patch(PathPatch(path, facecolor=colour, edgecolor="k", lw=0.6, label=name))]
        for mark in face.marks:
            m = np.vstack([mark, mark[:1]])
            own += ax.plot(m[:, 0], m[:, 1], "-", color="darkred", lw=1.0)
        if pitch:
            curve, _ = pitch_curve(name, drawing.law, drawing.distance)
            own += ax.plot(curve[:, 0], curve[:, 1], "-.", color="tab:green", lw=0.9)
            h = _handovers(name, drawing.law, drawing.distance)
            own += ax.plot(h[:, 0], h[:, 1], "o", ms=4, mfc="none", mec="purple")
        artists[name] = own
    set_pose(ax, artists, theta, phi, drawing.distance)
    ax.plot([0.0, drawing.distance], [0.0, 0.0], "+", color="k", ms=10)
    return artists


def set_pose(ax, artists: dict, theta: float, phi: float, distance: float) -> None:
    """Move the artists of :func:`draw_pair` to pinion angle ``theta``, wheel ``phi`` (rad)."""
    for name, own in artists.items():
        transform = pose_transform(ax, name, theta, phi, distance)
        for artist in own:
            artist.set_transform(transform)


def pair_limits(ax, drawing: PairDrawing, pad: float = 0.04) -> None:
    """Axis limits holding both gears' tip circles (mm), ``pad`` of the width around."""
    tip_p = _radii(drawing.faces["pinion"])[0]
    tip_w = _radii(drawing.faces["wheel"])[0]
    margin = pad * (drawing.distance + tip_p + tip_w)
    half = max(tip_p, tip_w) + margin
    ax.set_xlim(-tip_p - margin, drawing.distance + tip_w + margin)
    ax.set_ylim(-half, half)


def _radii(face) -> tuple[float, float]:
    """Tip and root radii (mm) of a face: its outline's largest and smallest radius."""
    r = np.hypot(face.outline[:, 0], face.outline[:, 1])
    return float(r.max()), float(r.min())


def _dimensions(ax, drawing: PairDrawing) -> None:
    """Centre distance, tip and root circles (dashed), and a table of the main figures."""
    d = drawing.distance
    tips = {}
    for name, centre in (("pinion", 0.0), ("wheel", d)):
        tip, root = _radii(drawing.faces[name])
        tips[name] = tip
        t = np.linspace(0.0, 2.0 * np.pi, 361)
        for radius, style in ((tip, "--"), (root, ":")):
            ax.plot(centre + radius * np.cos(t), radius * np.sin(t), style, color="0.55", lw=0.6)
    low = -1.08 * max(tips.values())
    ax.annotate("", (0.0, low), (d, low), arrowprops={"arrowstyle": "<->", "lw": 0.8})
    ax.plot([0.0, 0.0], [0.0, low], ":", color="0.4", lw=0.6)
    ax.plot([d, d], [0.0, low], ":", color="0.4", lw=0.6)
    ax.text(d / 2.0, low, f"centre distance {d:.6g} mm", ha="center", va="bottom", fontsize=8)
    rows = [f"module {drawing.module:.4g} mm, face width {drawing.thickness:g} mm"]
    for name in ("pinion", "wheel"):
        tip, root = _radii(drawing.faces[name])
        rows.append(f"{name}: {drawing.teeth[name]} teeth, tip R {tip:.2f} / root R {root:.2f} mm"
                    f" (diameter {2 * tip:.1f} / {2 * root:.1f})")
    rows.append("dashed: tip circles, dotted: root circles, dash-dot: pitch curves, "
                + ("circles: shoe handovers" if drawing.crank else
                   "circles: one per law period (its first corner, else its start)"))
    ax.text(0.01, 0.99, "\n".join(rows), transform=ax.transAxes, va="top", ha="left", fontsize=7,
            bbox={"facecolor": "white", "alpha": 0.85, "lw": 0.5})


def pair_picture(drawing: PairDrawing, fmt: str) -> bytes:
    """The pair in assembly phase as ``fmt`` ("png" or "svg") bytes, deterministic."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    theta, phi = assembly_phase(drawing.law)
    with matplotlib.rc_context({"svg.hashsalt": "wheelstep", "svg.fonttype": "none"}):
        fig, ax = plt.subplots(figsize=(11, 7.5), dpi=110)
        try:
            draw_pair(ax, drawing, theta, phi)
            _dimensions(ax, drawing)
            pair_limits(ax, drawing)
            tip = max(_radii(face)[0] for face in drawing.faces.values())
            ax.set_ylim(-1.15 * tip, 1.3 * tip)  # room for the dimension below, the table above
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlabel("mm")
            ax.set_ylabel("mm")
            ax.legend(loc="lower right", fontsize=8)
            zero = "carrier at 0 (a shoe in mid-stance)" if drawing.crank else "the law's driven angle at 0"
            ax.set_title(f"gear pair in assembly phase: {zero}, "
                         f"pinion {np.degrees(theta):.1f} deg, wheel {np.degrees(phi):.1f} deg",
                         fontsize=10)
            fig.tight_layout()
            buf = io.BytesIO()
            meta = {"Date": None} if fmt == "svg" else {"Software": None}
            fig.savefig(buf, format=fmt, metadata=meta)
        finally:
            plt.close(fig)
    return buf.getvalue()
