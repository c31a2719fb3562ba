"""Parts laid out on a printer's bed: the size check (footprint and height against the bed),
the packing onto as few plates as fit, and the design as 3MF object metadata. Lengths in mm."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from wheelstep_cli.config.printers import Printer
from wheelstep_cli.errors import NOTHING_WRITTEN, DesignError
from wheelstep_cli.formats.threemf import PlateObject, placed_object


def design_metadata(values: dict[str, Any]) -> dict[str, str]:
    """A part's design parameters as 3MF metadata values (None left out, floats as %g)."""
    return {k: f"{v:.12g}" if isinstance(v, float) else str(getattr(v, "value", v))
            for k, v in values.items() if v is not None}


def size_problem(name: str, bounds: np.ndarray, printer: Printer) -> str | None:
    """Why a part of these bounds (2 x 3, mm) cannot go on the printer's bed, or None."""
    from wheelstep_cli.geometry.packing import fits_bed

    size = bounds[1] - bounds[0]
    if fits_bed((size[0], size[1]), printer.bed, printer.edge_margin) is None:
        return f"part '{name}' ({size[0]:.1f} x {size[1]:.1f} mm) does not fit {_bed_words(printer)}"
    if size[2] > printer.max_height:
        return (f"part '{name}' is {_above(size[2], printer.max_height)} mm tall; printer "
                f"'{printer.given or printer.name}' prints at most {printer.max_height:g} mm")
    return None


def _bed_words(printer: Printer) -> str:
    """The printer's bed as a refusal says it (mm)."""
    edge = printer.edge_margin
    return (f"the bed of printer '{printer.given or printer.name}' ({printer.bed[0]:g} x {printer.bed[1]:g} mm "
            f"with {edge:g} mm margins: at most {printer.bed[0] - 2 * edge:g} x {printer.bed[1] - 2 * edge:g} mm)")


def require_on_bed(parts, printer: Printer, height_param: str, height: float,
                   footprint: dict[str, object] | None = None, height_only: tuple[str, ...] = (), *,
                   lowers: "HeightInputs") -> None:
    """Refuse (DesignError) a part taller than the printer prints (named by ``height_param``,
    the option that sets it, with the ``lowers`` remedies) or larger than its bed (named
    ``printer``); either also stated for the ``footprint`` inputs (name -> value) that set the
    part's size (a bed too small, not for those of them ``height_only`` names), so the line
    names the one the user gave."""
    for part in parts:
        require_height(part.name, float(part.bounds[1, 2] - part.bounds[0, 2]), printer, height_param, height,
                       footprint, lowers=lowers)
    # the part the bed's scale is set by first: the one a remedy's size is reckoned from
    scaled = sorted((bed_scale(p.bounds[1, :2] - p.bounds[0, :2], printer), k, p) for k, p in enumerate(parts))
    for _, _, part in scaled:
        size = part.bounds[1] - part.bounds[0]
        problem = size_problem(part.name, part.bounds, printer)
        if problem is not None:
            makes = f"with it, part '{part.name}' is {size[0]:.1f} x {size[1]:.1f} mm, larger than {_bed_words(printer)}"
            sizes = {name: (value, makes) for name, value in (footprint or {}).items()
                     if value is not None and name != "printer" and name not in height_only}
            error = _beyond(DesignError("printer", printer.given or printer.name, problem, sizes), printer)
            error.bed_scale = scaled[0][0]
            raise error


def bed_scale(size, printer: Printer) -> float:
    """The largest factor (at most 1) a footprint of ``size`` (X, Y mm) may be scaled by
    and still fit the printer's bed inside its margins, upright or turned a quarter."""
    room = np.asarray(printer.bed, dtype=float) - 2 * printer.edge_margin
    w, h = (float(v) for v in size)
    upright, turned = min(room[0] / w, room[1] / h), min(room[0] / h, room[1] / w)
    return min(1.0, max(upright, turned))


def gear_pair_height(spec) -> float:
    """How tall (mm) a gear pair's parts stand: the plate and the hub both gears carry on
    their top face, as the meshes' float32 vertices hold it (the plate's check sees that)."""
    return float(np.float32(spec.thickness + spec.hub_mm[1]))


def gear_pair_stack(spec) -> str:
    """What a gear pair's height (:func:`gear_pair_height`) is made of, for a refusal: the
    plate and the hub when it has one ("" without)."""
    hub = spec.hub_mm[1]
    return f" (its {spec.thickness:g} mm plate and {hub:g} mm hub)" if hub > 0 else ""


@dataclass(frozen=True)
class HeightInputs:
    """The inputs a part's height is the sum of (name -> value, mm; a shoe's width, a gear's
    plate and its hub), in the order a refusal offers them lowered, and ``accepts``:
    whether the part's spec takes the options (name -> value) a remedy would set."""

    values: dict[str, float]
    accepts: Callable[[dict], bool] = field(compare=False)


def _above(tall: float, most: float) -> str:
    """``tall`` mm as a line says it beside the ``most`` it exceeds: to a tenth, or to as many
    more decimals (up to 4) as it takes not to read as that limit (250.01 said 250.0)."""
    for places in range(1, 5):
        if float(f"{tall:.{places}f}") > most:
            break
    return f"{tall:.{places}f}"


def require_height(name: str, tall: float, printer: Printer, height_param: str, height: float,
                   footprint: dict[str, object] | None = None, stack: str = "", *,
                   lowers: HeightInputs) -> None:
    """Refuse (DesignError on ``height_param`` = ``height``) a part ``name`` ``tall`` mm tall
    (``stack``: what makes it that tall, when more than the parameter) when ``printer`` prints
    less, offering each of the ``lowers`` inputs lowered until the
    part is as tall as the printer prints, where its spec accepts that; a build can check
    this before it spends time on the part."""
    if tall > printer.max_height:
        error = _beyond(DesignError(height_param, height, f"makes part '{name}' "
                                    f"{_above(tall, printer.max_height)} mm tall{stack}, more than the "
                                    f"{printer.max_height:g} mm printer '{printer.given or printer.name}' prints"),
                        printer).tied_to(footprint or {})
        total = sum(lowers.values.values())
        offered = [{input_name: lower} for input_name, value in lowers.values.items()
                   if (lower := lowered_height(value, total - value, printer.max_height)) is not None
                   and lowers.accepts({input_name: lower})]
        if offered:
            from wheelstep_cli.config.names import as_flags

            error = error.with_advice(" or ".join(f"use {as_flags(option)}" for option in offered), offered[0])
            error.remedies = offered
        raise error


def lowered_height(value: float, rest: float, most: float) -> float | None:
    """The value (mm, a whole number of tenths) of an input now ``value`` mm, on which ``rest``
    mm of the part stand (its hub), rounded down so that the part, its height held as its
    float32 mesh holds it, is at most ``most`` mm tall; None when no positive value does (the
    rest of the part alone is too tall)."""
    tenths = math.floor((most - rest) * 10.0 + 1e-6)
    while tenths > 0 and float(np.float32(rest + tenths / 10.0)) > most:
        tenths -= 1
    return tenths / 10.0 if tenths > 0 else None


def default_printer_said(err: DesignError, stl_only: bool = True, note: str | None = None) -> DesignError:
    """``err`` (a part larger than the printer prints) said of the default printer, which the
    user did not name: how to choose another, and (``stl_only``) that STL files need no bed
    (``note``: another way to say it, in brackets); its statements for the inputs sharing the
    blame carry the note too."""
    note = f" ({note or 'the default printer; --printer chooses another' + (', --format stl writes no plate' if stl_only else '')})"

    def noted(limit: str) -> str:
        # said of the printer the refusal names, before what it advises
        cause, written, advice = limit.partition(NOTHING_WRITTEN)
        return cause + note + written + advice

    sizes = {name: (value, noted(limit)) for name, (value, limit) in err.alternatives.items()}
    return err._with_extras(DesignError(err.param, err.value, noted(err.limit), sizes))


def _beyond(error: DesignError, printer: Printer) -> DesignError:
    """``error`` marked as a part larger than ``printer`` prints (its ``beyond_printer``: the
    printer's name), for a command that chose the printer itself to say so."""
    error.beyond_printer = printer.name
    return error


def pack_units(units: list[list[tuple[float, float]]], printer: Printer
               ) -> list[list[tuple[int, float, float, bool]]]:
    """Pack groups of parts (each a list of footprint sizes X, Y in mm) onto the printer's beds,
    the parts of a group side by side in a row on one bed (a gear pair stays together) when
    that row fits, else each on its own. Returns per group, per part: (bed, x, y, rotated),
    (x, y) the lower-left corner of the part's (possibly turned) box."""
    from wheelstep_cli.geometry.packing import fits_bed, pack_on_bed

    gap, edge = printer.margin, printer.edge_margin
    boxes, owners = [], []
    for u, sizes in enumerate(units):
        row = (sum(w for w, _ in sizes) + gap * (len(sizes) - 1), max(h for _, h in sizes))
        if len(sizes) > 1 and fits_bed(row, printer.bed, edge) is not None:
            boxes.append(row)
            owners.append((u, None))
        else:
            boxes.extend(sizes)
            owners.extend((u, k) for k in range(len(sizes)))
    placed: list[list] = [[None] * len(sizes) for sizes in units]
    for (u, k), spot in zip(owners, pack_on_bed(boxes, printer.bed, gap, edge)):
        if k is not None:
            placed[u][k] = (spot.bed, spot.x, spot.y, spot.rotated)
            continue
        offset, depth = 0.0, max(h for _, h in units[u])
        for k, (w, h) in enumerate(units[u]):
            # turned by +90 deg, the row's box (x, y) -> (depth - y, x) goes up instead of right
            corner = (spot.x + depth - h, spot.y + offset) if spot.rotated else (spot.x + offset, spot.y)
            placed[u][k] = (spot.bed, *corner, spot.rotated)
            offset += w + gap
    return placed


def bed_plates(parts, printer: Printer, metadata: list[dict[str, str]]) -> list[list[PlateObject]]:
    """The parts packed onto as few of the printer's beds as fit, side by side on one when
    they fit, each in its own frame with the build-item transform that places it."""
    sizes = [tuple(p.bounds[1, :2] - p.bounds[0, :2]) for p in parts]
    plates: dict[int, list[PlateObject]] = {}
    for part, meta, (bed, x, y, turned) in zip(parts, metadata, pack_units([sizes], printer)[0]):
        plates.setdefault(bed, []).append(
            placed_object(part.name, part.vertices, part.faces, (x, y), turned, meta))
    return [plates[bed] for bed in sorted(plates)]


#: What a plate says when its parts are laid out on a printer's bed but drawn as designed.
NOT_COMPENSATED = ("no: drawn as designed, laid out on this printer's bed with its slicer "
                   "settings; --printer also compensates holes, tooth clearance and first layer")


def plate_files(stem: str, plates: list[list[PlateObject]], printer: Printer,
                title: str, compensated: bool) -> dict[str, bytes]:
    """File name -> 3MF bytes: ``STEM.3mf`` for one plate, ``STEM-1.3mf``, ``STEM-2.3mf``, ...
    for more; each carries the printer's PrusaSlicer configuration and says whether the
    parts were drawn for that printer (``compensated``) or as designed."""
    from wheelstep_cli.formats.slicer_config import slic3r_config_bytes
    from wheelstep_cli.formats.threemf import threemf_bytes

    config = slic3r_config_bytes(printer.slicer_config(), f"wheelstep: printer {printer.name}")
    names = [f"{stem}.3mf"] if len(plates) == 1 else [f"{stem}-{i}.3mf" for i in range(1, len(plates) + 1)]
    meta = {"Title": title, "Application": "wheelstep", "printer": printer.name,
            "compensated": "yes" if compensated else NOT_COMPENSATED}
    return {name: threemf_bytes(objects, meta, config)
            for name, objects in zip(names, plates)}
