"""Printed mass of a part: solid shells plus infill, from the printer profile's slicer settings."""

from __future__ import annotations

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


def solid_mass(part, printer) -> float:
    """Mass in g of the part printed solid: volume (mm^3) x density (g/cm3)."""
    return part.volume / 1000.0 * printer.density


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
    width = printer.nozzle * LINE_WIDTH_FACTOR
    layer = _number(settings.get("layer_height"), 0.2)
    layers = _number(settings.get("top_solid_layers"), 4) + _number(settings.get("bottom_solid_layers"), 4)
    shell = min(volume, part.perimeter * _number(settings.get("perimeters"), 2) * width * height
                + area * layers * layer)
    infill = _fraction(settings.get("fill_density"), 0.2)
    return (shell + infill * (volume - shell)) / 1000.0 * printer.density


def masses(built, results) -> dict[tuple[int, str], tuple[float, float]]:
    """(entry index, part name) -> (solid mass, estimated printed mass) in g, per built entry."""
    return {(entry.index, part.name): (solid_mass(part, entry.printer), estimated_mass(part, entry.printer))
            for entry in built for part in results[entry.index].parts}
