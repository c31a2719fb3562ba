"""Shaft holes and timing marks as 2D rings (mm, the gear's own frame), numpy only.

Every ring is counter-clockwise. A hole's straight features (flat, key, hex flat) face
the direction ``angle`` (rad); its round parts are circumscribed polygons so a shaft of
the nominal size fits.
"""

from __future__ import annotations

import numpy as np

#: DIN 6885-1 hub keyways: (largest bore mm, key width b mm, hub depth t2 mm).
DIN_6885 = ((8, 2, 1.0), (10, 3, 1.4), (12, 4, 1.8), (17, 5, 2.3), (22, 6, 2.8), (30, 8, 3.3),
            (38, 10, 3.3), (44, 12, 3.3), (50, 14, 3.8), (58, 16, 4.3), (65, 18, 4.4),
            (75, 20, 4.9), (85, 22, 5.4), (95, 25, 5.4), (110, 28, 6.4))
#: Mark engraving: stem width, arrowhead width and length, crossbar length (mm).
MARK_WIDTH, HEAD_WIDTH, HEAD_LENGTH, BAR_LENGTH = 0.8, 2.4, 2.0, 4.0


def din_6885_key(bore: float) -> tuple[float, float]:
    """Key width b and hub keyway depth t2 (mm) for a shaft of ``bore`` mm (DIN 6885-1)."""
    for limit, width, depth in DIN_6885:
        if bore <= limit:
            return float(width), float(depth)
    return float(DIN_6885[-1][1]), float(DIN_6885[-1][2])


def _turn(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def _arc(radius: float, start: float, stop: float, segments: int) -> np.ndarray:
    """Points on a circumscribed arc from ``start`` to ``stop`` rad (CCW), ends exact."""
    n = max(2, int(np.ceil((stop - start) / (2.0 * np.pi) * segments)))
    t = np.linspace(start, stop, n + 1)
    r = np.full_like(t, radius / np.cos(np.pi / segments))
    r[0] = r[-1] = radius
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def round_hole(diameter: float, segments: int, phase: float = 0.0) -> np.ndarray:
    """Polygon circumscribing a circle of ``diameter`` mm with ``segments`` sides, its first
    corner at polar angle ``phase`` (rad)."""
    r = diameter / 2.0 / np.cos(np.pi / segments)
    t = phase + np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    return r * np.column_stack([np.cos(t), np.sin(t)])


def d_flat_hole(diameter: float, depth: float, angle: float, segments: int) -> np.ndarray:
    """Round hole cut by a flat ``depth`` mm deep whose normal points along ``angle``."""
    r = diameter / 2.0
    half = float(np.arccos((r - depth) / r))
    return _turn(_arc(r, half, 2.0 * np.pi - half, segments), angle)


def keyway_hole(diameter: float, width: float, depth: float, angle: float,
                segments: int) -> np.ndarray:
    """Round hole with a keyway of ``width`` mm reaching ``depth`` mm beyond the bore
    (DIN 6885 t2) along ``angle``."""
    r = diameter / 2.0
    half = float(np.arcsin(width / 2.0 / r))
    arc = _arc(r, half, 2.0 * np.pi - half, segments)
    top = r + depth
    slot = np.array([[top, -width / 2.0], [top, width / 2.0]])
    return _turn(np.vstack([arc, slot]), angle)


def hex_hole(across_flats: float, angle: float) -> np.ndarray:
    """Hexagon of ``across_flats`` mm with one flat's normal along ``angle``."""
    t = angle + np.pi / 6.0 + np.arange(6) * np.pi / 3.0
    r = across_flats / 2.0 / np.cos(np.pi / 6.0)
    return r * np.column_stack([np.cos(t), np.sin(t)])


def arrow_mark(inner: float, outer: float, angle: float, bar: bool = False) -> np.ndarray:
    """An arrow from radius ``inner`` to ``outer`` mm pointing along ``angle``; ``bar``: with a
    crossbar at its foot (the wheel's carrier reference). One simple CCW polygon (mm)."""
    hw, hh = MARK_WIDTH / 2.0, HEAD_WIDTH / 2.0
    neck = outer - HEAD_LENGTH
    arrow = [(neck, -hw), (neck, -hh), (outer, 0.0), (neck, hh), (neck, hw)]
    if bar:
        cl = BAR_LENGTH / 2.0
        foot = [(inner, -cl), (inner + MARK_WIDTH, -cl), (inner + MARK_WIDTH, -hw)]
        back = [(inner + MARK_WIDTH, hw), (inner + MARK_WIDTH, cl), (inner, cl)]
        points = foot + arrow + back
    else:
        points = [(inner, -hw)] + arrow + [(inner, hw)]
    return _turn(np.array(points, dtype=float), angle)


#: Metric set screws with a hex nut: size -> (clearance hole d, nut across flats, nut height) mm
#: (ISO 4032 nuts; the pocket adds PRINT_PLAY).
SET_SCREWS = {"M2": (2.2, 4.0, 1.6), "M2.5": (2.7, 5.0, 2.0), "M3": (3.2, 5.5, 2.4),
              "M4": (4.3, 7.0, 3.2), "M5": (5.3, 8.0, 4.7), "M6": (6.4, 10.0, 5.2)}
#: Play (mm) added round the nut pocket so the nut slides in.
PRINT_PLAY = 0.3


def teardrop(diameter: float, segments: int = 32) -> np.ndarray:
    """A horizontal hole's cross-section (CCW, mm, y up): the circle with a 45 deg point on
    top, so its roof prints without support."""
    r = diameter / 2.0
    t = np.linspace(np.pi * 0.75, np.pi * 2.25, segments)
    return np.vstack([[0.0, r * np.sqrt(2.0)], r * np.column_stack([np.cos(t), np.sin(t)])])
