"""Plates: every built part times its quantity packed onto the beds of its printer, and each
plate as 3MF (parts in their own frames, placed by build-item transforms, with their design
in the object metadata and the printer's PrusaSlicer configuration) and as a top-view picture."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.batch.build import BuiltPart, EntryResult
from wheelstep_cli.batch.plan import Entry
from wheelstep_cli.config.printers import Printer
from wheelstep_cli.errors import counted
from wheelstep_cli.parts.plate_layout import design_metadata, pack_units, size_problem


@dataclass
class PlacedPart:
    label: str
    entry: str
    part: BuiltPart
    x: float          # translation on the bed, mm
    y: float
    rotated: bool
    metadata: dict[str, str]

    def plate_object(self):
        """The part in its own frame with the build-item transform that places it."""
        from wheelstep_cli.formats.threemf import placed_object

        return placed_object(self.label, self.part.vertices, self.part.faces, (self.x, self.y),
                             self.rotated, self.metadata)

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
    from wheelstep_cli.formats.slicer_config import slic3r_config_bytes
    from wheelstep_cli.formats.threemf import threemf_bytes

    printer = plate.printer
    config = slic3r_config_bytes(printer.slicer_config(), f"wheelstep batch: printer {printer.name}")
    return plate.number, threemf_bytes([item.plate_object() for item in plate.items], {
        "Title": f"wheelstep {plate.stem} ({printer.name})", "Application": "wheelstep batch",
        "printer": printer.name, "material": printer.material}, config)


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
    return plate_png(printer.bed, printer.edge_margin, shapes,
                     f"{plate.stem}: {printer.name} ({printer.bed[0]:g} x {printer.bed[1]:g} mm), "
                     + counted(len(plate.items), "part", "parts"))


def _metadata(entry: Entry, result: EntryResult, part: str, copy: int) -> dict[str, str]:
    """3MF metadata of one placed part: where it comes from, its parameters as printed and
    the printer geometry that changed it (a fitted pair's: no tooth clearance, its inset)."""
    from wheelstep_cli.batch.outputs import printed_values, printer_geometry

    meta = {"entry": entry.name, "kind": entry.kind, "part": part, "copy": f"{copy} of {entry.quantity}",
            "design_profile": entry.design_label, "printer_profile": entry.printer.name}
    if entry.kind == "gear-pair":
        meta["pair"] = f"{entry.name}/{copy}"
    if entry.kind == "gear-pair":   # where it is mounted, for mesh-check of the plate
        from wheelstep_cli.parts.gear_laws import distance_record, law_csv_metadata

        # the distances as the design gives them (a module resolves the rolling distance:
        # it is not stored beside it), whatever the report resolved
        values = {k: v for k, v in printed_values(entry, result).items()
                  if k not in ("center_distance", "install_distance")}
        meta.update(design_metadata({**values, **distance_record(entry.printed)}))
        meta.update(law_csv_metadata(entry.printed))
    else:
        meta.update(design_metadata(printed_values(entry, result)))
    geometry = printer_geometry(entry, result)
    if "outline_inset" in geometry:   # a fit's, not the printer's: named as `gears --fit` names it
        meta["outline_inset"] = f"{geometry.pop('outline_inset'):.12g}"
    for name, value in geometry.items():
        meta[f"printer.{name}"] = f"{value:g}"
    return meta


def plan_plates(entries: list[Entry], results: dict[int, EntryResult]) -> tuple[list[Plate], dict[int, str]]:
    """Pack every built part times its quantity onto beds, per printer (each copy of a gear
    pair side by side on one bed when it fits there).

    Returns the plates (numbered across printers in order of first use) and, per entry
    index, the reason an entry had to be dropped (a part larger or taller than the bed).
    """
    dropped = too_big(entries, results)
    plates: list[Plate] = []
    order = list(dict.fromkeys((e.printer.name, e.printer.sha256) for e in entries))
    for printer_key in order:
        units: list[tuple[Entry, int]] = [
            (entry, copy) for entry in entries
            if (entry.printer.name, entry.printer.sha256) == printer_key
            and not results[entry.index].error and entry.index not in dropped
            for copy in range(1, entry.quantity + 1)]
        if not units:
            continue
        printer = units[0][0].printer
        sizes = [[tuple(p.bounds[1, :2] - p.bounds[0, :2]) for p in results[e.index].parts]
                 for e, _ in units]
        beds: dict[int, list[PlacedPart]] = {}
        for (entry, copy), spots in zip(units, pack_units(sizes, printer)):
            for part, (bed, x, y, turned) in zip(results[entry.index].parts, spots):
                label = f"{entry.name} {part.name}" + (f" #{copy}" if entry.quantity > 1 else "")
                beds.setdefault(bed, []).append(PlacedPart(
                    label, entry.name, part, x, y, turned, _metadata(entry, results[entry.index], part.name, copy)))
        for bed in sorted(beds):
            plates.append(Plate(len(plates) + 1, printer, beds[bed]))
    return plates, dropped


def too_big(entries: list[Entry], results: dict[int, EntryResult]) -> dict[int, str]:
    """Entry index -> why it is left out: a built part larger or taller than its printer's bed."""
    dropped: dict[int, str] = {}
    for entry in entries:
        result = results[entry.index]
        if result.error:
            continue
        for part in result.parts:
            problem = size_problem(part.name, part.bounds, entry.printer)
            if problem is not None:
                dropped[entry.index] = problem
                break
    return dropped
