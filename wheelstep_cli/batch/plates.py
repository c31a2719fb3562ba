"""Plates: every built part times its quantity packed onto the beds of its printer, and each
plate as 3MF (with the parts' metadata) and as a top-view picture."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.batch.build import BuiltPart, EntryResult
from wheelstep_cli.batch.plan import Entry
from wheelstep_cli.config.printers import Printer


@dataclass
class PlacedPart:
    label: str
    entry: str
    part: BuiltPart
    x: float          # translation on the bed, mm
    y: float
    rotated: bool
    metadata: dict[str, str]

    def vertices(self) -> np.ndarray:
        v = self.part.vertices
        return np.column_stack([-v[:, 1], v[:, 0], v[:, 2]]) if self.rotated else v

    def footprint(self) -> list[list[np.ndarray]]:
        turn = (lambda r: np.column_stack([-r[:, 1], r[:, 0]])) if self.rotated else (lambda r: r)
        return [[turn(r) + (self.x, self.y) for r in polygon] for polygon in self.part.footprint]


@dataclass
class Plate:
    number: int
    printer: Printer
    items: list[PlacedPart]

    @property
    def stem(self) -> str:
        return f"plate-{self.number}"


def plate_threemf(plate: Plate) -> tuple[int, bytes]:
    """(plate number, 3MF bytes) of a packed plate (worker-process entry point)."""
    from wheelstep_cli.formats.threemf import PlateObject, threemf_bytes

    objects = []
    for item in plate.items:
        vertices = item.vertices()
        lo = vertices.min(axis=0)
        objects.append(PlateObject(item.label, vertices, item.part.faces,
                                   (item.x - lo[0], item.y - lo[1], -lo[2]), item.metadata))
    printer = plate.printer
    return plate.number, threemf_bytes(objects, {
        "Title": f"wheelstep {plate.stem} ({printer.name})", "Application": "wheelstep batch",
        "printer": printer.name, "material": printer.material})


def plate_picture(plate: Plate) -> bytes:
    """Top-view PNG of a packed plate: the bed with the parts' footprints."""
    from wheelstep_cli.render.plate_png import plate_png

    shapes = []
    for item in plate.items:
        polygons = item.footprint()
        lo = np.min([r.min(axis=0) for p in polygons for r in p], axis=0)
        label = item.label.replace(" ", "\n", 1)  # entry name over part name
        shapes.append((label, [[r - lo + (item.x, item.y) for r in p] for p in polygons]))
    printer = plate.printer
    return plate_png(printer.bed, printer.margin, shapes,
                     f"{plate.stem}: {printer.name} ({printer.bed[0]:g} x {printer.bed[1]:g} mm), "
                     f"{len(plate.items)} parts")


def _metadata(entry: Entry, part: str, copy: int) -> dict[str, str]:
    """3MF metadata of one placed part: where it comes from and its design parameters."""
    meta = {"entry": entry.name, "kind": entry.kind, "part": part, "copy": f"{copy} of {entry.quantity}",
            "design_profile": entry.design_label, "printer_profile": entry.printer.name}
    for name, value in entry.printed.model_dump().items():
        if value is not None:
            meta[f"design.{name}"] = f"{value:g}" if isinstance(value, float) else str(value)
    for name, value in entry.printer.geometry().items():
        meta[f"printer.{name}"] = f"{value:g}"
    return meta


def plan_plates(entries: list[Entry], results: dict[int, EntryResult]) -> tuple[list[Plate], dict[int, str]]:
    """Pack every built part times its quantity onto beds, per printer.

    Returns the plates (numbered across printers in order of first use) and, per entry
    index, the reason an entry had to be dropped (a part larger than the bed).
    """
    from wheelstep_cli.geometry.packing import pack_boxes

    dropped = too_big(entries, results)
    plates: list[Plate] = []
    order = list(dict.fromkeys((e.printer.name, e.printer.sha256) for e in entries))
    for printer_key in order:
        items: list[tuple[Entry, BuiltPart, int]] = []
        for entry in entries:
            result = results[entry.index]
            if (entry.printer.name, entry.printer.sha256) != printer_key or result.error \
                    or entry.index in dropped:
                continue
            for copy in range(1, entry.quantity + 1):
                items.extend((entry, part, copy) for part in result.parts)
        if not items:
            continue
        printer = items[0][0].printer
        sizes = [tuple(p.bounds[1, :2] - p.bounds[0, :2]) for _, p, _ in items]
        placements = pack_boxes(sizes, printer.bed, printer.margin)
        beds: dict[int, list[PlacedPart]] = {}
        for (entry, part, copy), spot in zip(items, placements):
            label = f"{entry.name} {part.name}" + (f" #{copy}" if entry.quantity > 1 else "")
            beds.setdefault(spot.bed, []).append(PlacedPart(
                label, entry.name, part, spot.x, spot.y, spot.rotated, _metadata(entry, part.name, copy)))
        for bed in sorted(beds):
            plates.append(Plate(len(plates) + 1, printer, beds[bed]))
    return plates, dropped


def too_big(entries: list[Entry], results: dict[int, EntryResult]) -> dict[int, str]:
    """Entry index -> why it is left out: a built part larger than its printer's bed."""
    from wheelstep_cli.geometry.packing import fits_bed

    dropped: dict[int, str] = {}
    for entry in entries:
        result = results[entry.index]
        if result.error:
            continue
        printer = entry.printer
        for part in result.parts:
            size = part.bounds[1, :2] - part.bounds[0, :2]
            if fits_bed(tuple(size), printer.bed, printer.margin) is None:
                dropped[entry.index] = (
                    f"part '{part.name}' ({size[0]:.1f} x {size[1]:.1f} mm) does not fit the bed of "
                    f"printer '{printer.name}' ({printer.bed[0]:g} x {printer.bed[1]:g} mm with "
                    f"{printer.margin:g} mm margins)")
                break
    return dropped
