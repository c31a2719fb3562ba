"""``mesh-check --gcode``: the gear pair as PrusaSlicer's G-code prints it (SPEC §11)."""

from __future__ import annotations

from pathlib import Path

from wheelstep_cli.cli.output import Output


def check_gcode(show: Output, gcode: list[Path], plates: list[str], pair, design: dict,
                how: tuple, band: tuple, writing: tuple) -> bool:
    """Read the pair of ``plates`` (default: FILE.3mf beside each FILE.gcode) back from the
    G-code files and check it; ``how`` = (samples, window, plot), ``band`` = (--tolerance,
    --printer), ``writing`` = (dry run, quiet, force). True when the print would not mesh."""
    from wheelstep_cli.cli.commands.meshcheck_shared import band_printer_of, pair_lines, warn_band_jams
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.errors import require
    from wheelstep_cli.parts.gcode_check import band_prediction, gcode_lines, run_gcode_check, within_band
    from wheelstep_cli.parts.gcode_layers import require_gcode_files
    from wheelstep_cli.parts.mesh_check_files import WrittenPairCheck, require_sampling, written_pair_files
    from wheelstep_cli.parts.tolerance_cli import tolerance_lines

    samples, window, plot = how
    dry_run, quiet, force = writing
    require(len(gcode) <= 2, "gcode", " ".join(map(str, gcode)), "takes one file, or the two "
                                                                   "files of the pair's two plates")
    chosen = band_printer_of(*band)
    require_sampling(samples, window, plot)
    require_gcode_files(gcode)
    _not_twice(gcode)
    found = _designs(plates, gcode, pair, design, (samples, window))
    require(len(found) == 1, "pair", "none", "the plates hold several pairs: name one (--pair ID), "
                                             "one of " + ", ".join(f"'{p.pair}'" for p in found))
    if band[0] and band[1] is None:
        chosen = plate_printer(found[0], chosen)
    report, summary, read = with_progress(not quiet, "G-code read-back", run_gcode_check, gcode,
                                          found[0], samples, window)
    if chosen is not None:
        summary["tolerance"] = with_progress(not quiet, "band check", band_prediction, read, chosen)
        summary["gcode"]["inside_band"] = within_band(summary, summary["tolerance"])
    files = written_pair_files(WrittenPairCheck(summary["pinion"], summary["wheel"], found[0].spec,
                                                samples, window, plot), report)
    named = show.write_named("mesh-check", files, dry_run, force, plot=plot)
    show.report(summary, lambda: pair_lines(summary, summary["distance_mm"])[:1]
                + gcode_lines(summary) + _rest(summary, tolerance_lines))
    # the fit the warning suggests is to the band checked: the plates' printer when they chose it
    warn_band_jams(show, summary.get("tolerance"), band[1] or (chosen.given or chosen.name if chosen else None))
    show.files(named, dry_run)
    return report.interferes or report.contact_lost


def _not_twice(gcode: list[Path]) -> None:
    """Refuse (naming --gcode) one G-code file given twice, or a copy of it: read twice, its
    parts would be found twice and its plate taken once."""
    from wheelstep_cli.cli.commands.meshcheck_shared import same_file
    from wheelstep_cli.errors import DesignError

    if len(gcode) == 2 and same_file(*gcode):
        twice = ("is given twice" if gcode[0] == gcode[1] else
                 f"is the same G-code as the first --gcode ({gcode[0]})")
        raise DesignError("gcode", str(gcode[1]), f"{twice}: give it once when its plate holds "
                                                  "the whole pair, or the G-code of each of the "
                                                  "pair's two plates")


def _designs(args: list[str], gcode: list[Path], pair, design: dict, poses: tuple) -> list:
    """The pair(s) the G-code was sliced from: two meshes (STL, FILE.3mf:NAME) drawn for the
    design the options give, checked for it as plain ``mesh-check`` checks them (``poses`` =
    (samples, window)), else plates (the design from their metadata; default FILE.3mf
    beside each FILE.gcode)."""
    from wheelstep_cli.cli.commands.meshcheck_shared import design_spec, no_design_options, require_two_meshes
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.gcode_check import default_plates, mesh_pair
    from wheelstep_cli.parts.plate_pairs import find_plate_pairs, is_plate_input

    if len(args) == 2 and not is_plate_input(*args):
        if pair is not None:
            raise DesignError("pair", pair, "picks a pair on plates; the meshes named are one pair")
        require_two_meshes(*args)
        return [mesh_pair(args[0], args[1], design_spec(design), *poses)]
    no_design_options(design)
    if args or len(gcode) != 1:
        return find_plate_pairs(args or default_plates(gcode), pair)
    try:
        return find_plate_pairs(default_plates(gcode), pair)
    except DesignError as err:
        if err.param != "pinion":       # the plate beside holds no whole pair
            raise
        raise DesignError("gcode", str(gcode[0]), "its plate holds no whole gear pair (a pair too "
                                                  "large for one bed is on two): give the other "
                                                  "plate's G-code too (--gcode FILE2.gcode)") from None


def _rest(summary: dict, tolerance_lines) -> list[str]:
    from wheelstep_cli.parts.mesh_check import meshing_lines

    return meshing_lines(summary) + (tolerance_lines(summary["tolerance"]) if "tolerance" in summary
                                     else [])


def plate_printer(pair, default):
    """The printer whose band --tolerance checks when --printer is not given: the one the
    plates were written for (their ``printer`` metadata), else ``default``; a plate's printer
    whose profile cannot be used here is refused (its band is not the default printer's)."""
    from wheelstep_cli.config.profiles import load_printer_profile
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.tolerance_cli import band_printer

    name = pair.pinion.metadata.get("printer")
    if not name:
        return default
    try:
        profile = load_printer_profile(name)
    except DesignError as err:      # not found, or a file's problems (config.schema.InvalidInput)
        why = "; ".join(err.lines()) if hasattr(err, "lines") else err.limit
        # said of --tolerance, the option the user gave that asks for the band
        raise DesignError("tolerance", "on", f"the plates were written for printer '{name}', whose profile cannot "
                                             f"be loaded here ({why}): name it (--printer PROFILE)") from None
    return band_printer(profile)    # a profile without a band is told to add one
