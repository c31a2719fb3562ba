"""``print-sheet.md``: what the person at the printer needs, in one page of Markdown."""

from __future__ import annotations

from collections import Counter

#: extrusion width as a multiple of the nozzle diameter (PrusaSlicer's default is about 1.125)
LINE_WIDTH_FACTOR = 1.125


def _fraction(value, default: float) -> float:
    """'30%' or 0.3 or 30 -> 0.3."""
    if value is None:
        return default
    text = str(value).strip()
    try:
        number = float(text.rstrip("%"))
    except ValueError:
        return default
    return number / 100.0 if text.endswith("%") or number > 1 else number


def _number(value, default: float) -> float:
    try:
        return float(str(value).split()[0])
    except (ValueError, IndexError):
        return default


def estimated_mass(part, printer) -> float:
    """Printed mass in g: solid shells (perimeters, top/bottom layers) plus infill of the rest.

    For a plate-like part of height H, mean section A = V/H and footprint perimeter P:
    shell = P * perimeters * line width * H + A * (top + bottom layers) * layer height,
    capped at V; mass = density * (shell + infill * (V - shell)). Resin parts print solid.
    """
    volume = part.volume
    settings = printer.slicer
    if printer.technology != "fdm":
        return volume / 1000.0 * printer.density * _fraction(settings.get("fill_density"), 1.0)
    height = float(part.bounds[1, 2] - part.bounds[0, 2])
    area = volume / height
    width = _number(settings.get("nozzle_diameter"), 0.4) * LINE_WIDTH_FACTOR
    layer = _number(settings.get("layer_height"), 0.2)
    layers = _number(settings.get("top_solid_layers"), 4) + _number(settings.get("bottom_solid_layers"), 4)
    shell = min(volume, part.perimeter * _number(settings.get("perimeters"), 2) * width * height
                + area * layers * layer)
    infill = _fraction(settings.get("fill_density"), 0.2)
    return (shell + infill * (volume - shell)) / 1000.0 * printer.density


def print_sheet_bytes(plan, plates, built, results, failed) -> bytes:
    """The print sheet: parts and quantities, volumes and masses, plates, slicer settings, failures."""
    lines = [f"# Print sheet: {plan.file.name}", ""]
    if plan.description:
        lines += [plan.description, ""]
    total_parts = sum(len(p.items) for p in plates)
    lines += [f"{len(built)} of {len(plan.entries)} entries built, {total_parts} parts on "
              f"{len(plates)} plate{'s' if len(plates) != 1 else ''}.", ""]
    if failed:
        lines += ["## Not built", "", "| entry | where | reason |", "| --- | --- | --- |"]
        for entry, where, reason in failed:
            lines.append(f"| {entry.name} | {plan.file.name}:{where.rsplit(':', 1)[1]} | {reason} |")
        lines.append("")

    lines += ["## Parts", "",
              "| entry | part | design | printer | qty | volume (cm3) | solid mass (g) | est. printed mass (g) "
              "| size X x Y x Z (mm) | checks |",
              "| --- | --- | --- | --- | ---: | ---: | ---: | ---: | --- | --- |"]
    totals: Counter = Counter()
    for entry in built:
        for part in results[entry.index].parts:
            size = part.bounds[1] - part.bounds[0]
            solid = part.volume / 1000.0 * entry.printer.density
            mass = estimated_mass(part, entry.printer)
            totals[entry.printer.name, "solid"] += solid * entry.quantity
            totals[entry.printer.name, "mass"] += mass * entry.quantity
            ok = "printable" if all(part.checks.values()) else "FAILED"
            lines.append(f"| {entry.name} | {part.name} | {entry.design_label} | {entry.printer.name} | "
                         f"{entry.quantity} | {part.volume / 1000:.2f} | {solid:.1f} | {mass:.1f} | "
                         f"{size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} | {ok} |")
    lines.append("")
    printers = list(dict.fromkeys(p.printer.name for p in plates))
    for name in printers:
        printer = next(p.printer for p in plates if p.printer.name == name)
        lines.append(f"Total for {name} ({printer.material}, {printer.density:g} g/cm3): "
                     f"{totals[name, 'mass']:.0f} g estimated printed, {totals[name, 'solid']:.0f} g if solid.")
    lines += ["", "Masses: solid = volume x density; estimated = perimeters and top/bottom layers "
              "solid, the rest at the profile's infill.", ""]

    lines += ["## Plates", ""]
    for plate in plates:
        printer = plate.printer
        lines += [f"### {plate.stem}.3mf: {printer.name} ({printer.material}, bed "
                  f"{printer.bed[0]:g} x {printer.bed[1]:g} mm)", "",
                  f"![{plate.stem}]({plate.stem}.png)", ""]
        counts = Counter(f"{i.entry} {i.part.name}" for i in plate.items)
        for label, count in counts.items():
            lines.append(f"- {count} x {label}")
        lines.append("")

    lines += ["## Printer profiles and recommended slicer settings", ""]
    seen = []
    for entry in plan.entries:
        if entry.printer.name in seen:
            continue
        seen.append(entry.printer.name)
        printer = entry.printer
        lines += [f"### {printer.name}", "", printer.description, "",
                  f"Geometry already compensated in the meshes: bores +{printer.hole_compensation:g} mm, "
                  f"tooth clearance +{printer.tooth_clearance:g} mm, bed-side edges inset "
                  f"{printer.elephant_foot_inset:g} mm over the lowest {printer.elephant_foot_height:g} mm "
                  "(elephant foot). Do not compensate again in the slicer.", "",
                  "| setting | value |", "| --- | --- |"]
        lines += [f"| {key} | {value} |" for key, value in printer.slicer.items()]
        lines.append("")
    return "\n".join(lines).encode("utf-8")
