"""Extrusion of checked outlines into solids with manifold3d, and mesh validity checks."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError
from wheelstep_cli.geometry.outline import check_outline, min_radius, signed_area


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


def circle(radius: float, segments: int) -> np.ndarray:
    """Counter-clockwise circle of ``segments`` points, radius in mm."""
    t = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def bore_segments(diameter: float) -> int:
    """Polygon count for a bore: chord error below 0.01 mm, at least 32."""
    r = diameter / 2.0
    return max(32, int(np.ceil(np.pi / np.arccos(max(1e-9, 1.0 - 0.01 / max(r, 0.01))))))


def extrude_plate(name: str, outline: np.ndarray, thickness: float, bore: float = 0.0,
                  bore_param: str = "bore") -> Part:
    """Extrude a closed outline (mm, any orientation) by ``thickness`` mm along +Z.

    A centred round ``bore`` of that diameter (mm, 0 for none) is cut through.
    The outline is checked first; the bore must leave wall to the outline.
    """
    if not thickness > 0:
        raise DesignError("thickness", thickness, "must be > 0 mm")
    outline = check_outline(outline, name)
    polygons = [outline]
    area = signed_area(outline)
    if bore > 0:
        wall = min_radius(outline) - bore / 2.0
        if wall < 1.0:
            raise DesignError(bore_param, bore,
                              f"must be < {2 * (min_radius(outline) - 1.0):.2f} mm "
                              f"(leave 1 mm of wall inside the {name}'s root)")
        segments = bore_segments(bore)
        # circumscribed polygon: its flats touch the nominal circle, so the shaft fits
        hole = circle(bore / 2.0 / np.cos(np.pi / segments), segments)
        polygons.append(hole[::-1])
        area -= signed_area(hole)
    elif bore < 0:
        raise DesignError(bore_param, bore, "must be >= 0 mm")
    return solid_from_polygons(name, polygons, thickness, area * thickness)


def solid_from_polygons(name: str, polygons: list[np.ndarray], height: float,
                        expected_volume: float) -> Part:
    """Extrude checked polygons (outer CCW, holes CW) with manifold3d into a Part."""
    import manifold3d as m3d

    section = m3d.CrossSection([np.ascontiguousarray(p, dtype=np.float64) for p in polygons],
                               m3d.FillRule.Positive)
    solid = m3d.Manifold.extrude(section, height)
    if solid.status() != m3d.Error.NoError:
        raise DesignError(name, "solid", f"manifold3d reports {solid.status().name}")
    mesh = solid.to_mesh()
    vertices = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    faces = np.asarray(mesh.tri_verts, dtype=np.int64)
    if len(faces) == 0:
        raise DesignError(name, "solid", "came out empty")
    return Part(name, vertices, faces, float(expected_volume))


def check_part(part: Part) -> MeshReport:
    """Check a part is printable: watertight, consistently wound, expected positive volume.

    Watertight: every undirected edge is shared by exactly two triangles.
    Consistent winding: those two triangles traverse it in opposite directions.
    """
    faces = np.asarray(part.faces, dtype=np.int64)
    directed = np.stack([faces, np.roll(faces, -1, axis=1)], axis=2).reshape(-1, 2)
    undirected = np.sort(directed, axis=1)
    _, edge_uses = np.unique(undirected, axis=0, return_counts=True)
    watertight = bool(len(faces) > 0 and np.all(edge_uses == 2))
    _, directed_uses = np.unique(directed, axis=0, return_counts=True)
    winding = bool(watertight and np.all(directed_uses == 1))
    return MeshReport(
        watertight=watertight,
        winding_consistent=winding,
        volume=mesh_volume(part.vertices, faces),
        expected_volume=part.expected_volume,
        triangles=len(faces),
    )


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
        raise DesignError(
            part.name, "mesh",
            f"failed the print check (watertight={report.watertight}, "
            f"winding={report.winding_consistent}, volume={report.volume:.1f} mm3, "
            f"expected {report.expected_volume:.1f} mm3)")
    return report


def inset_bottom(part: Part, height: float, inset: float) -> Part:
    """Elephant-foot compensation: the part's lowest ``height`` mm shrunk inwards by ``inset`` mm.

    The first layers of a print squash outwards on the bed; drawing them smaller by
    about the squash keeps bed-side edges (and bores) true. The part must be a prism
    over its lowest ``height`` (as every extruded plate is); this is checked. The
    expected volume drops by ``height`` times the area lost in the offset, computed
    independently with shapely, so the later volume check stays exact.
    """
    import manifold3d as m3d
    import shapely

    if not (np.isfinite(height) and height >= 0):
        raise DesignError("elephant_foot_height", height, "must be >= 0 mm")
    if not (np.isfinite(inset) and inset >= 0):
        raise DesignError("elephant_foot_inset", inset, "must be >= 0 mm")
    if height == 0 or inset == 0:
        return part
    z0, z1 = float(part.bounds[0, 2]), float(part.bounds[1, 2])
    if not height < z1 - z0:
        raise DesignError("elephant_foot_height", height,
                          f"must be < the {part.name}'s height {z1 - z0:g} mm")
    solid = _manifold_of(part)
    section = solid.slice(z0 + height / 2.0)
    below = solid.trim_by_plane((0.0, 0.0, -1.0), -(z0 + height))
    prism_error = abs(below.volume() - section.area() * height)
    if prism_error > 1e-6 * max(1.0, below.volume()):
        raise DesignError(part.name, "elephant foot",
                          f"needs a part that is a prism over its lowest {height:g} mm")
    foot_section = section.offset(-inset, m3d.JoinType.Miter, 2.0)
    if foot_section.is_empty():
        raise DesignError("elephant_foot_inset", inset, f"removes the whole bottom of the {part.name}")
    foot = m3d.Manifold.extrude(foot_section, height).translate((0.0, 0.0, z0))
    above = solid.trim_by_plane((0.0, 0.0, 1.0), z0 + height)
    result = above + foot
    if result.status() != m3d.Error.NoError:
        raise DesignError(part.name, "elephant foot", f"manifold3d reports {result.status().name}")
    mesh = result.to_mesh()
    shape = shapely.MultiPolygon([shapely.Polygon(ring[0], ring[1:])
                                  for ring in _rings_by_shell(section.to_polygons())])
    lost = shape.area - shape.buffer(-inset, join_style="mitre", mitre_limit=2.0).area
    return Part(part.name, np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3],
                np.asarray(mesh.tri_verts, dtype=np.int64), part.expected_volume - height * lost)


def footprint(part: Part) -> list[list[np.ndarray]]:
    """The part seen from above: a list of polygons, each [outer ring CCW, hole rings CW...] (mm).

    Slivers below 0.001 mm^2 (left by the projection where faces were split) are dropped.
    """
    rings = _manifold_of(part).project().to_polygons()
    return _rings_by_shell([r for r in rings if abs(signed_area(np.asarray(r))) >= 1e-3])


def _manifold_of(part: Part):
    import manifold3d as m3d

    mesh = m3d.Mesh(vert_properties=np.ascontiguousarray(part.vertices, dtype=np.float32),
                    tri_verts=np.ascontiguousarray(part.faces, dtype=np.uint32))
    solid = m3d.Manifold(mesh)
    if solid.status() != m3d.Error.NoError:
        raise DesignError(part.name, "mesh", f"is not a closed manifold ({solid.status().name})")
    return solid


def _rings_by_shell(rings) -> list[list[np.ndarray]]:
    """Group manifold3d contours (outer CCW, holes CW) into [outer, holes...] lists."""
    import shapely

    rings = [np.asarray(r, dtype=np.float64) for r in rings if len(r) >= 3]
    shells = [r for r in rings if signed_area(r) > 0]
    holes = [r for r in rings if signed_area(r) < 0]
    groups = [[s] for s in shells]
    polys = [shapely.Polygon(s) for s in shells]
    for hole in holes:
        probe = shapely.Point(hole[0])
        # the smallest shell containing the hole owns it
        owners = [i for i, p in enumerate(polys) if p.covers(probe)]
        if owners:
            groups[min(owners, key=lambda i: polys[i].area)].append(hole)
    return groups
