"""A shoe too large for the printer's bed, remedied by the shoe of the same mechanism drawn
smaller. The sole scales with the mechanism (a, b and the strut, SPEC §2: its points are
sums of those lengths' terms); the socket and the rim keep their size, so the smaller shoe
is built and put on the bed before it is offered. Lengths in mm."""

from __future__ import annotations

from typing import Callable

from wheelstep_cli.config.names import as_flags
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.mesh_bounds import no_remedy
from wheelstep_cli.parts.smaller import scaled_mechanism, size_percent

#: Rescalings after the first one, each by the scale the last smaller shoe's refusal gives
#: (the socket and rim, which do not scale, keep a part from shrinking by the mechanism's factor).
RESCALES = 2


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
    """(the options of the first smaller shoe on the bed, or None; what the tries gave; its factor)."""
    from wheelstep_cli.config.schema import build
    from wheelstep_cli.parts.shoe import require_shoe_on_bed

    tried = []
    for _ in range(1 + RESCALES):
        options, factor = scaled_mechanism(spec, scale)
        if min(options.values()) <= 0:
            zero = ", ".join(name for name, value in options.items() if value <= 0)
            tried.append(f"the mechanism drawn at {100 * scale:.2g} % of its size rounds {zero} to 0 mm")
            break
        try:
            require_shoe_on_bed(rebuild(build(type(spec), {**spec.model_dump(), **options})), printer)
            return options, tried, factor
        except DesignError as refusal:
            # the rule's own option when the try does not set it (a socket the smaller body cannot hold)
            rule = "" if refusal.param in options else f"--{refusal.param.replace('_', '-')} = {refusal.shown_value}: "
            tried.append(f"{as_flags(options)} is refused: {rule}{refusal.cause}")
            more = getattr(refusal, "bed_scale", None)
            if more is None or more >= 1.0:
                break
            scale *= more
    return None, tried, scale
