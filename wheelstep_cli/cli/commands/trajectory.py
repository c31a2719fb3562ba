"""``wheelstep trajectory``: foot path from a support segment and three tangent arcs (SPEC §8)."""

from __future__ import annotations

from enum import Enum
from pathlib import Path
from typing import Optional

import typer

from wheelstep_cli.errors import require

Opt = typer.Option


class Root(str, Enum):
    lower = "lower"
    upper = "upper"


def _point(p):
    return [float(p[0]), float(p[1])]


def trajectory(
    support_length: float = Opt(300.0, "--support-length", "-H", help="Support segment AD length H, mm."),
    r1: float = Opt(30.0, "--r1", help="Arc tangent to AD at A, mm."),
    r2: Optional[float] = Opt(None, "--r2", help="Arc tangent to AD at D, mm [= r1]."),
    r3: Optional[float] = Opt(None, "--r3", help="Top arc radius, mm (or give --h-max)."),
    h_max: Optional[float] = Opt(None, "--h-max", help="Required clearance: top of the path above AD, mm [100 if no --r3]."),
    o3_root: Root = Opt(Root.lower, "--o3-root", help="With --r3: top-arc centre on the support side of O1O2 (SPEC) or the other."),
    x0: float = Opt(0.0, "--x0", help="x of A, mm."),
    y0: float = Opt(0.0, "--y0", help="Support line height y0, mm."),
    spacing: float = Opt(1.0, "--spacing", help="Sample spacing along the path, mm."),
    csv: Optional[Path] = Opt(None, "--csv", help="Write the sampled path (x, y, piece) as CSV."),
    dxf: Optional[Path] = Opt(None, "--dxf", help="Write the path as DXF (line and arcs)."),
    dxf_polyline: bool = Opt(False, "--dxf-polyline", help="DXF as one closed polyline with arc bulges instead."),
    plot: Optional[Path] = Opt(None, "--plot", help="Write a plot of the path (PNG)."),
    json: bool = Opt(False, "--json", help="Print JSON instead of a table."),
) -> None:
    """Compose a foot path: support segment AD and arcs r1, r2, r3 (or clearance h_max), SPEC §8."""
    import numpy as np

    from wheelstep_cli.formats.jsonio import csv_bytes, json_text
    from wheelstep_cli.mechanism import trajectory as tr

    r2 = r1 if r2 is None else r2
    if r3 is None and h_max is None:
        h_max = 100.0
    require(r3 is None or h_max is None, "h-max", h_max, "give either --r3 or --h-max, not both")
    require(spacing > 0, "spacing", spacing, "must be > 0 mm")
    path = tr.foot_path(support_length, r1, r2, r3=r3, h_max=h_max, x0=x0, y0=y0, root=o3_root.value)
    require(path.length / spacing <= 1e6, "spacing", spacing, "gives over a million points")
    points, pieces = tr.sample_path(path, spacing)
    case = "symmetric" if r1 == r2 else "general"
    names = ("AD", "arc_r2", "arc_r3", "arc_r1")
    report = {
        "case": case, "given": "h_max" if r3 is None else "r3",
        "support_length_mm": path.support_length, "y0_mm": path.y0,
        "r1_mm": path.r1, "r2_mm": path.r2, "r3_mm": path.r3, "h_max_mm": path.h_max,
        "points_mm": {k: _point(getattr(path, k)) for k in ("A", "D", "C", "B", "O1", "O2", "O3")},
        "pieces": [{"name": n, "length_mm": p.length,
                    **({"center_mm": _point(p.center), "radius_mm": p.radius,
                        "start_deg": float(np.degrees(p.start)), "sweep_deg": float(np.degrees(p.sweep))}
                       if hasattr(p, "radius") else {"start_mm": _point(p.start), "end_mm": _point(p.end)})}
                   for n, p in zip(names, path.pieces)],
        "path_length_mm": path.length, "samples": int(points.shape[0]),
    }
    files = {}
    if csv is not None:
        files[csv] = csv_bytes(["x_mm", "y_mm", "piece"], np.column_stack([points, pieces]))
    if dxf is not None:
        from wheelstep_cli.formats.dxf import path_dxf_bytes

        files[dxf] = path_dxf_bytes(path.pieces, polyline=dxf_polyline)
    if plot is not None:
        from wheelstep_cli.render.mechanism_plots import trajectory_png

        title = (f"foot path: H = {path.support_length:g}, r1 = {path.r1:g}, r2 = {path.r2:g}, "
                 f"r3 = {path.r3:.2f}, h_max = {path.h_max:.2f} mm")
        files[plot] = trajectory_png(path, points, pieces, title)
    if files:
        from wheelstep_cli.formats.atomic import write_files_atomic

        write_files_atomic(files)
    if json:
        typer.echo(json_text(report), nl=False)
        return
    typer.echo(f"{case} case: support AD = {path.support_length:g} mm at y = {path.y0:g}, "
               f"r1 = {path.r1:g}, r2 = {path.r2:g}, r3 = {path.r3:.3f} mm, clearance h_max = {path.h_max:.3f} mm")
    typer.echo(f"{'point':>6} {'x (mm)':>10} {'y (mm)':>10}")
    for k in ("A", "D", "C", "B", "O1", "O2", "O3"):
        p = getattr(path, k)
        typer.echo(f"{k:>6} {p[0]:10.3f} {p[1]:10.3f}")
    typer.echo("pieces (counter-clockwise):")
    for n, p in zip(names, path.pieces):
        if hasattr(p, "radius"):
            typer.echo(f"  {n:7} centre ({p.center[0]:.3f}, {p.center[1]:.3f})  from {np.degrees(p.start):8.3f} deg "
                       f"sweep {np.degrees(p.sweep):8.3f} deg  length {p.length:8.3f} mm")
        else:
            typer.echo(f"  {n:7} straight  length {p.length:8.3f} mm")
    typer.echo(f"closed path length {path.length:.3f} mm, {points.shape[0]} samples")
    for f in files:
        typer.echo(f"wrote {f}")


def register(app: typer.Typer) -> None:
    app.command("trajectory")(trajectory)
