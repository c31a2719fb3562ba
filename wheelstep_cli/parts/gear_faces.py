"""The 2D faces of both gears (mm, each gear in its own frame): outline, holes, marks.

Provisional: a round bore of ``spec.bore`` (drawn as the solids cut it) and no marks yet.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from wheelstep_cli.geometry.planar import signed_area
from wheelstep_cli.geometry.solids import bore_segments, circle


@dataclass(frozen=True)
class GearFace:
    """One gear's top face: ``outline`` (N, 2) mm counter-clockwise, ``holes`` (bores, each
    (M, 2) mm clockwise) and ``marks`` (engraved timing marks, closed (K, 2) mm polylines),
    all in the gear's own frame (the meshing check's)."""

    name: str
    outline: np.ndarray
    holes: list[np.ndarray] = field(default_factory=list)
    marks: list[np.ndarray] = field(default_factory=list)


def _ccw(points: np.ndarray, ccw: bool = True) -> np.ndarray:
    """``points`` (N, 2) in the asked orientation."""
    points = np.asarray(points, dtype=float)
    return points if (signed_area(points) > 0) == ccw else points[::-1]


def _bore(diameter: float) -> list[np.ndarray]:
    """The bore as the solids cut it: the polygon circumscribing the nominal circle."""
    if diameter <= 0:
        return []
    segments = bore_segments(diameter)
    return [_ccw(circle(diameter / 2.0 / np.cos(np.pi / segments), segments), ccw=False)]


def gear_faces(pair) -> dict[str, GearFace]:
    """``{"pinion": GearFace, "wheel": GearFace}`` of a built
    :class:`~wheelstep_cli.parts.gear_pair.GearPair` (mm, own frames)."""
    bore = float(pair.spec.bore)
    return {name: GearFace(name, _ccw(outline), _bore(bore), [])
            for name, outline in (("pinion", pair.pinion_outline), ("wheel", pair.wheel_outline))}
