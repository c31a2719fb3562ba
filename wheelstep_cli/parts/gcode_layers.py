"""The parts a PrusaSlicer G-code file prints, read back layer by layer (SPEC §11): the
external perimeters of a layer, offset outward by half their extrusion width (an exact
polygon offset), grouped into parts with their holes; and how tall a part is printed.
Lengths in mm (on the bed).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from wheelstep_cli.errors import DesignError, file_problem
from wheelstep_cli.formats.gcode import GcodeLayers, read_gcode
from wheelstep_cli.geometry.planar import offset_outline, points_inside, prepared_polygon, signed_area


@dataclass(frozen=True)
class PrintedPart:
    """One printed part of a layer: the outer outline and holes (bed mm) as printed (the
    external perimeters offset by half ``width``), from G-code ``source`` at height ``z``."""

    source: str
    z: float
    width: float
    outline: np.ndarray
    holes: tuple

    @property
    def area(self) -> float:
        return signed_area(self.outline) - sum(abs(signed_area(h)) for h in self.holes)


def read_gcode_file(path: Path) -> GcodeLayers:
    """The external perimeters of a PrusaSlicer G-code file (DesignError naming ``gcode``)."""
    if not path.is_file():
        raise DesignError("gcode", str(path), file_problem(path))
    try:
        text = path.read_text(errors="replace")
    except OSError as err:
        raise DesignError("gcode", str(path), f"cannot be read ({err.strerror or err})") from None
    return read_gcode(text, str(path))


def require_gcode_files(paths: list[Path]) -> None:
    """Refuse (DesignError naming ``gcode``) a missing file, or one that is not a whole
    PrusaSlicer G-code file, reading only its head and tail: before any plate is read."""
    from wheelstep_cli.formats.gcode import check_prusaslicer

    for path in paths:
        if not path.is_file():
            raise DesignError("gcode", str(path), file_problem(path))
        try:
            size = path.stat().st_size
            with open(path, "rb") as handle:
                head = handle.read(2000)
                handle.seek(max(0, size - 200000))
                tail = handle.read()
        except OSError as err:
            raise DesignError("gcode", str(path), file_problem(path, err)) from None
        check_prusaslicer(head.decode(errors="replace") + "\n" + tail.decode(errors="replace"), str(path))


def _setting_mm(layers: GcodeLayers, key: str) -> float:
    """A layer height the slicer's config comments state (mm; PrusaSlicer's 0.2 when absent)."""
    return float(layers.config.get(key) or 0.2)


def mid_layer(layers: GcodeLayers, height: float, source: str = "gcode") -> float:
    """The layer (its top z, mm) whose middle is nearest to ``height`` mm."""
    if not layers.layers:
        raise DesignError("gcode", source, "has no external perimeter on any layer (nothing an "
                                           "outline can be read from)")
    step = _setting_mm(layers, "layer_height")
    return min(layers.heights(), key=lambda z: abs(z - 0.5 * step - height))


def printed_parts(layers: GcodeLayers, source: str, height: float) -> list[PrintedPart]:
    """The parts printed at ``height`` mm above the bed: each outermost loop with the loops
    inside it (its holes), offset by half their extrusion width away from the material."""
    z = mid_layer(layers, height, source)
    loops = [(np.asarray(loop.points, float), loop.width) for loop in layers.layers[z]]
    loops = [(p if signed_area(p) > 0 else p[::-1], w) for p, w in loops if abs(signed_area(p)) > 1e-6]
    loops.sort(key=lambda item: -signed_area(item[0]))
    shells: list[tuple] = []
    for points, width in loops:
        owner = next((s for s in shells if points_inside(s[2], points[:1])[0]), None)
        try:
            printed = offset_outline(points, 0.5 * width if owner is None else -0.5 * width, "gcode")
        except DesignError:
            continue    # a loop crossing itself is no gear outline (a gear's is then not found)
        if owner is None:
            shells.append((printed, width, prepared_polygon(points), []))
        else:
            owner[3].append(printed)
    return [PrintedPart(source, z, width, outline, tuple(holes)) for outline, width, _, holes in shells]


def printed_height(layers: GcodeLayers, axis: np.ndarray) -> float:
    """How tall (mm) the part printed round the point ``axis`` (bed mm, its gear's axis) is:
    from below its lowest layer with a loop round the axis (the first layer's height on the
    bed, a layer's on a raft) to its highest (a hub's top on a hub, the face elsewhere)."""
    point = np.asarray(axis, float).reshape(1, 2)

    def round_axis(points: np.ndarray) -> bool:
        lo, hi = points.min(axis=0), points.max(axis=0)
        return bool(np.all(lo <= point[0]) and np.all(point[0] <= hi)
                    and points_inside(prepared_polygon(points), point)[0])

    heights = [z for z, loops in layers.layers.items() if any(round_axis(loop.points) for loop in loops)]
    if not heights:
        return 0.0
    first, step = _setting_mm(layers, "first_layer_height"), _setting_mm(layers, "layer_height")
    lowest = min(heights)
    return max(heights) - lowest + (first if lowest == min(layers.heights()) and not
                                    float(layers.config.get("raft_layers") or 0) else step)


def require_height(part: PrintedPart, layers: GcodeLayers, axis: np.ndarray, height: float, gear: str,
                   pair: str) -> None:
    """DesignError naming the G-code when its ``part`` (its gear's axis at ``axis``, bed mm) is
    not printed ``height`` mm tall (to a layer): a pair of another thickness, whose sections
    are alike (a preset on two printers), fits the outline but is another design."""
    step = max(_setting_mm(layers, "layer_height"), _setting_mm(layers, "first_layer_height"), 0.05)
    printed = printed_height(layers, axis)
    if abs(printed - height) > step + 1e-6:
        raise DesignError("gcode", part.source, f"prints the {gear} {printed:g} mm tall, the {gear} of "
                                                f"pair '{pair}' is {height:g} mm: sliced from another "
                                                "design (or scaled on the bed)")
