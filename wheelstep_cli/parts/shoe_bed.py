"""A shoe too large for the printer's bed, remedied by the shoe of the same mechanism drawn
smaller. The sole scales with the mechanism (a, b and the strut, SPEC §2: its points are
sums of those lengths' terms); the socket and the rim keep their size, so the smaller shoe
is built and put on the bed before it is offered. Lengths in mm."""

from __future__ import annotations

from typing import Callable

from wheelstep_cli.config.names import as_flags
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.mesh_bounds import no_remedy, refused_try
from wheelstep_cli.parts.smaller import scaled_mechanism, size_percent

#: Builds of smaller shoes a remedy tries at most (the socket and rim, which do not scale, keep
#: a part from shrinking by the mechanism's factor, so the size is searched).
SHOE_TRIES = 8


def shoe_scaled_to_bed(shoe, printer, rebuild: Callable):
    """``shoe`` on ``printer``'s bed (config.printers.Printer), or its refusal (DesignError)
    with the mechanism drawn smaller as the remedy once ``rebuild(spec)`` (the shoe of a
    spec built as ``shoe`` was) is on that bed; else the tries said. Too tall (the width
    upright) keeps its own remedy."""
    from wheelstep_cli.parts.shoe import require_shoe_on_bed

    try:
        return require_shoe_on_bed(shoe, printer)
    except DesignError as err:
        scale = getattr(err, "bed_scale", None)
        if scale is None or scale >= 1.0:
            raise
        spec = shoe.printing.design if shoe.printing is not None and shoe.printing.design is not None else shoe.spec
        found, tried, factor = _smaller_shoe(spec, scale, printer, rebuild)
        if found is None:
            raise err.with_advice(f"{no_remedy(tried)}: a printer with a larger bed (--printer)", {}) from None
        raise err.with_advice(f"use {as_flags(found)} (the mechanism drawn at {size_percent(factor)} of its size, "
                              "the socket and rim as they are: the bed holds that shoe)", found) from None


def shoe_on_its_bed(shoe, chosen, plate: bool, rebuild: Callable):
    """``shoe`` checked on the bed its plate goes on (:func:`shoe_scaled_to_bed`, the smaller
    shoe as the remedy): the printer ``chosen`` (a printer profile, the one ``shoe`` was drawn
    for), or, when a plate is written (``plate``) with none chosen, the default printer, which
    the refusal says it is."""
    from wheelstep_cli.config.profiles import load_printer
    from wheelstep_cli.parts.plate_layout import default_printer_said

    if chosen is not None:
        return shoe_scaled_to_bed(shoe, shoe.printing.printer, rebuild)
    if not plate:
        return shoe
    try:
        return shoe_scaled_to_bed(shoe, load_printer(), rebuild)
    except DesignError as err:
        raise default_printer_said(err) from None


def _smaller_shoe(spec, scale: float, printer, rebuild: Callable) -> tuple[dict | None, list[str], float]:
    """(the options of the largest smaller shoe found on the bed, or None; what the tries gave;
    its factor). The first try scales the mechanism by the bed's scale; the socket and rim do
    not scale, so a try still off the bed steps by that try's scale squared, and once one fits
    the gap to the last one off the bed is halved (SHOE_TRIES builds, 0.1 s each)."""
    from wheelstep_cli.config.schema import build
    from wheelstep_cli.parts.shoe import require_shoe_on_bed

    tried, best, off = [], None, None      # best: (options, factor, scale) on the bed; off: a scale off it
    for attempt in range(SHOE_TRIES):
        options, factor = scaled_mechanism(spec, scale)
        if best is not None and options == best[0]:
            break       # nothing between them at 0.1 mm
        if min(options.values()) <= 0:
            zero = ", ".join(name for name, value in options.items() if value <= 0)
            tried.append(f"the mechanism drawn at {100 * scale:.2g} % of its size rounds {zero} to 0 mm")
            break
        try:
            require_shoe_on_bed(rebuild(build(type(spec), {**spec.model_dump(), **options})), printer)
            best = (options, factor, scale)
        except DesignError as refusal:
            more = getattr(refusal, "bed_scale", None)
            if more is None or more >= 1.0:
                tried.append(refused_try(options, refusal))
                break
            tried.append(f"{as_flags(options)} is still too large for the bed")
            off = scale
            if best is None:
                scale *= more if attempt == 0 else more * more
                continue
        if off is None:
            break       # the bed's own scale fits: the largest
        scale = (best[2] + off) / 2
    if best is None:
        return None, tried, scale
    return best[0], tried, best[1]
