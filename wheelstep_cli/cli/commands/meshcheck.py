"""``wheelstep mesh-check``: measure how two written gears mesh (SPEC §10)."""

from __future__ import annotations

from typing import Annotated, Optional

import typer

from wheelstep_cli.cli.options import (A, B, C, CenterDistance, DryRun, Json, LawCsv, Profile, Quiet,
                                       Turns, Verbose, opt, plot_option)
from wheelstep_cli.cli.output import Output

Plot = plot_option("the transfer function, the position error of both flanks and hub speed")
Blend = Annotated[Optional[float], opt(
    "--blend", help="Half-width (carrier deg) of the ratio blend the teeth were cut for.",
    shown="0")]


def mesh_check(
    pinion: str = typer.Argument(..., help="Pinion mesh: FILE.stl, FILE.3mf or FILE.3mf:NAME."),
    wheel: str = typer.Argument(..., help="Wheel mesh: FILE.stl, FILE.3mf or FILE.3mf:NAME."),
    distance: Annotated[Optional[float], opt("--distance", "-d", help="Installed centre distance, mm.",
                                             shown="the design's, 144")] = None,
    a: A = None, b: B = None, c: C = None, turns: Turns = None,
    center_distance: CenterDistance = None, law_csv: LawCsv = None, blend: Blend = None,
    profile: Profile = None,
    samples: Annotated[int, opt("--samples", help="Poses over one period of the pinion.")] = 1536,
    window: Annotated[Optional[float], opt("--window", help="Half-height of the mesh window round "
                                                            "the line of centres, mm.",
                                           shown="0.25 x the smaller outer radius")] = None,
    plot: Plot = None,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Section two gear meshes at mid-thickness and check them over one period of the law:
    interference, backlash, and per flank F'i, f'i (um along the wheel pitch curve) and
    the hub speed ripple of 3 tooth harmonics (SPEC §10). The law is the crank law of the
    design, or any law given as --law-csv, blended by --blend as the teeth were cut. Exit 1
    if they interfere or lose contact."""
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.mesh_check_files import (WrittenPairCheck, read_written_pair,
                                                      run_written_pair_check, written_pair_files)

    show = Output(json, quiet, verbose)
    spec = gear_pair_spec(profile, a=a, b=b, c=c, turns=turns, center_distance=center_distance,
                          install_distance=distance, law_csv=str(law_csv) if law_csv else None,
                          blend=blend)
    check = WrittenPairCheck(pinion, wheel, spec, samples, window, plot)
    show.parameters(vars(spec))
    outlines = read_written_pair(check)
    report, summary = with_progress(not quiet, "meshing check", run_written_pair_check, check,
                                    outlines)
    files = written_pair_files(check, report)
    show.write(files, dry_run)
    show.report(summary, lambda: _lines(summary, spec.install_distance, samples))
    show.files(files, dry_run)
    if report.interferes or report.contact_lost:
        raise typer.Exit(1)


def _lines(summary: dict, distance: float, samples: int) -> list[str]:
    from wheelstep_cli.parts.mesh_check import meshing_lines

    return [f"meshing check: {summary['pinion']} + {summary['wheel']} at {distance:g} mm, "
            f"{samples} poses over {summary['period_deg']:g} deg of pinion", *meshing_lines(summary)]


def register(app: typer.Typer) -> None:
    app.command("mesh-check")(mesh_check)
