"""What ``wheelstep trajectory`` computes and reports (SPEC §8): the foot path from its
support segment and three tangent arcs, sampled, as plain data (mm; arc angles in degrees)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.mechanism import trajectory as tr

#: The pieces of the path in order (counter-clockwise), and the points the report lists.
PIECE_NAMES = ("AD", "arc_r2", "arc_r3", "arc_r1")
POINT_NAMES = ("A", "D", "C", "B", "O1", "O2", "O3")


@dataclass(frozen=True)
class TrajectoryStudy:
    """The path, its samples (N, 2) mm ``spacing`` apart and each sample's piece index."""

    path: tr.FootPath
    points: np.ndarray
    pieces: np.ndarray
    given: str                # "h_max" or "r3": which one the top arc was found from

    @property
    def case(self) -> str:
        return "symmetric" if self.path.r1 == self.path.r2 else "general"


#: Most points a path is sampled into (count).
MAX_POINTS = 1_000_000


def trajectory_study(support_length: float, r1: float, r2: float | None, r3: float | None,
                     h_max: float | None, x0: float, y0: float, root: str,
                     spacing: float) -> TrajectoryStudy:
    """Compose and sample the path: ``r2`` defaults to ``r1``; give ``r3`` or the clearance
    ``h_max`` (100 mm if neither), not both; samples ``spacing`` mm apart."""
    r2 = r1 if r2 is None else r2
    if r3 is None and h_max is None:
        h_max = 100.0
    require(r3 is None or h_max is None, "h-max", h_max, "give either --r3 or --h-max, not both")
    require(spacing > 0, "spacing", spacing, "must be > 0 mm")
    path = tr.foot_path(support_length, r1, r2, r3=r3, h_max=h_max, x0=x0, y0=y0, root=root)
    if path.length / spacing > MAX_POINTS:
        # the sizes make the path that long: the line names the one the user gave
        raise DesignError("spacing", spacing, f"gives over a million points along the "
                          f"{path.length:.4g} mm path; must be >= {_up(path.length / MAX_POINTS)} mm"
                          ).tied_to({"support_length": support_length, "r1": r1, "r2": r2, "r3": r3,
                                     "h_max": h_max})
    points, pieces = tr.sample_path(path, spacing)
    return TrajectoryStudy(path, points, pieces, "h_max" if r3 is None else "r3")


def _up(value: float) -> str:
    """A positive lower limit to 3 significant digits, rounded up (so that it passes)."""
    unit = 10.0 ** (math.floor(math.log10(value)) - 2)
    return f"{math.ceil(value / unit - 1e-9) * unit:.3g}"


def _point(p) -> list[float]:
    return [float(p[0]), float(p[1])]


def _piece(piece) -> dict:
    if hasattr(piece, "radius"):
        return {"center_mm": _point(piece.center), "radius_mm": piece.radius,
                "start_deg": float(np.degrees(piece.start)), "sweep_deg": float(np.degrees(piece.sweep))}
    return {"start_mm": _point(piece.start), "end_mm": _point(piece.end)}


def trajectory_report(study: TrajectoryStudy) -> dict:
    """Case, inputs, the named points, each piece and the path length."""
    path = study.path
    return {
        "case": study.case, "given": study.given,
        "support_length_mm": path.support_length, "y0_mm": path.y0,
        "r1_mm": path.r1, "r2_mm": path.r2, "r3_mm": path.r3, "h_max_mm": path.h_max,
        "points_mm": {k: _point(getattr(path, k)) for k in POINT_NAMES},
        "pieces": [{"name": n, "length_mm": p.length, **_piece(p)}
                   for n, p in zip(PIECE_NAMES, path.pieces)],
        "path_length_mm": path.length, "samples": int(study.points.shape[0]),
    }
