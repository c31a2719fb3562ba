"""``wheelstep trajectory``: foot path from a support segment and three tangent arcs (SPEC §8)."""

from __future__ import annotations

from enum import Enum
from typing import Annotated, Optional

from wheelstep_cli.cli.options import (DryRun, Force, Json, Quiet, Verbose, csv_option, opt, output_file,
                                       plot_option, require_a_file, require_with)
from wheelstep_cli.cli.output import Output


class Root(str, Enum):
    lower = "lower"
    upper = "upper"


Csv = csv_option("the sampled path (x, y, piece)")
Plot = plot_option("a plot of the path")
Dxf = output_file("--dxf", "Write the path as DXF (line and arcs).", ".dxf")


def trajectory(
    support_length: Annotated[float, opt("--support-length", "-H",
                                         help="Support segment AD length H, mm.")] = 300.0,
    r1: Annotated[float, opt("--r1", help="Arc tangent to AD at A, mm.")] = 30.0,
    r2: Annotated[Optional[float], opt("--r2", help="Arc tangent to AD at D, mm.",
                                       shown="= r1")] = None,
    r3: Annotated[Optional[float], opt("--r3", help="Top arc radius, mm (or give --h-max).")] = None,
    h_max: Annotated[Optional[float], opt("--h-max", help="Required clearance: top of the path "
                                                          "above AD, mm.",
                                          shown="100 if no --r3")] = None,
    o3_root: Annotated[Optional[Root], opt("--o3-root", help="With --r3: top-arc centre on the "
                                                             "support side of O1O2 (SPEC) or the "
                                                             "other.", shown="lower")] = None,
    x0: Annotated[float, opt("--x0", help="x of A, mm.")] = 0.0,
    y0: Annotated[float, opt("--y0", help="Support line height y0, mm.")] = 0.0,
    spacing: Annotated[float, opt("--spacing", help="Sample spacing along the path, mm.")] = 1.0,
    csv: Csv = None,
    dxf: Dxf = None,
    dxf_polyline: Annotated[bool, opt("--dxf-polyline", help="DXF as one closed polyline with "
                                                             "arc bulges instead.")] = False,
    plot: Plot = None,
    force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Compose a foot path: support segment AD and arcs r1, r2, r3 (or clearance h_max), SPEC §8."""
    from wheelstep_cli.mechanism.trajectory_report import trajectory_report, trajectory_study
    from wheelstep_cli.parts.mechanism_files import trajectory_files

    show = Output(json, quiet, verbose)
    require_a_file(dry_run, force, csv=csv, dxf=dxf, plot=plot)
    require_with("o3_root", o3_root.value if o3_root is not None else None, r3, "--r3")
    require_with("dxf_polyline", "on" if dxf_polyline else None, dxf, "--dxf")
    study = trajectory_study(support_length, r1, r2, r3, h_max, x0, y0,
                             (o3_root or Root.lower).value, spacing)
    show.parameters({"r1": study.path.r1, "r2": study.path.r2, "r3": study.path.r3,
                     "h_max": study.path.h_max, "spacing": spacing})
    files = trajectory_files(study, csv, dxf, dxf_polyline, plot)
    named = show.write_named("trajectory", files, dry_run, force, csv=csv, dxf=dxf, plot=plot)
    show.report(trajectory_report(study), lambda: _lines(study))
    show.files(named, dry_run)


def _lines(study) -> list[str]:
    """The case, the named points and each piece of the path."""
    import numpy as np

    from wheelstep_cli.mechanism.trajectory_report import PIECE_NAMES, POINT_NAMES

    path = study.path
    lines = [f"{study.case} case: support AD = {path.support_length:g} mm at y = {path.y0:g}, "
             f"r1 = {path.r1:g}, r2 = {path.r2:g}, r3 = {path.r3:.3f} mm, clearance h_max = "
             f"{path.h_max:.3f} mm",
             f"{'point':>6} {'x (mm)':>10} {'y (mm)':>10}"]
    lines += [f"{k:>6} {getattr(path, k)[0]:10.3f} {getattr(path, k)[1]:10.3f}" for k in POINT_NAMES]
    lines.append("pieces (counter-clockwise):")
    for n, p in zip(PIECE_NAMES, path.pieces):
        if hasattr(p, "radius"):
            lines.append(f"  {n:7} centre ({p.center[0]:.3f}, {p.center[1]:.3f})  from "
                         f"{np.degrees(p.start):8.3f} deg sweep {np.degrees(p.sweep):8.3f} deg  "
                         f"length {p.length:8.3f} mm")
        else:
            lines.append(f"  {n:7} straight  length {p.length:8.3f} mm")
    lines.append(f"closed path length {path.length:.3f} mm, {study.points.shape[0]} samples")
    return lines


def register(app) -> None:
    app.command("trajectory")(trajectory)
