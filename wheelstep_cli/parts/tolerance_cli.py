"""The band check and fit as the commands run them (SPEC §11): which printer's band, the
pair built (fitted or as asked) and the record and text lines of the report. Lengths in mm."""

from __future__ import annotations

from wheelstep_cli.parts.fit import fit_line, fit_pair, fit_record
from wheelstep_cli.parts.tolerance import (NOMINAL, SectionedPair, band_lines, band_record, check_case,
                                           require_band, sectioned_pair)


def band_printer(printer):
    """The printer whose band is checked: the one given, else the default printer."""
    from wheelstep_cli.config.printers import DEFAULT_PRINTER
    from wheelstep_cli.config.profiles import load_printer_profile

    chosen = printer if printer is not None else load_printer_profile(DEFAULT_PRINTER)
    require_band(chosen)
    return chosen


def band_pair(spec, printer, check: bool, fit: str | None):
    """(pair, band record, nominal report): the pair of ``spec`` built for ``printer`` (None:
    as designed) and, when ``check`` (or a ``fit``), its band record and meshing report as
    written (reused: the band costs its 4 cases). With a fit the pair is built with the
    fitted tooth clearance on the printer (the default printer when none is given)."""
    from wheelstep_cli.parts.kinds import build_for_printer

    if not check and fit is None:
        return build_for_printer("gear-pair", spec, printer), None, None
    chosen = band_printer(printer)
    if fit is not None:
        result = fit_pair(spec, chosen, fit, lambda s, p: build_for_printer("gear-pair", s, p))
        return (result.pair, {**result.band, "fit": fit_record(result, fit, spec.backlash_mm)},
                result.nominal)
    pair = build_for_printer("gear-pair", spec, printer)
    sections = sectioned_pair(pair)
    nominal = check_case(sections, NOMINAL)
    record = band_record(sections, chosen.band, chosen.name, nominal)
    if printer is None:
        record["note"] = "the default printer's band on the pair as designed (no --printer)"
    return pair, record, nominal


def tolerance_lines(record: dict) -> list[str]:
    """Text lines of a band record (with its fit when there is one)."""
    lines = band_lines(record)
    if "fit" in record:
        lines.insert(0, fit_line(record["fit"]))
    if "note" in record:
        lines.append(f"  ({record['note']})")
    return lines


def outline_band(outlines, check, nominal, printer) -> dict:
    """The band record of two read outlines (mm, own frames) of ``mesh-check``: ``check`` a
    :class:`~wheelstep_cli.parts.mesh_check_files.WrittenPairCheck`, ``nominal`` its report."""
    from dataclasses import replace

    from wheelstep_cli.gears.meshing import MeshingSettings
    from wheelstep_cli.parts.gear_pair import generation_law, installed_distance

    _, blended = generation_law(check.spec)
    sections = SectionedPair(outlines[0], outlines[1], blended, installed_distance(check.spec, blended),
                             int(nominal.teeth))
    settings = replace(MeshingSettings(), samples=check.samples, window=check.window)
    return band_record(sections, printer.band, printer.name, nominal, settings)
