"""The band check and fit as the commands run them (SPEC §11): which printer's band, the
pair built (fitted or as asked) and the record and text lines of the report. Lengths in mm."""

from __future__ import annotations

from dataclasses import replace

from wheelstep_cli.parts.fit import fit_line, fit_pair, fit_record
from wheelstep_cli.parts.tolerance import (NOMINAL, SectionedPair, band_lines, band_record, check_case,
                                           design_printer, require_band, sectioned_pair)


def band_printer(printer):
    """The printer whose band is checked: the one given, else the default printer."""
    from wheelstep_cli.config.printers import DEFAULT_PRINTER
    from wheelstep_cli.config.profiles import load_printer_profile

    chosen = printer if printer is not None else load_printer_profile(DEFAULT_PRINTER)
    require_band(chosen)
    return chosen


def bore_fit(pair, band) -> dict | None:
    """The shaft fit of the pair's bores over the band (SPEC §11: holes shrink): the shaft
    is the designed bore, the hole is drawn larger by the printer's hole compensation and
    comes out up to ``band.hole_shrink`` smaller than drawn, so the diametral clearance
    runs from compensation - shrink (the band's tight extreme) to the compensation (mm;
    below zero the shaft must be pressed in). None for a pair without bores."""
    printing = getattr(pair, "printing", None)
    shaft = float((printing.design if printing is not None else pair.spec).bore or 0.0)
    return shaft_fit(shaft, float(pair.spec.bore or 0.0), pair.spec.bore_shape, band)


def plate_bore_fit(found, printer) -> dict | None:
    """:func:`bore_fit` of a pair found on plates (parts.plate_pairs.PlatePair, its bores as
    drawn) over ``printer``'s band, when the plates say the hole compensation they were drawn
    with (batch plates state it; a ``gears`` plate was drawn by the printer it names, so that
    printer's); None otherwise (the shaft is not known) or for a pair without bores."""
    metadata = found.pinion.metadata
    given = metadata.get("printer.hole_compensation")
    if given is None:
        if metadata.get("printer") not in (printer.name, printer.given) or metadata.get("compensated") != "yes":
            return None
        given = printer.hole_compensation
    drawn = float(found.spec.bore or 0.0)
    return shaft_fit(drawn - float(given), drawn, found.spec.bore_shape, printer.band)


def shaft_fit(shaft: float, drawn: float, bore_shape, band) -> dict | None:
    """The fit (mm) of a shaft of diameter ``shaft`` in a bore drawn ``drawn`` over ``band``
    (see :func:`bore_fit`); None for no bore."""
    if shaft <= 0.0:
        return None
    shrink = float(band.hole_shrink)
    # rounded to the nanometre: 8.2 - 0.2 - 8 is a zero, not a press fit of 2e-15 mm
    least, most = round(drawn - shrink - shaft, 9), round(drawn - shaft, 9)
    return {"bore_shape": str(getattr(bore_shape, "value", bore_shape)),
            "shaft_mm": shaft, "drawn_mm": drawn, "hole_compensation_mm": most,
            "printed_mm": [round(drawn - shrink, 9), drawn], "clearance_mm": [least, most],
            "shaft_fits": bool(least >= 0.0),
            "note": "diameters (across flats for a hex bore); a bore printed smaller than the shaft "
                    "needs reaming or a press fit"}


def bore_line(record: dict) -> str:
    lo, hi = (value + 0.0 for value in record["clearance_mm"])   # + 0.0: no "-0.000"
    return (f"  bore: shaft {record['shaft_mm']:g} mm in a bore drawn {record['drawn_mm']:g} mm, "
            f"printed {record['printed_mm'][0]:g}..{record['printed_mm'][1]:g} mm: clearance "
            f"{lo:+.3f}..{hi:+.3f} mm " + ("(slides on)" if lo > 0.0 else
                                          "(line to line at the band's extreme: may need reaming)"
                                          if record["shaft_fits"] else
                                          "(TIGHT at the band's extreme: ream or press)"))


def band_pair(spec, printer, check: bool, bed=None):
    """(pair, band record, nominal report): the pair of ``spec`` built for ``printer`` (None:
    as designed), refused (DesignError) at once when a gear cannot go on ``bed``'s bed (a
    printer; None: not checked), and, when ``check``, its band record and meshing report as
    written, with its mounting record (reused: the band costs its 4 cases)."""
    from wheelstep_cli.parts.gear_pair import require_pair_on_bed
    from wheelstep_cli.parts.kinds import build_for_printer

    pair = build_for_printer("gear-pair", spec, printer)
    if bed is not None:
        require_pair_on_bed(pair, bed)
    if not check:
        return pair, None, None
    chosen = band_printer(printer)
    sections = sectioned_pair(pair)
    nominal = check_case(sections, NOMINAL)
    record = band_record(sections, chosen.band, chosen.name, nominal)
    record["bore"] = bore_fit(pair, chosen.band)
    if printer is None:
        record["note"] = "the default printer's band on the pair as designed (no --printer)"
    return pair, record, replace(nominal, mounting=pair_mounting(pair, sections))


def fit_design(spec, printer):
    """(the printer whose band a fit is for: ``printer``, else the default printer; the
    design drawn on it without its tooth clearance, which the fit's inset replaces),
    refused (DesignError) at once when a gear cannot go on its bed."""
    from wheelstep_cli.parts.gear_pair import require_pair_on_bed

    chosen = band_printer(printer)
    return chosen, require_pair_on_bed(design_pair(spec, chosen), chosen)


def design_pair(spec, printer):
    """The gear pair of ``spec`` drawn for ``printer`` as a fit's design: without the
    printer's tooth clearance (:func:`~wheelstep_cli.parts.tolerance.design_printer`)."""
    from wheelstep_cli.parts.kinds import build_for_printer

    return build_for_printer("gear-pair", spec, design_printer(printer))


def fitted_pair(spec, chosen, fit: str, design, design_report=None, progress=None):
    """(pair, band record with its fit, nominal report with its mounting record): ``design``
    (of :func:`design_pair`; ``design_report`` its meshing report, None: checked here)
    inset for ``fit`` on ``chosen``'s band. The inset pair is no larger than the design, so
    a design on the bed stays on it."""
    result = fit_pair(spec, chosen, fit, lambda s, p: design, design_report=design_report,
                      progress=progress)
    record = {**fit_record(result, fit), "replaces_tooth_clearance_mm": float(chosen.tooth_clearance)}
    return (result.pair, {**result.band, "fit": record, "bore": bore_fit(result.pair, chosen.band)},
            replace(result.nominal, mounting=pair_mounting(result.pair)))


def pair_mounting(pair, sections: SectionedPair | None = None) -> dict:
    """The mounting record (parts.mesh_check) of ``pair``'s outlines as written (its
    ``sections`` when already cut), a fit's inset included."""
    from wheelstep_cli.parts.mesh_check import mounting_record

    sections = sectioned_pair(pair) if sections is None else sections
    return mounting_record(sections.pinion, sections.wheel, sections.law, sections.distance,
                           getattr(pair, "generated", None), float(getattr(pair, "inset", 0.0)))


def printer_band_record(pair, printer) -> dict:
    """The band record of a pair built for ``printer`` with its tooth clearance (as batch
    builds it), or, when the printer states no band, a record saying to add one (a printer
    without a band is not taken as perfect)."""
    if printer.band is None:
        return {"printer": printer.name, "checked": False, "jams": None,
                "note": f"printer {printer.name} has no dimensional band: add a `band:` section "
                        "(outline, hole_shrink, center_distance, mm) to its profile to check the "
                        "pair over it"}
    sections = sectioned_pair(pair)
    record = band_record(sections, printer.band, printer.name, check_case(sections, NOMINAL))
    return {"checked": True, "tooth_clearance_mm": printer.tooth_clearance, **record,
            "bore": bore_fit(pair, printer.band)}


def tolerance_lines(record: dict) -> list[str]:
    """Text lines of a band record (with its fit when there is one)."""
    lines = band_lines(record)
    if "fit" in record:
        lines.insert(0, fit_line(record["fit"]))
    if record.get("bore"):
        lines.append(bore_line(record["bore"]))
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
