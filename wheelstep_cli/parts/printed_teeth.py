"""Whether an FDM printer can lay down a generated pair's teeth (issue 13): a tooth whose tip
land is narrower than two extrusion lines loses its tip when printed, so the pair is refused
for that printer, with a tooth count it can print. Lengths in mm.

A tooth's loss is how much of its height a morphological opening of two lines' width
takes away (geometry.planar.tooth_heights_lost): what the lines can fill. The nozzle is
the narrowest line a slicer lays (PrusaSlicer's default width is 1.125 x nozzle, its thin
walls go down to about the nozzle), so two lines are 2 x nozzle_diameter.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.config.names import as_flags
from wheelstep_cli.config.specs import MIN_MODULE, MIN_TEETH
from wheelstep_cli.errors import DesignError

#: Height (mm) the typical (median) tooth may lose: the rounding of a tip land's two
#: corners, as even wide teeth have.
TYPICAL_LOSS = 0.1
#: Height (mm) any other tooth may lose (about one layer, a tenth of the working depth at
#: module 1): beyond, its tip land is under two lines and the tip is not printed.
MAX_LOSS = 0.2
#: Teeth on each side of each handover corner (SPEC §3) that may lose more: they are
#: topped to the generator's land floor by design (the pitch curve's corner narrows them).
CORNER_TEETH = 2


def two_lines(printer) -> float | None:
    """Width (mm) of two extrusion lines of ``printer``; None for a printer that lays no
    lines (resin)."""
    if printer is None or printer.technology != "fdm":
        return None
    return 2.0 * printer.nozzle


def thin_teeth(outline: np.ndarray, module: float, width: float, corners: int) -> str | None:
    """Why a gear outline's teeth are too thin for lines ``width`` mm wide (None: they are
    not); ``corners``: handover corners round the gear."""
    from wheelstep_cli.geometry.planar import tooth_heights_lost

    lost = tooth_heights_lost(outline, module, width)
    allowed = 2 * CORNER_TEETH * corners
    over = int((lost > MAX_LOSS).sum())
    if len(lost) and np.median(lost) > TYPICAL_LOSS:
        return f"the typical tooth loses {np.median(lost):.2f} mm of its height (> {TYPICAL_LOSS:g})"
    if over > allowed:
        return (f"{over} teeth lose more than {MAX_LOSS:g} mm of their height (up to {lost.max():.2f}; "
                f"{allowed} beside the {corners} handover corners may)")
    return None


def require_printable_teeth(pair, printer=None) -> None:
    """Refuse (DesignError naming --z) a generated pair whose pinion or wheel teeth keep a tip
    land under two extrusion lines of ``printer`` (default: the printer it was drawn for),
    with the largest smaller tooth count whose pinion keeps it, when one is found."""
    printer = printer or (pair.printing.printer if pair.printing is not None else None)
    width = two_lines(printer)
    if width is None or pair.generated is None:
        return
    gen, law = pair.generated, pair.generated.law
    found = [f"{name}: {why}" for name, outline, corners in (
        ("pinion", pair.pinion_outline, law.pinion_periods),
        ("wheel", pair.wheel_outline, law.wheel_periods))
        if (why := thin_teeth(outline, gen.module, width, corners)) is not None]
    if not found:
        return
    design = pair.as_asked
    z = fewer_teeth(pair, design, printer, width)
    options = None if z is None else sized_teeth(design, z)
    remedy = (f"use {as_flags(options)} (fewer, larger teeth)" if options is not None else
              "use fewer teeth (--z) or a larger --module")
    # a fitted pair's teeth are drawn smaller: what prints thick enough unfitted may not
    inset = float(getattr(pair, "inset", 0.0) or 0.0)
    fitted = (f", the outlines drawn {abs(inset):.3f} mm {'smaller' if inset > 0 else 'larger'} by the fit "
              "to the printer's band" if inset else "")
    error = DesignError("z", design.z,
                        f"the teeth are too thin for printer '{printer.name}' (tip land under two "
                        f"{width / 2:g} mm extrusion lines{fitted}; {'; '.join(found)}); nothing written; "
                        f"{remedy}, or a printer with a finer nozzle")
    if options is not None:
        error.remedy = options
    raise error


def sized_teeth(design, z: int) -> dict:
    """The options (name -> value) that give ``design`` (the pair refused, a remedy's try
    included) ``z`` teeth keeping that pair's size: with a module the user gave (which sizes
    the pair with the count) that module scaled by z0 / z too, so the teeth grow; without one
    the count alone (the module follows it). The module is at least MIN_MODULE."""
    if design.module is None:
        return {"z": z}
    return {"z": z, "module": max(MIN_MODULE, round(float(design.module) * design.z / z, 3))}


def sized_remedy(design, remedy: dict, shrink: float = 1.0) -> dict:
    """``remedy`` keeping the size of the pair asked for: a module the user gave sizes the
    pair with the tooth count (the centre distance is solved for it), so more teeth on that
    module may outgrow the printer; then a remedy that changes the count scales the module
    by z / z' (printed_teeth.sized_teeth), one that keeps it keeps the design's module. With
    ``shrink`` < 1 (a pair kept at its size still off the bed) the pair is drawn that much
    smaller (the module rounded down to 0.001 mm)."""
    import math

    if design.module is None:
        return remedy
    z = remedy.get("z", design.z)
    kept = {name: value for name, value in remedy.items() if name != "module"}
    if shrink < 1.0:
        module = sized_teeth(design, z).get("module", design.module) * shrink
        return {**kept, "z": z, "module": max(MIN_MODULE, math.floor(module * 1000 + 1e-9) / 1000)}
    return kept if z == design.z else {**kept, **sized_teeth(design, z)}


def fewer_teeth(pair, design, printer, width: float) -> int | None:
    """The largest tooth count below the design's (in whole law periods) whose pinion, drawn
    for ``printer`` and inset by ``pair``'s fit inset, keeps its tips under two lines
    ``width`` mm wide; None if none does. (The wheel, carved by that pinion, gets the larger
    module too; a module the user gave is scaled with the count, :func:`sized_teeth`: fewer
    teeth on the same module are about as thin.) Counts 1, 2, 4 ... periods below are tried, down to the least count, until
    one prints or cannot be cut (it undercuts); then the counts between are halved: fewer
    teeth print wider tips, and below the printing ones the pinion undercuts. A candidate's
    own fit may need a few um more or less inset than ``pair``'s: the count is the one that
    inset leaves printable."""
    periods = pair.generated.law.pinion_periods
    inset = float(getattr(pair, "inset", 0.0))
    state = lambda z: _printing(design, z, printer, width, inset, periods)  # noqa: E731
    least = design.z - (design.z - MIN_TEETH) // periods * periods
    # the largest count known not to be too thin (and whether it prints; below the least, a
    # count none), and the least known to be too thin (the design's)
    below, prints, thin, step = least - periods, False, design.z, 1
    while thin > least:
        z = max(design.z - step * periods, least)
        found = state(z)
        if found != "thin":
            below, prints = z, found == "prints"
            break
        thin, step = z, 2 * step
    # halved between them: the largest count that is not too thin prints, or none does
    # (the ones below the printing counts undercut)
    while thin - below > periods:
        middle = below + (thin - below) // (2 * periods) * periods
        found = state(middle)
        if found == "thin":
            thin = middle
        else:
            below, prints = middle, found == "prints"
    return below if prints else None


def _printing(design, z: int, printer, width: float, inset: float, periods: int) -> str:
    """Whether the pinion of ``design`` with ``z`` teeth, drawn for ``printer`` and inset by
    ``inset`` mm, keeps its tips under two lines ``width`` mm wide: "prints", "thin", or
    "uncut" when it cannot be cut at all (it undercuts)."""
    from wheelstep_cli.geometry.planar import offset_outline
    from wheelstep_cli.parts.gear_pair import generation_settings
    from wheelstep_cli.parts.kinds import KINDS, printed_spec

    printed = printed_spec(KINDS["gear-pair"], design.model_copy(update=sized_teeth(design, z)), printer)
    try:
        outline, module = _pinion(printed)
    except DesignError:
        return "uncut"
    if inset:
        # a fit thins every tooth by its inset: the remedy must keep the tips after it
        thin = generation_settings(printed).at_module(module).wheel_tolerance
        outline = offset_outline(outline, -inset, "pinion", thin=thin)
    return "prints" if thin_teeth(outline, module, width, periods) is None else "thin"


def _pinion(spec) -> tuple[np.ndarray, float]:
    """The pinion of ``spec`` as the pair's pipeline cuts it (outline mm, module mm)."""
    from dataclasses import replace

    from wheelstep_cli.gears.generation import GenerationSettings, generate_pinion
    from wheelstep_cli.parts.gear_laws import design_backlash, generation_law, rolling_distance

    if spec.backlash is None:   # a printer without tooth clearance: the design's default
        spec = spec.model_copy(update={"backlash": design_backlash(spec)})
    _, law = generation_law(spec)
    settings = replace(GenerationSettings(), tilt=spec.tilt)
    return generate_pinion(law, spec.z, spec.cutter(), corner=spec.corner, settings=settings,
                           center_distance=rolling_distance(spec, law))
