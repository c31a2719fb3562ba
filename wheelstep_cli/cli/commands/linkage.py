"""``wheelstep linkage``: foot path and gait of a walking linkage (SPEC §7)."""

from __future__ import annotations

from enum import Enum
from pathlib import Path
from typing import List, Optional

import typer

from wheelstep_cli.errors import DesignError, require

Opt = typer.Option


class Preset(str, Enum):
    four_bar = "four-bar"
    six_bar = "six-bar"
    chebyshev = "chebyshev"
    jansen = "jansen"


def _four_bar(l1, l2, l3, l4, beta, o1):
    """The paper four-bar with any of its numbers replaced (mm, deg)."""
    import numpy as np

    from wheelstep_cli.mechanism import linkage as lk

    base = lk.four_bar_paper()
    steps = {s.name: s for s in base.steps}
    l1 = steps["K"].length if l1 is None else l1
    l3 = steps["L"].rp if l3 is None else l3
    l2 = steps["L"].rq if l2 is None else l2
    l4 = steps["H"].length if l4 is None else l4
    beta = float(np.degrees(steps["H"].angle)) if beta is None else beta
    ox, oy = (steps["O1"].x, steps["O1"].y) if o1 is None else _pair(o1)
    for name, value in (("l1", l1), ("l2", l2), ("l3", l3), ("l4", l4)):
        require(value > 0, name, value, "link length must be > 0 mm")
    return lk.Linkage(
        name="four-bar",
        description=f"four-bar leg (SPEC §7): crank OK {l1:g}, rocker O1L {l2:g}, coupler KL {l3:g}, "
                    f"bent arm LH {l4:g} mm at {beta:g} deg, O1 = ({ox:g}, {oy:g}) mm",
        steps=(lk.Fixed("O", 0.0, 0.0), lk.Fixed("O1", ox, oy), lk.Crank("K", "O", l1),
               lk.Dyad("L", "K", l3, "O1", l2, branch=steps["L"].branch),
               lk.Attached("H", "L", "K", l4, float(np.radians(beta)))),
        foot="H", ground=-1, rpm=base.rpm, links=base.links)


def _pair(text: str):
    try:
        x, y = (float(v) for v in text.split(","))
    except ValueError:
        raise DesignError("o1", text, "must be 'x,y' in mm") from None
    return x, y


def _flips(items: list[str]) -> dict:
    out = {}
    for item in items:
        name, _, sign = item.partition("=")
        require(sign in ("+1", "1", "-1"), "branch", item, "must be NAME=+1 or NAME=-1")
        out[name] = int(sign)
    return out


def linkage(
    preset: Preset = Opt(Preset.four_bar, "--preset", help="Which leg."),
    rpm: Optional[float] = Opt(None, "--rpm", help="Crank speed, rpm [preset's: 27 for the source legs, 60 else]."),
    samples: int = Opt(720, "--samples", help="Crank angles per turn."),
    scale: float = Opt(1.0, "--scale", help="Multiply every length by this."),
    branch: List[str] = Opt([], "--branch", help="Assembly branch of a dyad joint, NAME=+1 or NAME=-1 (repeatable)."),
    ground_tol: Optional[float] = Opt(None, "--ground-tol", help="Support phase: foot within this of its lowest level, mm [2 % of the lift]."),
    l1: Optional[float] = Opt(None, "--l1", help="four-bar: crank OK, mm [270]."),
    l2: Optional[float] = Opt(None, "--l2", help="four-bar: rocker O1L, mm [638]."),
    l3: Optional[float] = Opt(None, "--l3", help="four-bar: coupler KL, mm [650]."),
    l4: Optional[float] = Opt(None, "--l4", help="four-bar: support arm LH, mm [654]."),
    beta: Optional[float] = Opt(None, "--beta", help="four-bar: arm angle to the coupler, deg [70.8]."),
    o1: Optional[str] = Opt(None, "--o1", help="four-bar: rocker pivot 'x,y', mm [567,615]."),
    step: float = Opt(15.0, "--step", help="Crank-angle step of the printed table, deg."),
    csv: Optional[Path] = Opt(None, "--csv", help="Write the foot path at every sample (CSV)."),
    plot: Optional[Path] = Opt(None, "--plot", help="Write the path and speed plot (PNG)."),
    gif: Optional[Path] = Opt(None, "--gif", help="Write an animation of one crank turn (GIF)."),
    gif_frames: int = Opt(48, "--gif-frames", help="Frames of the GIF animation."),
    json: bool = Opt(False, "--json", help="Print JSON instead of tables."),
) -> None:
    """Foot path, stride, lift, duty factor, foot and body speed of a walking linkage (SPEC §7)."""
    import numpy as np

    from wheelstep_cli.formats.jsonio import csv_bytes, json_text
    from wheelstep_cli.mechanism import linkage as lk

    require(36 <= samples <= 100000, "samples", samples, "must be in [36, 100000]")
    require(scale > 0, "scale", scale, "must be > 0")
    require(2 <= gif_frames <= 720, "gif-frames", gif_frames, "must be in [2, 720]")
    require(0 < step <= 180, "step", step, "must be in (0, 180] deg")
    custom = any(v is not None for v in (l1, l2, l3, l4, beta, o1))
    if custom:
        require(preset == Preset.four_bar, "preset", preset.value, "--l1..--l4, --beta, --o1 apply to four-bar only")
        leg = _four_bar(l1, l2, l3, l4, beta, o1)
    else:
        leg = lk.PRESETS[preset.value]()
    flips = _flips(branch)
    dyads = {s.name for s in leg.steps if isinstance(s, lk.Dyad)}
    for name in flips:
        require(name in dyads, "branch", name, f"not a dyad joint of {leg.name} (those are {', '.join(sorted(dyads))})")
    leg = leg.with_branches(flips)
    if scale != 1.0:
        leg = leg.scaled(scale)
    rpm = leg.rpm if rpm is None else rpm
    require(rpm > 0, "rpm", rpm, "must be > 0")
    if ground_tol is not None:
        require(ground_tol >= 0, "ground-tol", ground_tol, "must be >= 0 mm")

    theta = lk.cycle_angles(samples)
    sol = lk.solve(leg, theta)
    probe = lk.gait(leg, sol, rpm)
    gait = lk.gait(leg, sol, rpm, 0.02 * probe.lift if ground_tol is None else ground_tol)
    body = gait.body_speed[gait.support]
    every = max(1, int(round(np.radians(step) / (theta[1] - theta[0]))))
    rows = [{"crank_deg": float(np.degrees(theta[k])), "x_mm": gait.foot[k, 0], "y_mm": gait.foot[k, 1],
             "vx_mm_s": gait.velocity[k, 0], "vy_mm_s": gait.velocity[k, 1], "speed_mm_s": gait.speed[k],
             "support": bool(gait.support[k])} for k in range(0, samples, every)]
    report = {
        "preset": leg.name, "description": leg.description, "rpm": rpm, "samples": samples,
        "branches": sol.branches, "loop_residual_mm": sol.residual,
        "stride_mm": gait.stride, "lift_mm": gait.lift, "duty_factor": gait.duty_factor,
        "ground_level_mm": gait.ground_level, "ground_tol_mm": gait.ground_tol,
        "foot_speed_mm_s": {"min": gait.speed.min(), "mean": gait.speed.mean(), "max": gait.speed.max()},
        "body_speed_mm_s": {"min": body.min(), "mean": body.mean(), "max": body.max()},
        "path": rows,
    }

    files = {}
    if csv is not None:
        table = np.column_stack([np.degrees(theta), gait.foot, gait.velocity, gait.speed, gait.support])
        files[csv] = csv_bytes(["crank_deg", "x_mm", "y_mm", "vx_mm_s", "vy_mm_s", "speed_mm_s", "support"], table)
    if plot is not None:
        from wheelstep_cli.render.mechanism_plots import linkage_png

        files[plot] = linkage_png(leg, sol, gait, rpm)
    if gif is not None:
        from wheelstep_cli.render.mechanism_plots import linkage_gif

        files[gif] = linkage_gif(leg, sol, gait, min(gif_frames, samples))
    if files:
        from wheelstep_cli.formats.atomic import write_files_atomic

        write_files_atomic(files)

    if json:
        typer.echo(json_text(report), nl=False)
        return
    typer.echo(leg.description)
    typer.echo("assembly branches: " + ", ".join(f"{k} {v:+d}" for k, v in sol.branches.items())
               + f"   loop-closure residual {sol.residual:.1e} mm over {samples} crank angles")
    typer.echo(f"stride {gait.stride:.1f} mm   lift {gait.lift:.1f} mm   duty factor {gait.duty_factor:.3f}   "
               f"(support: foot within {gait.ground_tol:.2f} mm of its lowest level y = {gait.ground_level:.1f} mm)")
    typer.echo(f"at {rpm:g} rpm: foot speed {gait.speed.min() / 1000:.3f} .. {gait.speed.max() / 1000:.3f} m/s "
               f"(mean {gait.speed.mean() / 1000:.3f});  body speed in support "
               f"{body.min() / 1000:.3f} .. {body.max() / 1000:.3f} m/s (mean {body.mean() / 1000:.3f})")
    typer.echo(f"{'crank':>7} {'x':>9} {'y':>9} {'vx':>9} {'vy':>9} {'|v|':>9}  phase")
    typer.echo(f"{'deg':>7} {'mm':>9} {'mm':>9} {'mm/s':>9} {'mm/s':>9} {'mm/s':>9}")
    for r in rows:
        typer.echo(f"{r['crank_deg']:7.1f} {r['x_mm']:9.2f} {r['y_mm']:9.2f} {r['vx_mm_s']:9.1f} "
                   f"{r['vy_mm_s']:9.1f} {r['speed_mm_s']:9.1f}  {'support' if r['support'] else 'swing'}")
    for path in files:
        typer.echo(f"wrote {path}")


def register(app: typer.Typer) -> None:
    app.command("linkage")(linkage)
