"""``wheelstep mesh-check``: measure how two written gears mesh (SPEC §10)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, List, Optional

import typer

from wheelstep_cli.cli.options import (A, B, Blend, C, DryRun, Force, Json, LawCsv, RMin,
                                       Profile, Quiet, Tolerance, Turns, Verbose, opt, plot_option,
                                       require_a_file)
from wheelstep_cli.cli.commands.meshcheck_shared import (band_printer_of, design_spec, no_design_options,
                                                    pair_lines, warn_band_jams)
from wheelstep_cli.cli.output import Output

Plot = plot_option("the transfer function, the position error of both flanks and hub speed")
BandPrinter = Annotated[Optional[str], opt(
    "--printer", help="Printer profile (a name in profiles/ or a YAML path) whose dimensional "
                      "band --tolerance checks.",
    shown="with plates or --gcode, the printer the plates were written for; else the default printer")]
Gcode = Annotated[Optional[List[Path]], opt(
    "--gcode", help="Check the pair as PrusaSlicer prints it: G-code of the pair (one plate, or "
                    "repeat --gcode for the files of both plates). The external perimeter of the "
                    "layer half-way up the teeth, offset by half its width, is each printed outline; the "
                    "design (law, installed distance) comes from the plate(s) it was sliced from: "
                    "PINION [WHEEL] name them, else FILE.3mf beside each FILE.gcode; or from "
                    "the two meshes named (PINION.stl WHEEL.stl) and the design options. A print's "
                    "teeth are each its own: it is checked over the law's whole cycle (one wheel "
                    "turn), not one period. With --tolerance, also the band's prediction of the least backlash.",
    callback=None, metavar="<FILE.gcode>")]


def mesh_check(
    pinion: Optional[str] = typer.Argument(None, help="Pinion mesh: FILE.stl, FILE.3mf or FILE.3mf:NAME "
                                                      "(a wheelstep plate's, with no design option: its "
                                                      "stored design); alone, a plate (3MF) whose gear pairs "
                                                      "are found by their metadata; with --gcode, the plate "
                                                      "it was sliced from."),
    wheel: Optional[str] = typer.Argument(None, help="Wheel mesh: FILE.stl, FILE.3mf or "
                                                     "FILE.3mf:NAME; or a second plate."),
    distance: Annotated[Optional[float], opt("--distance", "-d", help="Installed centre distance, mm.",
                                             shown="the design's, 144")] = None,
    a: A = None, b: B = None, c: C = None, r_min: RMin = None, turns: Turns = None,
    center_distance: Annotated[Optional[float], opt(
        "--center-distance", help="Centre distance the pitch curves roll at, mm: here the distance "
                                  "checked at when no --distance (or profile install_distance) is "
                                  "given.", shown="the design's, 144")] = None,
    law_csv: LawCsv = None, blend: Blend = None, profile: Profile = None,
    pair: Annotated[Optional[str], opt("--pair", help="On plates: the pair to check (its "
                                                      "wheelstep:pair id).", shown="every pair")] = None,
    samples: Annotated[Optional[int], opt("--samples", help="Poses over one period of the law (more than 6 "
                                          "per tooth pitch); with --gcode as many in each period of the whole "
                                          "cycle a print is checked over (one wheel turn).",
                                          shown="16 in the shortest tooth pitch, at least 1536")] = None,
    window: Annotated[Optional[float], opt("--window", help="Half-height of the mesh window round the line of "
                                           "centres, mm; larger than the default only (a narrower one misses "
                                           "contacts).", shown="0.25 x the smaller outer radius")] = None,
    plot: Plot = None, tolerance: Tolerance = False, printer: BandPrinter = None,
    gcode: Gcode = None, force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Section two gear meshes half-way up their teeth and check them over one period of the law:
    interference, backlash, and per flank F'i, f'i (um along the wheel pitch curve) and
    the hub speed ripple of 3 tooth harmonics (SPEC §10). The law is the crank law of the
    design, or any law given as --law-csv, blended by --blend as the teeth were cut. Given plates (3MF written by wheelstep),
    the pinion and wheel of each pair are found by their metadata and checked with the law and
    installed distance stored there. With --gcode, the pair as PrusaSlicer's G-code prints it
    (SPEC §11), over the law's whole cycle (one wheel turn): a print does not repeat every
    period. Exit 1 if they interfere or lose contact."""
    show = Output(json, quiet, verbose)
    require_a_file(dry_run, force, plot=plot)
    design = {"distance": distance, "a": a, "b": b, "c": c, "r_min": r_min, "turns": turns,
              "center_distance": center_distance, "law_csv": law_csv, "blend": blend, "profile": profile}
    band = (tolerance, printer)
    if gcode:
        from wheelstep_cli.cli.commands.meshcheck_gcode import check_gcode

        failed = check_gcode(show, gcode, [a for a in (pinion, wheel) if a], pair, design,
                             (samples, window, plot), band, (dry_run, quiet, force))
    elif _plates_given(pinion, wheel):
        failed = _check_plates(show, [pinion] + ([wheel] if wheel else []), pair, design, samples,
                               window, plot, dry_run, quiet, force, band)
    elif (named := _named_plate_pair(pinion, wheel, pair, design)) is not None:
        failed = _check_plates(show, [pinion, wheel], pair, design, samples, window, plot, dry_run, quiet,
                               force, band, named)
    else:
        failed = _check_meshes(show, pinion, wheel, pair, design, samples, window, plot, dry_run, quiet,
                               force, band)
    if failed:
        raise typer.Exit(1)


def _plates_given(pinion: str | None, wheel: str | None) -> bool:
    """Whether the meshes named are plates (3MF) whose pairs their metadata finds; a missing
    mesh refused as Click refuses a missing argument (the user gave none to name), a file
    named alone that does not exist as when two are named."""
    from wheelstep_cli.cli import click_errors
    from wheelstep_cli.errors import DesignError, file_problem
    from wheelstep_cli.formats.mesh_read import split_mesh_spec
    from wheelstep_cli.parts.plate_pairs import is_plate_input

    if pinion is None:
        raise click_errors.UsageError("Missing argument 'PINION': give the PINION and WHEEL meshes, a "
                                      "plate, or --gcode FILE")
    if wheel is None and not split_mesh_spec(pinion)[0].is_file():
        raise DesignError("pinion", pinion, file_problem(split_mesh_spec(pinion)[0]))
    for param, given in (("pinion", pinion), ("wheel", wheel)):
        if given is None:
            continue
        if str(given).lower().endswith((".gcode", ".gco", ".bgcode")):
            raise DesignError(param, given, "is G-code, not a mesh: read it back with --gcode FILE.gcode")
        # a report or any other file is no mesh, said so before it is taken for half a pair
        path = split_mesh_spec(given)[0]
        if path.is_file() and path.suffix.lower() not in (".stl", ".3mf"):
            raise DesignError(param, given, "must be an .stl or .3mf file")
    plates = is_plate_input(pinion, wheel)
    if wheel is None and not plates:
        raise click_errors.UsageError(f"Missing argument 'WHEEL': {pinion} is one gear; give the wheel "
                                      "mesh after it (PINION WHEEL), or a plate (3MF) holding the pair")
    return plates


def _named_plate_pair(pinion: str, wheel: str, pair, design: dict):
    """Two objects of wheelstep plates named as FILE.3mf:NAME, the pinion and the wheel by
    their metadata, with no design option given: the pair with the design they carry
    (parts.plate_pairs.PlatePair); else None (the design from the options, which override it)."""
    from wheelstep_cli.parts.plate_pairs import named_plate_pair

    if pair is not None or any(value is not None for value in design.values()):
        return None
    return named_plate_pair(pinion, wheel)


def _check_meshes(show: Output, pinion: str, wheel: str, pair, design: dict, samples: int | None, window,
                  plot, dry_run: bool, quiet: bool, force: bool,
                  band: tuple = (False, None)) -> bool:
    """Two meshes named on the command line, the design from the options; with
    ``band`` = (--tolerance, --printer) also over the printer's band (SPEC §11)."""
    from wheelstep_cli.cli.commands.meshcheck_shared import require_two_meshes
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.gear_laws import installed_distance
    from wheelstep_cli.parts.mesh_check_files import (WrittenPairCheck, read_written_pair,
                                                      run_written_pair_check, written_pair_files)

    if pair is not None:
        raise DesignError("pair", pair, "picks a pair on plates; give one or two 3MF plates")
    require_two_meshes(pinion, wheel)
    spec = design_spec(design)
    check = WrittenPairCheck(pinion, wheel, spec, samples, window, plot)
    show.parameters(vars(spec), design["profile"])
    chosen = band_printer_of(*band)
    outlines = read_written_pair(check)
    report, summary = with_progress(not quiet, "meshing check", run_written_pair_check, check,
                                    outlines)
    if chosen is not None:
        from wheelstep_cli.parts.tolerance_cli import outline_band

        summary["tolerance"] = outline_band(outlines, check, report, chosen)
    files = written_pair_files(check, report)
    named = show.write_named("mesh-check", files, dry_run, force, plot=plot)
    show.report(summary, lambda: pair_lines(summary, installed_distance(spec)))
    if not summary["in_phase"]:
        # two meshes carry no law: a pair made with other options is checked against the wrong one
        # and teeth that interfere may only be mounted closer than the pair was made for
        closer = (f"; teeth that interfere may also be mounted closer than the pair was made for "
                  f"(--distance {installed_distance(spec):g} mm)" if summary["interference"] else "")
        show.warning("WARNING: out of phase, checked against the law of the options given (mechanism, "
                     "--turns, --blend, --law-csv): if the pair was made with others, give them as it was "
                     f"made, or its design's --profile{closer}")
    elif summary.get("bounds", {}).get("within") is False:
        # in phase and far outside: --blend 5 left out of a pair cut with it reads F'i 144 um
        # a pair mounted off its distance no longer follows its law either: 0.875 mm farther
        # reads F'i 452 um
        show.warning("WARNING: outside the bounds: one cause is a law or a distance other than the pair was "
                     "made for (checked against the options given: mechanism, --turns, --blend, --law-csv, "
                     f"at --distance {installed_distance(spec):g} mm; give them as it was made, or its "
                     "design's --profile); a fit's inset, teeth written with --allow-interference and a "
                     "print's own deviations are others")
    warn_band_jams(show, summary.get("tolerance"), band[1])
    show.files(named, dry_run)
    return report.interferes or report.contact_lost


def _check_plates(show: Output, plates: list[str], pair, design: dict, samples: int | None, window, plot,
                  dry_run: bool, quiet: bool, force: bool, band: tuple = (False, None), named=None) -> bool:
    """Every gear pair of the plates (or the one --pair names; or ``named``, the one the two
    objects named are), designs from their metadata; with ``band`` = (--tolerance, --printer)
    also over a printer's band: the one named, else the one each pair's plates were written
    for (SPEC §11)."""
    from wheelstep_cli.cli.commands.meshcheck_gcode import plate_printer
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.errors import require
    from wheelstep_cli.parts.mesh_check_files import (WrittenPairCheck, plate_pair_outlines, run_plate_pair_check,
                                                      written_pair_files)
    from wheelstep_cli.parts.plate_pairs import find_plate_pairs
    from wheelstep_cli.parts.tolerance_cli import outline_band, plate_bore_fit

    no_design_options(design)
    chosen = band_printer_of(*band)
    pairs = [named] if named is not None else find_plate_pairs(plates, pair)
    require(plot is None or len(pairs) == 1, "plot", str(plot),
            "draws one pair: add --pair ID, one of " + ", ".join(f"'{p.pair}'" for p in pairs))
    summaries, failed, files, warned = [], False, {}, []
    for found in pairs:
        report, summary = with_progress(not quiet, f"meshing check {found.pair}", run_plate_pair_check,
                                        found, samples, window)
        check = WrittenPairCheck(*summary_files(summary), found.spec, samples, window, plot)
        printer = plate_printer(found, chosen) if band[0] and band[1] is None else chosen
        if printer is not None:     # the outlines as written, any fit's inset in them
            summary["tolerance"] = outline_band(plate_pair_outlines(found), check, report, printer)
            summary["tolerance"]["bore"] = plate_bore_fit(found, printer)
            # the fit the warning suggests is to the band checked, its printer as it was loaded
            warned.append((summary["tolerance"], band[1] or printer.given or printer.name))
        summaries.append(summary)
        failed = failed or report.interferes or report.contact_lost
        files.update(written_pair_files(check, report))
    named = show.write_named("mesh-check", files, dry_run, force, plot=plot)
    show.report({"pairs": summaries}, lambda: [line for s in summaries
                                               for line in pair_lines(s, s["distance_mm"])])
    for record, name in warned:
        warn_band_jams(show, record, name)
    show.files(named, dry_run)
    return failed


def summary_files(summary: dict) -> tuple[str, str]:
    return summary["pinion"], summary["wheel"]


def register(app: typer.Typer) -> None:
    app.command("mesh-check")(mesh_check)
