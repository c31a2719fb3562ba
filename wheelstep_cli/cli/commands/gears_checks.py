"""What ``wheelstep gears`` checks before it writes a pair: the meshing check, the design
bounds and, with a fit, the design before the search and the fit itself (SPEC §10, §11)."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

from wheelstep_cli.cli.output import Output
from wheelstep_cli.errors import CheckRefused, DesignError


def checked_pair(spec, printer, show: Output, allow_interference: bool, band: tuple, bed=None,
                 trying: bool = False):
    """(pair, meshing record, band record or None, meshing report) of ``spec`` built for
    ``printer``, refused (DesignError, or exit 1 for interference) as ``gears`` refuses it;
    ``band`` = (check over the printer's band, the fit or None[, where the fit comes from]);
    ``bed``: the printer whose bed the written plate needs (None: none), checked as soon as
    the gears are built, before any meshing check; ``trying``: a remedy's build, whose
    interfering teeth are its refusal (DesignError), not the command's."""
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.parts.bed_remedy import scaled_to_bed
    from wheelstep_cli.parts.fit import PROFILE_FIT_REMEDY, require_fit_met
    from wheelstep_cli.parts.interference_refusals import require_tips_clear_of_roots
    from wheelstep_cli.parts.mesh_bounds import remedy_check, require_within_bounds, undercut_checked
    from wheelstep_cli.parts.mesh_check import check_gear_pair
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth
    from wheelstep_cli.parts.tolerance_cli import band_pair, fit_design, fitted_pair

    def checked_remedy(check, trial):
        return with_progress(not show.quiet, "checking the remedy", check, trial)

    # a remedy's try (trying) runs no remedy search of its own: refused, it is no remedy
    plain = None if trying else remedy_check(printer, checked_remedy, bed)
    whole = None if trying else whole_check(printer, show, band, bed)
    # the tip clearance is known before any tooth is cut (a fit's design is checked before its inset)
    require_tips_clear_of_roots(spec, plain if band[1] is None else whole)
    if band[1] is not None:
        # the design is checked, bounded and refused as without a fit before the search
        # spends a dozen meshing checks on it; the fit's inset is print compensation, judged
        # on the band (the written pair's own figures are the inset outlines')
        chosen, design = scaled_to_bed(lambda: _on_the_bed(lambda: undercut_checked(
            lambda: fit_design(spec, printer), spec, plain), printer, True), spec, whole)
        design_check = with_progress(not show.quiet, "meshing check", check_gear_pair, design)
        design_verify = None if trying else remedy_check(design.printing.printer, checked_remedy, bed)
        design_record = _meshing_or_refused(design, design_check, allow_interference, design_verify, trying)
        # a bounds remedy is built with its fit: the inset thins the teeth the design's check passed
        require_within_bounds(design, design_record, verify=whole)
        if trying:
            require_printable_teeth(design)
        else:   # the fewer teeth offered are built with their fit first: its inset thins them more
            printable_or_remedied(design, spec, printer, show, band, bed)
        pair, tolerance, check = with_progress(not show.quiet, f"fitting to the band of {chosen.name}",
                                               fitted_pair, spec, chosen, band[1], design, design_check)
        record = _meshing_or_refused(pair, check, allow_interference, trying=trying)
        if len(band) > 2 and band[2]:
            tolerance["fit"]["from"] = band[2]
        require_fit_met(tolerance, **({} if tolerance["fit"].get("from", "--fit") == "--fit" else
                                      {"remedy": PROFILE_FIT_REMEDY}))
    else:
        pair, tolerance, check = scaled_to_bed(lambda: _on_the_bed(lambda: undercut_checked(
            lambda: band_pair(spec, printer, bool(band[0]), bed), spec, plain), printer, False), spec, whole)
        if check is None:
            check = with_progress(not show.quiet, "meshing check", check_gear_pair, pair)
        record = _meshing_or_refused(pair, check, allow_interference, plain, trying)
        try:
            require_within_bounds(pair, record, verify=plain)
        except DesignError as err:
            raise err if trying else _fit_offered(err, spec, pair, printer, show, bed) from None
    return pair, record, tolerance, check


def whole_check(printer, show: Output, band: tuple, bed) -> Callable:
    """``verify(design)`` -> (pair, meshing record within the bounds) for a remedy of ``gears``
    (``band``, ``bed`` as :func:`checked_pair` takes them): the pair built, fitted and checked
    as `gears` checks what it writes, its teeth wide enough for the printer, refused
    (DesignError, with the remedy the figures point to, unbuilt) where `gears` refuses it. A
    fitted pair's record is its design's, as the bounds judge it (bound_figures)."""
    from wheelstep_cli.parts.bound_figures import fit_design_record
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth

    def verify(design):
        # the band's check refuses nothing (it warns): a fit's search is the band's part that does
        pair, record, tolerance, _ = checked_pair(design, printer, show, False, (False, *band[1:]), bed,
                                                  trying=True)
        require_printable_teeth(pair)
        return pair, fit_design_record(record, tolerance["fit"]) if pair.inset else record
    return verify


def printable_or_remedied(pair, spec, printer, show: Output, band: tuple, bed) -> None:
    """Refuse (DesignError) ``pair`` (``spec`` as `gears` built it) when its teeth are too thin
    for the printer, offering the fewer teeth the refusal names only once that pair passes all
    `gears` checks (:func:`whole_check`: its bounds, its fit), following each try's own remedy;
    else saying what the tries gave."""
    from wheelstep_cli.config.names import as_flags
    from wheelstep_cli.parts.mesh_bounds import MeshBounds, change_advice, no_remedy, verified_remedy
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth

    try:
        require_printable_teeth(pair)
    except DesignError as err:
        if not getattr(err, "remedy", None):
            raise
        found, tried, _ = verified_remedy(spec, err.remedy, whole_check(printer, show, band, bed), MeshBounds())
        if found:
            raise err.with_advice(f"use {as_flags(found)} (fewer, larger teeth), or a printer with a finer "
                                  "nozzle", found) from None
        raise err.with_advice(change_advice(spec, no_remedy(tried)) + ", or a printer with a finer nozzle",
                              {}) from None


#: Builds of a fit (each a fit search over the printer's band) a ripple refusal tries: the
#: fit, then the fit with the remedies its own refusals name (a backlash that clears without
#: the printer's clearance, teeth thick enough after the inset).
FIT_TRIES = 3


def _fit_offered(err, spec, pair, printer, show: Output, bed):
    """``err``, a bounds refusal of ``pair`` (``spec`` built for ``printer``), or, when it found
    no remedy for a ripple drawn with the printer's tooth clearance, the same refusal offering
    ``--fit auto`` (with the options its own refusals then ask for) once the fitted pair passes
    as ``gears --fit auto`` checks it: a fit replaces the clearance, whose play the ripple pays
    and which no backlash can lower. A fit that does not pass is said as tried."""
    from wheelstep_cli.cli.progress import terminal_note
    from wheelstep_cli.config.names import as_flags
    from wheelstep_cli.parts.mesh_bounds import change_advice, fit_may_cure, no_remedy
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth

    if err.remedy or not fit_may_cure(pair, getattr(err, "broken", [])):
        return err
    terminal_note(not show.quiet, f"the ripple is the play of printer {printer.name}'s "
                                  f"{printer.tooth_clearance:g} mm tooth clearance: trying a fit to its "
                                  "band (--fit auto) instead")
    remedy, why = {"fit": "auto"}, []
    while len(why) < FIT_TRIES:
        try:
            fitted, *_ = checked_pair(spec.model_copy(update=remedy), printer, show, False,
                                      (True, "auto", "--fit"), bed, trying=True)
            require_printable_teeth(fitted)
        except DesignError as refusal:
            why.append(f"{as_flags(remedy)} is refused: {refusal.cause}")
            # the design outside the bounds without the clearance: no fit cures what its teeth do
            own = {} if getattr(refusal, "broken", None) else getattr(refusal, "remedy", None) or {}
            following = {**remedy, **own}
            if following == remedy:     # no remedy of its own, or one already applied
                break
            remedy = following
            continue
        return err.with_advice(f"use {as_flags(remedy)} (the fit to the band of printer {printer.name} "
                               f"replaces its {printer.tooth_clearance:g} mm tooth clearance, whose "
                               "play costs the ripple)", remedy)
    return err.with_advice(change_advice(spec, no_remedy([*getattr(err, "tried_words", []), *why])), {})


def _meshing_or_refused(pair, check, allow_interference: bool, verify=None,
                        trying: bool = False) -> dict:
    """The meshing record of ``check`` (of ``pair``), refused (CheckRefused: exit 1, nothing written) when
    the teeth interfere and that is not allowed; as bad input (exit 2, with a remedy checked
    by ``verify`` when given) when the mounted distance or a backlash set too small is the cause;
    ``trying``: a remedy's build, refused by a DesignError with nothing said."""
    from wheelstep_cli.parts.interference_refusals import (interference_phrase, require_mounted_where_rolling,
                                                           require_play_that_clears)
    from wheelstep_cli.parts.mesh_check import meshing_record

    record = meshing_record(check)
    if record["interference"] and not allow_interference:
        interfere = interference_phrase(record)
        # mounted off the rolling distance the user's distance is the cause: refused as bad
        # input (exit 2) like a pair mounted farther off, whose figures break the bounds
        require_mounted_where_rolling(pair, interfere, verify)
        if verify is not None:
            require_play_that_clears(pair, record, interfere, verify)
        if trying:
            raise DesignError("allow_interference", "off", f"{interfere}; nothing written")
        raise CheckRefused(f"{interfere}; nothing written (--allow-interference writes them anyway)",
                           {"allow_interference": True})
    return record


def require_height_first(spec, printer, fmt: str, fit: bool):
    """The printer the pair is drawn or laid out for (the one given, else the default printer
    when a 3MF is written or a fit is asked for; None: plain STL for no printer), the pair
    refused when taller than it prints before any tooth is cut, as writing it would refuse it."""

    from wheelstep_cli.config.profiles import load_printer
    from wheelstep_cli.parts.gear_pair import footprint
    from wheelstep_cli.parts.kinds import height_inputs
    from wheelstep_cli.parts.plate_layout import gear_pair_height, gear_pair_stack, require_height

    target = printer or (load_printer() if fmt in ("3mf", "both") or fit else None)
    if target is None:
        return None
    return _on_the_bed(lambda: require_height("pinion", gear_pair_height(spec), target, "thickness",
                                              spec.thickness, footprint(spec), gear_pair_stack(spec),
                                              lowers=height_inputs("gear-pair", spec))
                       or target, printer, fit)


def _on_the_bed(build, printer, fit: bool):
    """``build()``; when the user named no printer, a part too tall for the default printer or
    too large for its bed is refused saying which printer that is and how to choose another
    (or, without a fit, to write no plate)."""
    from wheelstep_cli.parts.plate_layout import default_printer_said

    try:
        return build()
    except DesignError as err:
        if printer is not None or not getattr(err, "beyond_printer", None):
            raise
        # its statements for the inputs that size the part (plate_layout) carry the note too
        raise default_printer_said(err, stl_only=not fit) from None


def collisions_first(show, out: Path, fmt: str, extras, force: bool) -> None:
    """Before the pair is built (seconds): refuse an ``out`` that is a file, and a user's file
    where a named picture (``extras``: parts.gear_exports.GearExtras) or a file of certain
    name (gears.json, the STLs, DXF, SVG, STEP asked for) would go. The plates' names depend
    on the layout: they are checked, with everything, when the files are written."""
    if out.exists() and not out.is_dir():
        raise DesignError("out", str(out), "cannot be written (is a file, not a folder)")
    named = {"plot": extras.plot, "gif": extras.gif}
    show.write_named("gears-pictures", {p: b"" for p in named.values() if p is not None}, True, force, **named)
    suffixes = [s for s, asked in (("stl", fmt in ("stl", "both")), ("dxf", extras.dxf), ("svg", extras.svg),
                                   ("step", extras.step)) if asked]
    certain = {out / "gears.json": "the report",
               **{out / f"{gear}.{s}": f"the {gear}'s {s.upper()}" + (f" (--{s})" if s != "stl" else "")
                  for s in suffixes for gear in ("pinion", "wheel")}}
    # a picture where this run writes a file of its own would overwrite it, or be refused as
    # not written by the pictures' record once the meshes are written (--plot OUT/pinion.svg --svg)
    own = {path.resolve(): what for path, what in certain.items()}
    for option, path in named.items():
        what = own.get(path.resolve()) if path is not None else None
        if what is not None:
            raise DesignError(option, str(path), f"is where this run writes {what}: give the picture "
                                                 "another name")
    show.write_owned(out, "gears", dict.fromkeys(certain, b""), True, force, check_only=True)


#: Least closer mounting (mm) a written pair tolerates without a warning: a hundredth, well
#: below any printed frame's centre-distance error (FDM +-0.05 mm, SPEC §11).
MOUNTING_WARNING = 0.01


def warn_of_the_figures(show: Output, record: dict, speed: str = "hub speed") -> None:
    """Warning lines on stderr: when the law the teeth follow (blended, or from a CSV) ripples
    beyond the bound the teeth are held to (SPEC §10), when the pair tolerates next to no
    closer mounting, and when the (allowed) teeth interfere. ``speed``: what the ripple is of."""
    from wheelstep_cli.parts.bound_figures import MeshBounds

    own = record.get("law_hub_speed_ripple_pct", 0.0)
    if own > MeshBounds().ripple_pct:
        # with --json the figures are not printed above the warning but in the report
        where = "the report's meshing.drive and meshing.coast" if show.json else "the figures above"
        show.warning(f"WARNING: the law the teeth follow itself ripples {own:.2f} % (however exact "
                     f"the teeth, the output speed varies that much; the teeth add {where})")
    closer = record.get("mounting", {}).get("closer_mm")
    if closer is not None and closer < MOUNTING_WARNING and not record["interference"]:
        # said as the mounting line says it: none known (0 or less) is "any closer ... may meet"
        how = (f"mounted {closer:.3f} mm closer than designed the teeth meet" if closer > 0.0
               else "mounted any closer than designed the teeth may meet")
        show.warning(f"WARNING: {how} (see 'mounting'): less than a printed frame's centre distance can be "
                     "held to (a printer profile's band.center_distance; +-0.05 mm on the FDM presets, SPEC §11)")
    if record["interference"]:
        from wheelstep_cli.parts.interference_refusals import interference_phrase
        from wheelstep_cli.parts.mesh_check import figure_text

        clear = figure_text(record["diagnostic_pointwise_ripple_clear_pct"], ".2f")
        show.warning(f"WARNING: {interference_phrase(record)}; pointwise {speed} ripple where they "
                     f"do not (diagnostic): {clear} %")


def warn_no_printed_play(show: Output, pair, record: dict) -> None:
    """A warning line on stderr when generated teeth drawn for a printer keep no play of their
    own (:func:`~wheelstep_cli.parts.tolerance.printed_play`): the backlash is all the printer's tooth clearance (a default
    design backlash no larger than it, or --backlash 0), so a print whose teeth come out
    larger than the clearance allows for jams. Not said when the band was checked (its cases
    say it)."""
    from wheelstep_cli.parts.tolerance import keeps_no_play

    if "tolerance" in record or not keeps_no_play(pair):
        return
    show.warning(f"WARNING: printed on '{pair.printing.printer.name}' the teeth keep no play of their own "
                 f"(backlash j_n {pair.generated.cutter.backlash:.4g} mm, all of it the printer's tooth "
                 "clearance): teeth printed larger than the clearance allows for jam; the same command with "
                 "--tolerance checks it over the printer's band, with --fit auto fits the teeth to it (if the "
                 "inset leaves the teeth too thin, its refusal names the tooth count that prints)")
