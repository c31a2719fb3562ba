"""PNG plots and GIF animations of the mechanism analyses (hub speed, stairs, linkages,
trajectories).

Each function takes plain arrays/dataclasses and returns the file's bytes, so the
command can write every output atomically. matplotlib (Agg) is imported lazily.
"""

from __future__ import annotations

import io

import numpy as np


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    _plt().close(fig)
    return buf.getvalue()


def stairs_png(climb: np.ndarray, descent: np.ndarray, climb_path: np.ndarray,
               descent_path: np.ndarray, title: str, cycle: tuple = (None, None)) -> bytes:
    """Climb/descent kinematics (rows of phi[rad], X01, dX01, d2X01, Y01, dY01, d2Y01) and hub paths.

    ``cycle`` = (advance, rise) per cycle in mm, shown in the hub-path titles."""
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    for col, (name, kin) in enumerate((("climb", climb), ("descent", descent))):
        ax = axes[0, col]
        deg = np.degrees(kin[:, 0])
        ax.plot(deg, kin[:, 1], label="X01 (mm)")
        ax.plot(deg, kin[:, 4], label="Y01 (mm)")
        ax.plot(deg, kin[:, 2], "--", label="dX01/dphi (mm/rad)")
        ax.plot(deg, kin[:, 5], "--", label="dY01/dphi (mm/rad)")
        ax.set_xlabel("hub angle phi (deg)")
        ax.set_ylabel("mm, mm/rad")
        ax.set_title(f"{name}: one cycle (landing to landing + 90 deg)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    for col, (name, path) in enumerate((("climb", climb_path), ("descent", descent_path))):
        ax = axes[1, col]
        ax.plot(path[:, 0], path[:, 1], color="C3")
        ax.plot(path[0, 0], path[0, 1], "o", color="C3", label="first landing")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("hub x (mm)")
        ax.set_ylabel("hub y above the first tread (mm)")
        per = "" if cycle[0] is None else f": {cycle[0]:.1f} mm on, {cycle[1]:.1f} mm {'up' if name == 'climb' else 'down'} per cycle"
        ax.set_title(f"hub path, {name}, 3 cycles{per}", fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    return _png(fig)


def _draw_linkage(ax, linkage, joints, k, path, support):
    ax.plot(path[:, 0], path[:, 1], color="C0", lw=1.2, label=f"foot path ({linkage.foot})")
    ax.plot(path[support, 0], path[support, 1], ".", color="C3", ms=3, label="support phase")
    lines = []
    for a, b in linkage.links:
        seg = np.array([joints[a][k], joints[b][k]])
        (line,) = ax.plot(seg[:, 0], seg[:, 1], "-", color="k", lw=2, solid_capstyle="round")
        lines.append(line)
    fixed = [s for s in linkage.steps if type(s).__name__ == "Fixed"]
    ax.plot([s.x for s in fixed], [s.y for s in fixed], "^", color="C2", ms=9, label="frame pivots")
    (foot,) = ax.plot(*joints[linkage.foot][k], "o", color="C3", ms=7)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(True, alpha=0.3)
    return lines, foot


def linkage_png(linkage, solution, gait, rpm: float) -> bytes:
    """Foot path with the linkage drawn at crank angle 0, foot speed and body speed over the cycle."""
    plt = _plt()
    fig = plt.figure(figsize=(13, 7))
    ax = fig.add_subplot(1, 2, 1)
    _draw_linkage(ax, linkage, solution.joints, 0, gait.foot, gait.support)
    ax.set_title(f"{linkage.name}: foot path, linkage at crank angle 0\n"
                 f"stride {gait.stride:.1f} mm, lift {gait.lift:.1f} mm, duty {gait.duty_factor:.2f}")
    ax.legend(fontsize=8, loc="best")
    deg = np.degrees(gait.theta)
    ax2 = fig.add_subplot(2, 2, 2)
    ax2.plot(deg, gait.speed / 1000, label="|v| foot")
    ax2.plot(deg, gait.velocity[:, 0] / 1000, "--", label="vx foot")
    ax2.plot(deg, gait.velocity[:, 1] / 1000, ":", label="vy foot")
    ax2.set_xlabel("crank angle (deg)")
    ax2.set_ylabel("foot speed rel. body (m/s)")
    ax2.set_title(f"foot velocity at {rpm:g} rpm")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8)
    ax3 = fig.add_subplot(2, 2, 4)
    ax3.plot(deg, gait.body_speed / 1000, color="C3")
    ax3.set_xlim(0, 360)
    ax3.set_xlabel("crank angle (deg)")
    ax3.set_ylabel("body speed (m/s)")
    ax3.set_title("body speed while the foot stands (= -vx of the foot)")
    ax3.grid(True, alpha=0.3)
    fig.tight_layout()
    return _png(fig)


def linkage_gif(linkage, solution, gait, frames: int = 48) -> bytes:
    """Animation of one crank turn (GIF bytes, matplotlib + pillow)."""
    from wheelstep_cli.render.gif import animation_gif

    plt = _plt()

    fig, ax = plt.subplots(figsize=(4.5, 5.0), dpi=80)
    n = gait.theta.size
    idx = np.unique(np.linspace(0, n, frames, endpoint=False).astype(int))
    lines, foot = _draw_linkage(ax, linkage, solution.joints, 0, gait.foot, gait.support)
    pts = np.concatenate([solution.joints[name] for name in solution.joints])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.05 * float(np.max(hi - lo))
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    # below the axes: inside them the legend hides joints the linkage sweeps through
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3, frameon=False)
    ax.set_title(f"{linkage.name} leg, one crank turn")
    fig.tight_layout()

    def frame(k):
        for line, (a, b) in zip(lines, linkage.links):
            seg = np.array([solution.joints[a][k], solution.joints[b][k]])
            line.set_data(seg[:, 0], seg[:, 1])
        foot.set_data([solution.joints[linkage.foot][k, 0]], [solution.joints[linkage.foot][k, 1]])
        return [*lines, foot]

    return animation_gif(fig, frame, idx, fps=20)


def trajectory_png(path, points: np.ndarray, pieces: np.ndarray, title: str) -> bytes:
    """The composed foot path, its pieces, centres and tangent points (equal aspect)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(9, 7))
    names = ("support AD", f"arc r2 = {path.r2:g} (D-C)", f"arc r3 = {path.r3:.2f} (C-B)",
             f"arc r1 = {path.r1:g} (B-A)")
    for i, name in enumerate(names):
        sel = pieces == i
        ax.plot(points[sel, 0], points[sel, 1], ".-", ms=1.5, lw=1.8, color=f"C{i}", label=name)
    for label in ("A", "D", "B", "C"):
        p = getattr(path, label)
        ax.plot(*p, "ko", ms=5)
        ax.annotate(label, p, textcoords="offset points", xytext=(5, -12 if label in "AD" else 6))
    for label in ("O1", "O2", "O3"):
        p = getattr(path, label)
        ax.plot(*p, "+", color="0.4", ms=9)
        ax.annotate(label, p, textcoords="offset points", xytext=(5, 5), color="0.4")
    for o, t in ((path.O3, path.B), (path.O3, path.C)):
        ax.plot([o[0], t[0]], [o[1], t[1]], ":", color="0.6", lw=0.8)
    top_y = path.y0 + path.h_max
    ax.axhline(path.y0, color="0.5", lw=0.8, ls="--")
    ax.axhline(top_y, color="C3", lw=0.8, ls="--", label=f"h_max = {path.h_max:.2f} mm")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    return _png(fig)


def _speed_axes(ax, kin, law: str = "the crank law") -> None:
    """Hub speed (m/s) over the hub angle (deg), without and with the non-circular gears
    (following ``law``, said in the legend)."""
    deg = np.degrees(kin.phi)
    ax.plot(deg, kin.speed_plain / 1000, label=f"without non-circular gears (ripple {100 * kin.ripple_plain:.1f} %)")
    ax.plot(deg, kin.speed_geared / 1000,
            label=f"with non-circular gears on {law} (ripple {100 * kin.ripple_geared:.1f} %)")
    ax.set_xlabel("hub angle phi, deg (one shoe in contact)")
    ax.set_ylabel("hub speed, m/s")
    ax.set_xlim(deg[0], deg[-1])
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower center")
    ax.set_title(f"constant motor speed {kin.motor_speed * 60 / (2 * np.pi):g} rpm")


def _sole_axes(ax, design) -> None:
    """The sole in the shoe frame (mm), with the strut and its pivot."""
    from wheelstep_cli.mechanism.sole import contact_angles, sole_profile

    sole = sole_profile(design, contact_angles(201))
    ax.plot(sole[:, 0], sole[:, 1], lw=2, label="sole")
    ax.plot([0, 0], [0, design.c], "k--", lw=1, label="strut")
    ax.plot([0], [0], "ko", label="strut pivot")
    ax.set_aspect("equal")
    ax.invert_yaxis()  # Y of the shoe frame points to the ground
    ax.set_xlabel("X, mm")
    ax.set_ylabel("Y, mm (shoe frame, along the strut)")
    ax.set_title(f"shoe sole, R_min = {design.r_min:g} mm")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="center right", fontsize="small")


def kinematics_png(design, kin, law: str = "the crank law") -> bytes:
    """PNG: hub speed without/with the gears (following ``law``) over one shoe cycle (a
    ``HubKinematics``), and the sole of ``design`` (a ``CrankMechanism``) in the shoe frame."""
    plt = _plt()
    fig, (ax_v, ax_s) = plt.subplots(1, 2, figsize=(11, 4.5), gridspec_kw={"width_ratios": [3, 2]})
    _speed_axes(ax_v, kin, law)
    _sole_axes(ax_s, design)
    fig.tight_layout()
    return _png(fig)


def stair_study_png(study) -> bytes:
    """:func:`stairs_png` of a ``StairStudy``: its kinematics and three cycles of hub path up
    and down, titled with the design and the stair."""
    from wheelstep_cli.mechanism import stairs as st

    d, req = study.design, study.request
    what = "check of" if req.checking else "sized"
    title = (f"{what} a = {d.a:.1f}, b = {d.b:.1f}, Y1 = {d.y1:.1f}, Y2 = {d.y2:.1f} mm; "
             f"stair {req.run:g} x {req.rise:g} mm, landing {req.landing_angle_deg:g} deg")
    beta = study.descent_landing
    return stairs_png(study.climb, study.descent,
                      st.hub_path(d, study.landing, study.advance, study.rise, 3),
                      st.hub_path(d, beta, *st.cycle_motion(d, beta), 3), title,
                      (float(study.advance), float(study.rise)))
