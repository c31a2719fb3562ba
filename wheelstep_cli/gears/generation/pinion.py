"""The pinion: cut by the rolling rack as polygon booleans, tips rounded, pointed teeth topped.

Angles in radians, lengths in mm.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.generation.envelope import PolarGrid, outline_from_radii
from wheelstep_cli.gears.generation.outline import polar_sweep
from wheelstep_cli.gears.generation.rack import (RackCutter, RackRolling, RackTeeth, rack_poses,
                                                 rack_tooth_polygons)
from wheelstep_cli.gears.threads import thread_map
from wheelstep_cli.geometry.planar import (grown_minus_rotated_union, intersect_outlines, open_outline,
                                          polygon_union)


#: Piles of consecutive rack poses united separately (on threads), then together.
UNION_PILES = 2


def pinion_by_rack(rolling: RackRolling, cutter: RackCutter, module: float) -> np.ndarray:
    """Pinion outline (N, 2, CCW, mm) = blank minus the union of every rack-tooth pose (exact).

    The rack rolls on ``rolling.curve``, pivots at its corner and has its teeth tilted
    by -tilt mu (see :func:`~wheelstep_cli.gears.generation.rack.rack_poses`); polygon
    booleans let teeth that lean over their neighbours' spaces keep their true shape,
    which a polar ray map cannot hold. The blank is the pitch curve grown by the
    addendum (``cutter.addendum`` x ``module`` mm).
    """
    polygons, centres = rack_tooth_polygons(cutter, module, rolling.pitch)
    k = polygons.shape[1]
    teeth = RackTeeth(polygons.reshape(-1, 2), np.repeat(centres, k))
    worlds = rack_poses(rolling, teeth)
    pieces = np.concatenate([w.reshape(-1, len(centres), k, 2).reshape(-1, k, 2) for w in worlds])
    # one period's cutter region, then its rotated copies (a union of all poses at once costs more)
    angles = np.sign(polar_sweep(rolling.curve)) * rolling.period_angle * np.arange(rolling.copies)
    curve = rolling.curve
    body = np.concatenate([curve[:-1] @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
                           for a in angles])
    # the poses' union in UNION_PILES piles of consecutive poses on threads (a fixed count,
    # so the outline does not depend on the machine's cores)
    regions = list(thread_map(polygon_union, np.array_split(pieces, UNION_PILES)))
    # bevel joins: a chord across each pitch-curve corner relieves the corner teeth's tips
    return grown_minus_rotated_union(body, cutter.addendum * module, regions, angles)


def round_tips(outline: np.ndarray, radius: float, thin: float) -> np.ndarray:
    """The outline (N, 2, mm) with its convex corners (tooth tips) rounded to ``radius`` mm.

    An opening (erode, then dilate) changes nothing else. The outline is first thinned
    by ``thin`` mm (Douglas-Peucker), a fraction of a micron: a boolean's many collinear
    points slow the buffers down.
    """
    if radius <= 0:
        return outline
    return open_outline(outline, radius, thin=thin, quad_segs=8)


def topped_outline(outline: np.ndarray, grid: PolarGrid, topped: np.ndarray, before: np.ndarray,
                   copies: int) -> np.ndarray:
    """The exact outline (N, 2) mm cut down to the topped radii (mm per ray of ``grid``).

    Only rays a topping lowered (``topped`` below ``before``) are cut; ``copies``
    periods make the turn.
    """
    lowered = topped < before - 1e-12
    if not lowered.any():
        return outline
    cap = np.where(lowered, topped, 10.0 * float(before.max()))
    return intersect_outlines(outline, outline_from_radii(grid, cap, copies))

