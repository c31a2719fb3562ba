"""Checks a mesh must pass before it is written: closed, consistently wound, expected volume.

A :class:`Part` is a triangle mesh in mm with the volume its outline says it must have;
the checks are plain numpy, so they hold whatever engine made the mesh.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import MeshDefect


@dataclass(frozen=True)
class Part:
    """A printable triangle mesh in mm with its name and the volume it should have."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    expected_volume: float

    @property
    def bounds(self) -> np.ndarray:
        """[[xmin, ymin, zmin], [xmax, ymax, zmax]] in mm."""
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])


@dataclass(frozen=True)
class MeshReport:
    """What the pre-write mesh check found."""

    watertight: bool
    winding_consistent: bool
    volume: float
    expected_volume: float
    triangles: int

    @property
    def volume_error(self) -> float:
        return abs(self.volume - self.expected_volume) / self.expected_volume

    @property
    def ok(self) -> bool:
        return (self.watertight and self.winding_consistent and self.volume > 0
                and self.volume_error < VOLUME_TOLERANCE)


VOLUME_TOLERANCE = 1e-3


def check_part(part: Part) -> MeshReport:
    """Check a part is printable: watertight, consistently wound, expected positive volume.

    Checked as a strict reader reads the written file: vertices that coincide once written
    (float32, as STL stores them) are merged first, and a triangle that then repeats a vertex
    (zero area) fails the check. Watertight: every undirected edge is shared by exactly two
    triangles. Consistent winding: those two triangles traverse it in opposite directions.
    """
    faces = _welded(part.vertices, np.asarray(part.faces, dtype=np.int64))
    zero_area = bool(np.any((faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2])
                            | (faces[:, 0] == faces[:, 2])))
    start, end = faces.ravel(), np.roll(faces, -1, axis=1).ravel()
    # an edge (a, b) as the one integer a * n + b: a flat sort is much cheaper than a row-wise unique
    n = int(faces.max()) + 1 if len(faces) else 1
    undirected = np.minimum(start, end) * n + np.maximum(start, end)
    watertight = bool(len(faces) > 0 and not zero_area and np.all(_uses(undirected) == 2))
    winding = bool(watertight and np.all(_uses(start * n + end) == 1))
    return MeshReport(
        watertight=watertight,
        winding_consistent=winding,
        volume=mesh_volume(part.vertices, part.faces),
        expected_volume=part.expected_volume,
        triangles=len(faces),
    )


def _welded(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """``faces`` re-indexed onto the distinct vertices as written (float32 coordinates)."""
    if len(faces) == 0:
        return faces
    written = np.ascontiguousarray(np.asarray(vertices, dtype=np.float32)[:, :3])
    _, index = np.unique(written.view(np.dtype((np.void, 12))).ravel(), return_inverse=True)
    return index.ravel()[faces]


def _uses(keys: np.ndarray) -> np.ndarray:
    """How many times each distinct value of ``keys`` (1-D integers) occurs."""
    ordered = np.sort(keys)
    starts = np.flatnonzero(np.r_[True, ordered[1:] != ordered[:-1]])
    return np.diff(np.r_[starts, len(ordered)])


def mesh_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume in mm^3 of a closed triangle mesh (positive when outward-wound)."""
    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    return float(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0)


def part_record(part: Part, check: MeshReport) -> dict:
    """The part's size and print checks for a JSON report (mm, mm^3)."""
    return {
        "volume_mm3": check.volume,
        "bounding_box_mm": part.bounds,
        "triangles": check.triangles,
        "checks": {"manifold": True, "watertight": check.watertight,
                   "winding_consistent": check.winding_consistent,
                   "volume_matches_outline": check.volume_error < VOLUME_TOLERANCE},
    }


def require_printable(part: Part) -> MeshReport:
    """Run :func:`check_part` and raise if the part must not be written."""
    report = check_part(part)
    if not report.ok:
        raise MeshDefect(
            part.name,
            f"failed the print check (watertight={report.watertight}, "
            f"winding={report.winding_consistent}, volume={report.volume:.1f} mm3, "
            f"expected {report.expected_volume:.1f} mm3)")
    return report


#: Vertices within this distance (mm) of the farthest one from the axis are tooth tips.
TIP_BAND = 0.01


def tooth_zone_middle(vertices: np.ndarray) -> float:
    """Height (mm) half-way up a gear mesh's tooth zone, the part in its own frame (axis along
    z through x = y = 0): the middle of the heights of the vertices within TIP_BAND of the
    greatest distance from the axis, the tooth tips' vertical edges. A hub or boss, nearer
    the axis, does not move it; chamfers and an elephant-foot inset draw the tips in, so it
    stays in the straight part of the teeth."""
    vertices = np.asarray(vertices, dtype=np.float64)
    radius = np.hypot(vertices[:, 0], vertices[:, 1])
    tips = vertices[radius >= radius.max() - TIP_BAND, 2]
    return 0.5 * float(tips.min() + tips.max())
