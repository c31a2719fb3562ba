"""Deterministic skyline packing of parts' XY bounding boxes onto as few beds as fit.

First-fit decreasing, bottom-left: boxes are taken tallest first; each goes on the
first bed where it fits, at the lowest (then leftmost) spot on that bed's skyline
(the upper edge of what is already placed), else on a new bed. A box is turned by
90 degrees when only that fits, or when turned its top ends lower on the skyline.
All in mm; ``margin`` is kept between boxes and to the bed edges.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace


@dataclass(frozen=True)
class Placement:
    """Where box ``key`` goes: bed index, lower-left corner (mm), turned by 90 degrees or not."""

    key: int
    bed: int
    x: float
    y: float
    rotated: bool


@dataclass
class _Bed:
    """Skyline of one bed: segments (x, width, y) covering the usable width, in inflated units."""

    skyline: list[list[float]] = field(default_factory=list)


class DoesNotFit(ValueError):
    """A box larger than the bed in both orientations; ``key`` names it."""

    def __init__(self, key: int, size: tuple[float, float], room: tuple[float, float]):
        self.key, self.size, self.room = key, size, room
        super().__init__(f"box {key} of {size[0]:.1f} x {size[1]:.1f} mm does not fit "
                         f"{room[0]:.1f} x {room[1]:.1f} mm")


def fits_bed(size: tuple[float, float], bed: tuple[float, float], margin: float) -> bool | None:
    """True if ``size`` fits as is, False if only turned, None if not at all."""
    room_x, room_y = bed[0] - 2 * margin, bed[1] - 2 * margin
    w, h = size
    if w <= room_x and h <= room_y:
        return True
    if h <= room_x and w <= room_y:
        return False
    return None


def pack_boxes(sizes: list[tuple[float, float]], bed: tuple[float, float],
               margin: float) -> list[Placement]:
    """Place boxes of ``sizes`` (width X, depth Y in mm) on beds; returns one Placement per box."""
    room_x, room_y = bed[0] - 2 * margin, bed[1] - 2 * margin
    boxes = []
    for key, size in enumerate(sizes):
        upright = fits_bed(size, bed, margin)
        if upright is None:
            raise DoesNotFit(key, size, (room_x, room_y))
        turnable = upright and size[1] <= room_x and size[0] <= room_y
        w, h = size if upright else size[::-1]
        boxes.append((key, w, h, not upright, turnable))
    # tallest first, then widest, then input order: deterministic
    boxes.sort(key=lambda b: (-round(max(b[1], b[2]), 6), -round(min(b[1], b[2]), 6), b[0]))
    # boxes are inflated by one margin; the usable region grows by one margin to match
    width, depth = room_x + margin, room_y + margin
    beds: list[_Bed] = []
    placed: list[Placement] = []
    for key, w, h, rotated, turnable in boxes:
        for index, bed in enumerate(beds + [_Bed([[0.0, width, 0.0]])]):
            options = [(w, h, rotated)] + ([(h, w, not rotated)] if turnable else [])
            best = None
            for bw, bh, turned in options:  # the orientation whose top ends lowest, then leftmost
                spot = _lowest_spot(bed.skyline, bw + margin, bh + margin, width, depth)
                if spot is not None:
                    rank = (round(spot[1] + bh, 6), round(spot[0], 6), turned != rotated)
                    if best is None or rank < best[0]:
                        best = (rank, spot, bw, bh, turned)
            if best is not None:
                break
        if index == len(beds):
            beds.append(bed)
        _, (x, y), bw, bh, turned = best
        _raise_skyline(bed.skyline, x, bw + margin, y + bh + margin)
        placed.append(Placement(key, index, margin + x, margin + y, turned))
    return sorted(placed, key=lambda p: p.key)


def pack_on_bed(sizes: list[tuple[float, float]], bed: tuple[float, float], gap: float,
                edge: float) -> list[Placement]:
    """:func:`pack_boxes` with ``gap`` mm between boxes and ``edge`` mm (at least ``gap``) from
    the bed edges, e.g. room for a skirt."""
    extra = max(0.0, edge - gap)
    inner = (bed[0] - 2.0 * extra, bed[1] - 2.0 * extra)
    return [replace(p, x=p.x + extra, y=p.y + extra) for p in pack_boxes(sizes, inner, gap)]


def _lowest_spot(skyline: list[list[float]], w: float, h: float, width: float, depth: float):
    """Bottom-left position (x, y) for a w x h box on the skyline, or None if it does not fit."""
    best = None
    for i, (x, _, _) in enumerate(skyline):
        if x + w > width + 1e-9:
            break
        y, j = 0.0, i
        while j < len(skyline) and skyline[j][0] < x + w - 1e-9:
            y = max(y, skyline[j][2])
            j += 1
        if y + h <= depth + 1e-9 and (best is None or (y, x) < best[::-1]):
            best = (x, y)
    return best


def _raise_skyline(skyline: list[list[float]], x: float, w: float, top: float) -> None:
    """Put a box spanning [x, x + w) with its top at ``top`` on the skyline (in place)."""
    new = []
    for sx, sw, sy in skyline:
        end = sx + sw
        if end <= x + 1e-9 or sx >= x + w - 1e-9:
            new.append([sx, sw, sy])
            continue
        if sx < x:
            new.append([sx, x - sx, sy])
        if end > x + w:
            new.append([x + w, end - (x + w), sy])
    new.append([x, w, top])
    new.sort(key=lambda s: s[0])
    merged = [new[0]]
    for seg in new[1:]:
        last = merged[-1]
        if abs(last[2] - seg[2]) < 1e-9 and abs(last[0] + last[1] - seg[0]) < 1e-9:
            last[1] += seg[1]
        else:
            merged.append(seg)
    skyline[:] = merged
