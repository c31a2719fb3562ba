"""``wheelstep mesh-check``: measure how two written gears mesh (SPEC §10)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from wheelstep_cli.cli.commands.gears import A, B, C, CENTER, JSON, PROFILE, TURNS, Opt


def mesh_check(
    pinion: str = typer.Argument(..., help="Pinion mesh: FILE.stl, FILE.3mf or FILE.3mf:NAME."),
    wheel: str = typer.Argument(..., help="Wheel mesh: FILE.stl, FILE.3mf or FILE.3mf:NAME."),
    distance: Optional[float] = Opt(None, "--distance", "-d",
                                    help="Installed centre distance, mm [the design's, 144]."),
    a: Optional[float] = A, b: Optional[float] = B, c: Optional[float] = C,
    turns: Optional[int] = TURNS, center_distance: Optional[float] = CENTER,
    profile: Optional[str] = PROFILE,
    samples: int = Opt(1536, "--samples", help="Poses over one period of the pinion."),
    window: Optional[float] = Opt(None, "--window",
                                  help="Half-height of the mesh window round the line of "
                                       "centres, mm [0.25 x the smaller outer radius]."),
    plot: Optional[Path] = Opt(None, "--plot", help="Write a PNG: transfer function, TE, hub speed."),
    json: bool = JSON,
) -> None:
    """Section two gear meshes at mid-thickness and check them over one period of the law:
    interference, backlash, transmission error and hub speed ripple. Exit 1 if they
    interfere or lose contact."""
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.errors import require
    from wheelstep_cli.formats.atomic import write_bytes_atomic
    from wheelstep_cli.formats.jsonio import json_text
    from wheelstep_cli.formats.mesh_read import read_outline
    from wheelstep_cli.parts.mesh_check import check_outlines, meshing_lines
    from wheelstep_cli.render.meshing_plot import meshing_plot_png

    spec = gear_pair_spec(profile, a=a, b=b, c=c, turns=turns, center_distance=center_distance,
                 install_distance=distance)
    law = spec.law()
    dist = spec.install_distance
    require(dist > 0, "distance", dist, "must be > 0 mm")
    require(samples >= 16, "samples", samples, "must be >= 16")
    require(window is None or window > 0, "window", window, "must be > 0 mm")
    if plot is not None:
        require(plot.suffix.lower() == ".png", "plot", str(plot), "must be a .png file")
    pinion_outline = read_outline(pinion, "pinion", default_name="pinion")
    wheel_outline = read_outline(wheel, "wheel", default_name="wheel")
    require(dist > 0, "distance", dist, "must be > 0 mm")
    report = _run_with_progress(check_outlines, pinion_outline, wheel_outline, law, dist,
                                samples, window)
    summary = {"pinion": str(pinion), "wheel": str(wheel),
               "law": {"a": law.mechanism.a, "b": law.mechanism.b, "c": law.mechanism.c,
                       "turns": law.turns, "u": law.u},
               **report.to_dict()}
    if plot is not None:
        write_bytes_atomic(plot, meshing_plot_png(
            report, f"{Path(pinion).name} + {Path(wheel).name} at {dist:g} mm"))
    if json:
        typer.echo(json_text(summary), nl=False)
    else:
        typer.echo(f"meshing check: {pinion} + {wheel} at {dist:g} mm, {samples} poses over "
                   f"{summary['period_deg']:g} deg of pinion")
        for line in meshing_lines(summary):
            typer.echo(line)
        if plot is not None:
            typer.echo(f"wrote {plot}")
    if report.interferes or report.contact_lost:
        raise typer.Exit(1)


def _run_with_progress(check, *args):
    """Run the check with a transient rich progress bar on stderr."""
    from rich.console import Console
    from rich.progress import Progress

    with Progress(console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("meshing check", total=None)
        return check(*args, progress=lambda done, total: bar.update(task, completed=done,
                                                                    total=total))


def register(app: typer.Typer) -> None:
    app.command("mesh-check")(mesh_check)
