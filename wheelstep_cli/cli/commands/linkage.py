"""``wheelstep linkage``: foot path and gait of a walking linkage (SPEC §7)."""

from __future__ import annotations

from enum import Enum
from typing import Annotated, List, Optional

from wheelstep_cli.cli.options import (DryRun, Force, Json, Quiet, Verbose, csv_option, opt, output_file,
                                       plot_option, point, require_a_file, require_printed, require_with,
                                       signs)
from wheelstep_cli.cli.output import Output
from wheelstep_cli.errors import DesignError


class Preset(str, Enum):
    four_bar = "four-bar"
    six_bar = "six-bar"
    chebyshev = "chebyshev"
    jansen = "jansen"


Length = Optional[float]
Csv = csv_option("the foot path at every sample")
Plot = plot_option("the path and speed plot")
Gif = output_file("--gif", "Write an animation of one crank turn (GIF).", ".gif")


def linkage(
    preset: Annotated[Preset, opt("--preset", help="Which leg.")] = Preset.four_bar,
    rpm: Annotated[Length, opt("--rpm", help="Crank speed, rpm.",
                               shown="the preset's: 27 for four-bar (also with --l1..--o1 changed) and "
                                     "six-bar, 60 for chebyshev and jansen")] = None,
    samples: Annotated[int, opt("--samples", help="Crank angles per turn.")] = 720,
    scale: Annotated[float, opt("--scale", help="Multiply every length by this.")] = 1.0,
    branch: Annotated[List[str], opt("--branch", help="Assembly branch of a dyad joint, NAME=+1 "
                                                      "or NAME=-1 (repeatable).")] = [],
    ground_tol: Annotated[Length, opt("--ground-tol", help="Support phase: foot within this of "
                                                           "its lowest level, mm.",
                                      shown="2 % of the lift")] = None,
    l1: Annotated[Length, opt("--l1", help="four-bar: crank OK, mm.", shown="270")] = None,
    l2: Annotated[Length, opt("--l2", help="four-bar: rocker O1L, mm.", shown="638")] = None,
    l3: Annotated[Length, opt("--l3", help="four-bar: coupler KL, mm.", shown="650")] = None,
    l4: Annotated[Length, opt("--l4", help="four-bar: support arm LH, mm.", shown="654")] = None,
    beta: Annotated[Length, opt("--beta", help="four-bar: arm angle to the coupler, deg, in (-360, 360).",
                                shown="70.8")] = None,
    o1: Annotated[Optional[str], opt("--o1", help="four-bar: rocker pivot 'x,y', mm.",
                                     shown="567,615")] = None,
    step: Annotated[Optional[float], opt("--step", help="Crank-angle step of the printed table "
                                                        "(and of --json's), deg.",
                                        shown="15, or the multiple of 360/--samples nearest it, the larger on a tie")] = None,
    csv: Csv = None, plot: Plot = None,
    gif: Gif = None,
    gif_frames: Annotated[Optional[int], opt("--gif-frames", help="Frames of the GIF animation.",
                                             shown="48")] = None,
    force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Foot path, stride, lift, duty factor, foot and body speed of a walking linkage (SPEC §7)."""
    from wheelstep_cli.mechanism.linkage import study as ls
    from wheelstep_cli.parts.mechanism_files import linkage_files

    show = Output(json, quiet, verbose)
    require_a_file(dry_run, force, csv=csv, plot=plot, gif=gif)
    require_with("gif_frames", gif_frames, gif, "--gif")
    require_printed("step", step, quiet and not json, "table")
    gif_frames = 48 if gif_frames is None else gif_frames
    ls.check_sampling(samples, scale, gif_frames, ls.DEFAULT_STEP if step is None else step)
    if step is None:
        step = ls.default_step(samples)
    else:
        ls.require_step_on_samples(step, samples)
    four_bar = {"l1": l1, "l2": l2, "l3": l3, "l4": l4, "beta_deg": beta,
                "o1": None if o1 is None else point(o1, "o1")}
    request = ls.LinkageRequest(preset.value, rpm, samples, scale, signs(branch, "branch"),
                                ground_tol, four_bar, step)
    show.parameters(vars(request))
    study = _study(request, branch)
    files = linkage_files(study, csv, plot, gif, gif_frames)
    named = show.write_named("linkage", files, dry_run, force, csv=csv, plot=plot, gif=gif)
    report = ls.linkage_report(study)
    show.report(report, lambda: _lines(report))
    show.files(named, dry_run)


def _study(request, branch: list[str]):
    """The study of ``request``; a --branch joint it refuses echoed as the user typed its item."""
    from wheelstep_cli.mechanism.linkage import study as ls

    try:
        return ls.linkage_study(request)
    except DesignError as err:
        if err.param != "branch":
            raise
        typed = next((item for item in branch if item.partition("=")[0] == err.value), err.value)
        raise DesignError("branch", typed, err.limit) from None


def _lines(report: dict) -> list[str]:
    """The leg, its branches and residual, the gait figures and the sampled path."""
    foot, body = report["foot_speed_mm_s"], report["body_speed_mm_s"]
    lines = [report["description"],
             "assembly branches: " + ", ".join(f"{k} {v:+d}" for k, v in report["branches"].items())
             + f"   loop-closure residual {report['loop_residual_mm']:.1e} mm over "
               f"{report['samples']} crank angles",
             f"stride {report['stride_mm']:.1f} mm   lift {report['lift_mm']:.1f} mm   duty factor "
             f"{report['duty_factor']:.3f}   (support: foot within {report['ground_tol_mm']:.2f} mm "
             f"of its lowest level y = {report['ground_level_mm']:.1f} mm)",
             f"at {report['rpm']:g} rpm: foot speed {foot['min'] / 1000:.3f} .. {foot['max'] / 1000:.3f} "
             f"m/s (mean {foot['mean'] / 1000:.3f});  body speed in support "
             f"{body['min'] / 1000:.3f} .. {body['max'] / 1000:.3f} m/s (mean {body['mean'] / 1000:.3f})",
             f"{'crank':>7} {'x':>9} {'y':>9} {'vx':>9} {'vy':>9} {'|v|':>9}  phase   "
             f"(every {report['table_step_deg']:.10g} deg)",
             f"{'deg':>7} {'mm':>9} {'mm':>9} {'mm/s':>9} {'mm/s':>9} {'mm/s':>9}"]
    for r in report["path"]:
        lines.append(f"{r['crank_deg']:7.1f} {r['x_mm']:9.2f} {r['y_mm']:9.2f} {r['vx_mm_s']:9.1f} "
                     f"{r['vy_mm_s']:9.1f} {r['speed_mm_s']:9.1f}  "
                     f"{'support' if r['support'] else 'swing'}")
    return lines


def register(app) -> None:
    app.command("linkage")(linkage)
