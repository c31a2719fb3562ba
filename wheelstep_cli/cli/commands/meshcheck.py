"""``wheelstep mesh-check``: measure how two written gears mesh (SPEC §10)."""

from __future__ import annotations

from typing import Annotated, Optional

import typer

from wheelstep_cli.cli.options import (A, B, Blend, C, CenterDistance, DryRun, Force, Json, LawCsv,
                                       Profile, Quiet, Tolerance, Turns, Verbose, opt, plot_option)
from wheelstep_cli.cli.output import Output

Plot = plot_option("the transfer function, the position error of both flanks and hub speed")
BandPrinter = Annotated[Optional[str], opt(
    "--printer", help="Printer profile (a name in profiles/ or a YAML path) whose dimensional "
                      "band --tolerance checks.", shown="the default printer")]


def mesh_check(
    pinion: str = typer.Argument(..., help="Pinion mesh: FILE.stl, FILE.3mf or FILE.3mf:NAME; "
                                           "alone, a plate (3MF) whose gear pairs are found by "
                                           "their metadata."),
    wheel: Optional[str] = typer.Argument(None, help="Wheel mesh: FILE.stl, FILE.3mf or "
                                                     "FILE.3mf:NAME; or a second plate."),
    distance: Annotated[Optional[float], opt("--distance", "-d", help="Installed centre distance, mm.",
                                             shown="the design's, 144")] = None,
    a: A = None, b: B = None, c: C = None, turns: Turns = None,
    center_distance: CenterDistance = None, law_csv: LawCsv = None, blend: Blend = None,
    profile: Profile = None,
    pair: Annotated[Optional[str], opt("--pair", help="On plates: the pair to check (its "
                                                      "wheelstep:pair id).", shown="every pair")] = None,
    samples: Annotated[int, opt("--samples", help="Poses over one period of the pinion.")] = 1536,
    window: Annotated[Optional[float], opt("--window", help="Half-height of the mesh window round "
                                                            "the line of centres, mm.",
                                           shown="0.25 x the smaller outer radius")] = None,
    plot: Plot = None, tolerance: Tolerance = False, printer: BandPrinter = None,
    force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Section two gear meshes half-way up their teeth and check them over one period of the law:
    interference, backlash, and per flank F'i, f'i (um along the wheel pitch curve) and
    the hub speed ripple of 3 tooth harmonics (SPEC §10). The law is the crank law of the
    design, or any law given as --law-csv, blended by --blend as the teeth were cut. Given plates (3MF written by wheelstep),
    the pinion and wheel of each pair are found by their metadata and checked with the law and
    installed distance stored there. Exit 1 if they interfere or lose contact."""
    from wheelstep_cli.parts.plate_pairs import is_plate_input

    show = Output(json, quiet, verbose)
    design = {"distance": distance, "a": a, "b": b, "c": c, "turns": turns,
              "center_distance": center_distance, "law_csv": law_csv, "blend": blend, "profile": profile}
    band = (tolerance, printer)
    if is_plate_input(pinion, wheel):
        _no_band_on_plates(tolerance, printer)
        failed = _check_plates(show, [pinion] + ([wheel] if wheel else []), pair, design, samples,
                               window, plot, dry_run, quiet, force)
    else:
        failed = _check_meshes(show, pinion, wheel, pair, design, samples, window, plot, dry_run, quiet,
                               force, band)
    if failed:
        raise typer.Exit(1)


def _no_band_on_plates(tolerance: bool, printer) -> None:
    from wheelstep_cli.errors import DesignError

    if tolerance or printer is not None:
        raise DesignError("tolerance" if tolerance else "printer", printer or "on",
                          "checks two named meshes (PINION WHEEL), not plates")


def _check_meshes(show: Output, pinion: str, wheel: str, pair, design: dict, samples: int, window,
                  plot, dry_run: bool, quiet: bool, force: bool,
                  band: tuple = (False, None)) -> bool:
    """Two meshes named on the command line, the design from the options; with
    ``band`` = (--tolerance, --printer) also over the printer's band (SPEC §11)."""
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_check_files import (WrittenPairCheck, read_written_pair,
                                                      run_written_pair_check, written_pair_files)

    if pair is not None:
        raise DesignError("pair", pair, "picks a pair on plates; give one or two 3MF plates")
    if _same_mesh(pinion, wheel):
        raise DesignError("wheel", wheel, f"is the same mesh as the pinion ({pinion}): give the "
                                          "pinion and the wheel of one pair")
    law_csv = design["law_csv"]
    spec = gear_pair_spec(design["profile"], a=design["a"], b=design["b"], c=design["c"],
                          turns=design["turns"], center_distance=design["center_distance"],
                          install_distance=design["distance"], law_csv=str(law_csv) if law_csv else None,
                          blend=design["blend"])
    check = WrittenPairCheck(pinion, wheel, spec, samples, window, plot)
    show.parameters(vars(spec))
    chosen = _band_printer(*band)
    outlines = read_written_pair(check)
    report, summary = with_progress(not quiet, "meshing check", run_written_pair_check, check,
                                    outlines)
    if chosen is not None:
        from wheelstep_cli.parts.tolerance_cli import outline_band

        summary["tolerance"] = outline_band(outlines, check, report, chosen)
    files = written_pair_files(check, report)
    named = show.write_named("mesh-check", files, dry_run, force, plot=plot)
    show.report(summary, lambda: _lines(summary, spec.install_distance, samples))
    show.files(named, dry_run)
    return report.interferes or report.contact_lost


def _band_printer(tolerance: bool, printer):
    """The printer whose band --tolerance checks (None: no band check); --printer alone is
    refused (it only says whose band)."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.tolerance_cli import band_printer

    if not tolerance:
        if printer is not None:
            raise DesignError("printer", printer, "names the band --tolerance checks: add --tolerance")
        return None
    from wheelstep_cli.config.profiles import load_printer_profile

    return band_printer(load_printer_profile(printer) if printer else None)


def _check_plates(show: Output, plates: list[str], pair, design: dict, samples: int, window, plot,
                  dry_run: bool, quiet: bool, force: bool) -> bool:
    """Every gear pair of the plates (or the one --pair names), designs from their metadata."""
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.errors import DesignError, require
    from wheelstep_cli.parts.mesh_check_files import WrittenPairCheck, run_plate_pair_check, written_pair_files
    from wheelstep_cli.parts.plate_pairs import find_plate_pairs

    for name, value in design.items():
        if value is not None:
            raise DesignError(name, value, "comes from the plate's metadata; to give it, name the "
                                           "two meshes (PINION WHEEL) instead of plates")
    pairs = find_plate_pairs(plates, pair)
    require(plot is None or len(pairs) == 1, "plot", str(plot), "draws one pair: add --pair ID")
    summaries, failed, files = [], False, {}
    for found in pairs:
        report, summary = with_progress(not quiet, f"meshing check {found.pair}", run_plate_pair_check,
                                        found, samples, window)
        summaries.append(summary)
        failed = failed or report.interferes or report.contact_lost
        files.update(written_pair_files(WrittenPairCheck(*summary_files(summary), found.spec, samples,
                                                         window, plot), report))
    named = show.write_named("mesh-check", files, dry_run, force, plot=plot)
    show.report({"pairs": summaries}, lambda: [line for s in summaries
                                               for line in _lines(s, s["distance_mm"], samples)])
    show.files(named, dry_run)
    return failed


def _same_mesh(pinion: str, wheel: str | None) -> bool:
    """Whether the two mesh arguments name one mesh: the same file (or object of a 3MF), or
    two files of identical content. Checking a part against itself cannot give a meshing
    figure, and its sections overlap everywhere: refused before any work."""
    from pathlib import Path

    if wheel is None:
        return False
    (p_file, p_obj), (w_file, w_obj) = (_split(pinion), _split(wheel))
    if p_obj != w_obj:
        return False
    try:
        sizes = (Path(p_file).stat().st_size, Path(w_file).stat().st_size)
        return Path(p_file).resolve() == Path(w_file).resolve() or (
            sizes[0] == sizes[1] and Path(p_file).read_bytes() == Path(w_file).read_bytes())
    except OSError:
        return False        # a missing or unreadable file is refused where it is read


def _split(given: str) -> tuple[str, str]:
    """FILE.3mf:NAME -> (FILE.3mf, NAME); any other argument -> (it, "")."""
    head, sep, tail = given.rpartition(":")
    return (head, tail) if sep and head.lower().endswith(".3mf") else (given, "")


def summary_files(summary: dict) -> tuple[str, str]:
    return summary["pinion"], summary["wheel"]


def _lines(summary: dict, distance: float, samples: int) -> list[str]:
    from wheelstep_cli.parts.mesh_check import meshing_lines

    pair = f"pair {summary['pair']}: " if "pair" in summary else ""
    return [f"meshing check: {pair}{summary['pinion']} + {summary['wheel']} at {distance:g} mm, "
            f"{samples} poses over {summary['period_deg']:g} deg of pinion", *meshing_lines(summary),
            *_band_lines(summary)]


def _band_lines(summary: dict) -> list[str]:
    if "tolerance" not in summary:
        return []
    from wheelstep_cli.parts.tolerance_cli import tolerance_lines

    return tolerance_lines(summary["tolerance"])


def register(app: typer.Typer) -> None:
    app.command("mesh-check")(mesh_check)
