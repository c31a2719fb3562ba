"""Checks on closed 2D outlines before they go to manifold3d.

manifold3d can abort the process on malformed input and silently empties a
clockwise polygon, so every outline is checked here first.
"""

from __future__ import annotations

import numpy as np
import shapely

from wheelstep_cli.errors import DesignError


def signed_area(outline: np.ndarray) -> float:
    """Shoelace area in mm^2 of a closed polygon (N, 2); positive when counter-clockwise."""
    x, y = outline[:, 0], outline[:, 1]
    # elementwise, not np.dot: a BLAS dot runs on the BLAS's threads (15 ms for a 10 k-point
    # outline on a busy machine) and sums in an order that depends on their count
    return 0.5 * float(np.sum(x * np.roll(y, -1) - y * np.roll(x, -1)))


def drop_repeated_points(outline: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Remove consecutive duplicates (and a closing point equal to the first)."""
    outline = np.asarray(outline, dtype=float)
    step = np.linalg.norm(np.diff(outline, axis=0, append=outline[:1]), axis=1)
    return outline[step > tol]


def check_outline(outline: np.ndarray, what: str) -> np.ndarray:
    """Validate a part outline and return it counter-clockwise without repeated points.

    Raises :class:`DesignError` (naming ``what``) for non-finite values, too few
    points, zero area or self-intersections.
    """
    outline = np.asarray(outline, dtype=float)
    if outline.ndim != 2 or outline.shape[1] != 2 or not np.isfinite(outline).all():
        raise DesignError(what, "outline", "has non-finite points")
    outline = drop_repeated_points(outline)
    if len(outline) < 3:
        raise DesignError(what, "outline", "needs at least 3 distinct points")
    area = signed_area(outline)
    if abs(area) < 1e-9:
        raise DesignError(what, "outline", "has zero area")
    if area < 0:
        outline = outline[::-1].copy()
    ring = shapely.LinearRing(outline)
    if not ring.is_simple:
        raise DesignError(what, "outline", "crosses itself (teeth overlap or a curve loops)")
    return outline


def min_radius(outline: np.ndarray) -> float:
    """Smallest distance in mm from the origin to the outline (vertices and edges)."""
    return float(shapely.Polygon(outline).exterior.distance(shapely.Point(0.0, 0.0)))


def group_rings_by_shell(rings) -> list[list[np.ndarray]]:
    """Group manifold3d contours (outer CCW, holes CW) into [outer, holes...] lists."""
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


def inset_area_lost(shells: list[list[np.ndarray]], inset: float, mitre_limit: float) -> float:
    """Area (mm^2) an inward mitred offset by ``inset`` mm removes from [outer, holes...] shells."""
    shape = shapely.MultiPolygon([shapely.Polygon(ring[0], ring[1:]) for ring in shells])
    return float(shape.area - shape.buffer(-inset, join_style="mitre", mitre_limit=mitre_limit).area)


def polyline_box_distance(points: np.ndarray, box: tuple[float, float, float, float]) -> float:
    """Least distance (mm) between an open polyline (N, 2) and the box (xmin, ymin, xmax, ymax);
    0 where they meet."""
    return float(shapely.LineString(points).distance(shapely.box(*box)))


# polygon booleans for the gear generator
#
# numpy arrays in and out (mm): a closed outline is an (N, 2) array without its closing
# point; a result is the counter-clockwise exterior of the largest part.


def _largest_exterior_ccw(polygon) -> np.ndarray:
    """Exterior (N, 2) of a shapely polygon, counter-clockwise; of the largest part if it split."""
    if polygon.geom_type != "Polygon":
        polygon = max(polygon.geoms, key=lambda g: g.area)
    outline = np.asarray(polygon.exterior.coords)[:-1]
    return outline if signed_area(outline) > 0 else outline[::-1]


def polygon_union(pieces: np.ndarray):
    """An opaque handle on the union of the closed polygons ``pieces`` (P, K, 2) mm, for
    :func:`grown_minus_rotated_union` (shapely releases the GIL: unions of separate piles of
    pieces may run on threads)."""
    return shapely.union_all(shapely.polygons(pieces))


def grown_minus_rotated_union(body: np.ndarray, grow: float, regions: list,
                              angles: np.ndarray) -> np.ndarray:
    """The polygon ``body`` (N, 2) grown by ``grow`` mm (bevel joins) minus a cutter region.

    The cutter region is the union of the :func:`polygon_union` ``regions``, taken once,
    and its copies rotated about the origin by each of ``angles`` (rad). The zero-area
    slivers a boolean leaves where pieces just touch are dropped. Returns the CCW outline
    of the largest part left.
    """
    from shapely import affinity

    region = shapely.union_all(regions)
    cutter = shapely.union_all([affinity.rotate(region, a, origin=(0.0, 0.0), use_radians=True)
                                for a in angles])
    blank = shapely.Polygon(body).buffer(grow, join_style="bevel")
    return _largest_exterior_ccw(blank.difference(cutter).buffer(0))


def intersect_outlines(outline: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """CCW outline (N, 2) of the largest part of two closed outlines' intersection (slivers dropped)."""
    both = shapely.Polygon(outline).intersection(shapely.Polygon(limit))
    return _largest_exterior_ccw(both.buffer(0))


def polylines_distance(first: list[np.ndarray], second: list[np.ndarray]) -> float:
    """Least distance (mm) between two sets of open polylines (each (K, 2) mm); 0 when they cross."""
    a = shapely.MultiLineString([line for line in first if len(line) > 1])
    b = shapely.MultiLineString([line for line in second if len(line) > 1])
    return float(shapely.distance(a, b))


def open_outline(outline: np.ndarray, radius: float, thin: float, quad_segs: int = 8) -> np.ndarray:
    """Morphological opening of a closed outline: convex corners rounded to ``radius`` mm.

    The outline is first thinned (Douglas-Peucker, ``thin`` mm); then eroded and dilated
    by ``radius`` with ``quad_segs`` chords per quarter circle. Concave corners stay sharp.
    """
    body = shapely.Polygon(_simplified_ring(shapely.LinearRing(outline), thin))
    return _largest_exterior_ccw(body.buffer(-radius, quad_segs=quad_segs).buffer(radius, quad_segs=quad_segs))


def segmentize_ring(outline: np.ndarray, max_length: float) -> np.ndarray:
    """The closed outline (N, 2) with points added so no segment is longer than ``max_length`` mm."""
    return np.asarray(shapely.segmentize(shapely.LinearRing(outline), max_length).coords)[:-1]


def simplify_ring(outline: np.ndarray, tolerance: float) -> np.ndarray:
    """The closed outline (N, 2) thinned by Douglas-Peucker to ``tolerance`` mm, topology kept."""
    return np.asarray(_simplified_ring(shapely.LinearRing(outline), tolerance).coords)[:-1]


def _simplified_ring(ring, tolerance: float):
    """``ring`` (a shapely LinearRing) simplified as ``shapely.simplify(..., preserve_topology=True)``
    gives it.

    The topology-preserving simplifier costs about ten times plain Douglas-Peucker on a
    dense gear outline (0.18 s for the 184 k-point wheel). Where plain Douglas-Peucker
    leaves a simple ring there was nothing for the topology checks to keep, and both keep
    the same points; they differ only in where the ring starts when its first point is
    dropped (plain: the next kept point; topology-preserving: the last kept one before
    it), which is matched here so the written bytes do not change. A non-simple result
    goes the slow way.
    """
    plain = shapely.simplify(ring, tolerance, preserve_topology=False)
    if plain.is_empty or not plain.is_simple:
        return shapely.simplify(ring, tolerance, preserve_topology=True)
    coords = shapely.get_coordinates(plain)[:-1]
    if len(coords) < 3:
        return shapely.simplify(ring, tolerance, preserve_topology=True)
    if not np.array_equal(coords[0], shapely.get_coordinates(ring)[0]):
        coords = np.roll(coords, 1, axis=0)
    return shapely.LinearRing(coords)


# polygon queries for the meshing check


def prepared_polygon(outline: np.ndarray):
    """An opaque handle on the polygon ``outline`` (N, 2) mm, made fast for repeated
    :func:`points_inside` queries. Not thread-safe: one handle per thread."""
    polygon = shapely.Polygon(outline)
    shapely.prepare(polygon)
    return polygon


def points_inside(polygon, points: np.ndarray) -> np.ndarray:
    """Per point (M, 2) mm, True when it lies strictly inside the :func:`prepared_polygon`."""
    return shapely.contains_xy(polygon, points[:, 0], points[:, 1])


def clipped_overlap_areas(first: np.ndarray, second: np.ndarray,
                          box: tuple[float, float, float, float]) -> np.ndarray:
    """Per pair of polygons (K, N, 2) and (K, M, 2) mm: the area (mm^2) they share inside
    the rectangle ``box`` = (x_lo, y_lo, x_hi, y_hi) mm."""
    a = shapely.clip_by_rect(shapely.polygons(first), *box)
    b = shapely.clip_by_rect(shapely.polygons(second), *box)
    return shapely.area(shapely.intersection(a, b))


def body_clipped_overlap_areas(first, second, to_world, body_boxes: np.ndarray,
                               box: tuple[float, float, float, float]) -> np.ndarray:
    """Per pose: the area (mm^2) two posed polygons share inside the rectangle ``box`` =
    (x_lo, y_lo, x_hi, y_hi) mm, as :func:`clipped_overlap_areas` of the posed outlines
    gives it, without posing the whole outlines.

    ``first``, ``second``: :func:`prepared_polygon` handles in their own (body) frames;
    ``body_boxes`` (2, P, 4): per polygon and pose, a body-frame rectangle whose posed
    image holds ``box`` grown by more than the polygon's longest edge;
    ``to_world(which, points, pose)``: the points (M, 2) of polygon ``which`` (0, 1) posed
    at the poses (M,) into the world, exactly as the posed outlines are. Each polygon is
    first cut to its body box: every edge that meets ``box`` keeps both its vertices there,
    so it is posed to the very same coordinates and the region in ``box`` is the same.
    """
    areas = np.zeros(body_boxes.shape[1])
    pieces = [[shapely.clip_by_rect(body, *rect) for rect in body_boxes[which]]
              for which, body in enumerate((first, second))]
    posed = []
    for which in (0, 1):
        cut = np.array(pieces[which], dtype=object)
        coords, index = shapely.get_coordinates(cut, return_index=True)
        # the cut pieces are this function's own: their coordinates are replaced in place
        posed.append(shapely.set_coordinates(cut, to_world(which, coords, index)))
    a = shapely.clip_by_rect(posed[0], *box)
    b = shapely.clip_by_rect(posed[1], *box)
    areas[:] = shapely.area(shapely.intersection(a, b))
    return areas


def offset_outline(outline: np.ndarray, distance: float, what: str = "outline",
                   thin: float = 1e-4) -> np.ndarray:
    """The exact offset (mm) of a closed outline (N, 2) mm along its normals: every point at
    ``distance`` from the outline, outward when positive (the Minkowski sum with a disc;
    convex corners rounded, concave ones cut), inward when negative. Returned
    counter-clockwise without the closing point, thinned to ``thin`` mm (the round joins
    add an arc at every convex vertex of a dense outline, most of them shorter than a
    micrometre: the meshing check's time grows with the vertices); DesignError naming
    ``what`` if the offset splits the outline or leaves nothing."""
    outline = check_outline(outline, what)
    if distance == 0.0:
        return outline
    # round joins: a convex corner's offset is the arc of points at exactly ``distance``
    grown = shapely.Polygon(outline).buffer(float(distance), quad_segs=8, join_style="round")
    if grown.is_empty or grown.geom_type != "Polygon":
        raise DesignError(what, f"offset {distance:g} mm", "splits or empties the outline")
    ring = _simplified_ring(grown.exterior, thin) if thin > 0 else grown.exterior
    return check_outline(np.asarray(ring.coords, dtype=float)[:-1], what)

def spoked_pockets(r_in: float, r_out: float, spokes: int, spoke_width: float, direction: float,
                   fillet: float) -> list[np.ndarray]:
    """Pockets (CCW rings, mm) of the annulus ``r_in``..``r_out`` between ``spokes`` straight
    spokes ``spoke_width`` mm wide, the first along ``direction`` rad; corners rounded by
    ``fillet`` mm (a rounded pocket prints and carries load better than a sharp one)."""
    annulus = shapely.Point(0.0, 0.0).buffer(r_out, quad_segs=64).difference(
        shapely.Point(0.0, 0.0).buffer(r_in, quad_segs=64))
    for k in range(spokes):
        t = direction + 2.0 * np.pi * k / spokes
        c, s = np.cos(t), np.sin(t)
        half = spoke_width / 2.0
        box = [(0.0, -half), (2.0 * r_out, -half), (2.0 * r_out, half), (0.0, half)]
        annulus = annulus.difference(shapely.Polygon([(x * c - y * s, x * s + y * c) for x, y in box]))
    rounded = annulus.buffer(-fillet, quad_segs=8).buffer(fillet, quad_segs=8)
    parts = list(getattr(rounded, "geoms", [rounded]))
    rings = [np.asarray(shapely.geometry.polygon.orient(p, 1.0).exterior.coords)[:-1]
             for p in parts if p.area > 1.0]
    # order by angle so the result does not depend on shapely's ordering
    return sorted(rings, key=lambda r: float(np.mod(np.arctan2(*r.mean(axis=0)[::-1]) - direction,
                                                    2.0 * np.pi)))


def tooth_heights_lost(outline: np.ndarray, module: float, line_width: float) -> np.ndarray:
    """Per tooth of a gear outline (mm): how much of its height is lost when every feature
    narrower than ``line_width`` mm is taken away (a morphological opening: what extrusion
    lines of that width can lay down). The teeth are what a 1.2 module opening cuts off."""
    gear = shapely.Polygon(outline)
    # the gear with its teeth taken off (their tips lie within 1.2 module of the body)
    body = gear.buffer(-1.2 * module).buffer(1.2 * module)
    opened = gear.buffer(-line_width / 2).buffer(line_width / 2)
    pieces = [t for t in getattr(gear.difference(body), "geoms", [gear.difference(body)])
              # slivers where the opened body differs from the outline are not teeth
              if t.area >= 0.05 * module**2]
    lost = []
    for tooth in _whole_teeth(pieces, 0.05 * module):
        # each tooth meets only what lies round it: every point of a tooth is nearer to the body
        # than the tooth's own extent (it stands on the body), so the body's boundary clipped
        # to the tooth's box grown by that extent holds every nearest point, and the opened
        # gear clipped to the box holds all of it that overlaps the tooth
        x0, y0, x1, y1 = tooth.bounds
        reach = float(np.hypot(x1 - x0, y1 - y0))
        base = shapely.clip_by_rect(body.boundary, x0 - reach, y0 - reach, x1 + reach, y1 + reach)
        height = shapely.distance(base, shapely.points(np.asarray(tooth.exterior.coords))).max()
        kept = shapely.clip_by_rect(opened, x0 - reach, y0 - reach, x1 + reach, y1 + reach).intersection(tooth)
        rings = [np.asarray(g.exterior.coords) for g in getattr(kept, "geoms", [kept])
                 if g.geom_type == "Polygon" and not g.is_empty]
        left = shapely.distance(base, shapely.points(np.vstack(rings))).max() if rings else 0.0
        lost.append(height - left)
    return np.array(lost)


def _whole_teeth(pieces: list, gap: float) -> list:
    """The tooth pieces (shapely polygons) with those nearer than ``gap`` mm to each other
    joined: a tooth whose head dips to the cut (a relieved corner tooth) is one tooth, not two."""
    joined: list = []
    for piece in sorted(pieces, key=lambda t: np.arctan2(t.centroid.y, t.centroid.x)):
        if joined and joined[-1].distance(piece) < gap:
            joined[-1] = joined[-1].buffer(gap).union(piece.buffer(gap)).buffer(-gap)
        else:
            joined.append(piece)
    if len(joined) > 1 and joined[-1].distance(joined[0]) < gap:
        joined[0] = joined[0].buffer(gap).union(joined.pop().buffer(gap)).buffer(-gap)
    return [t if t.geom_type == "Polygon" else max(t.geoms, key=lambda g: g.area) for t in joined]


def drop_collinear(ring: np.ndarray, tol: float = 1e-5) -> np.ndarray:
    """The ring without the points lying on the segment between their neighbours (within
    ``tol`` mm). A section of an extruded wall cuts every side quad's diagonal at its
    midpoint, doubling the points without changing the shape; the meshing check costs
    in proportion to the points."""
    prev, nxt = np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0)
    a, b = ring - prev, nxt - ring
    chord = np.hypot(*(nxt - prev).T)
    off_line = np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) > tol * np.maximum(chord, 1e-300)
    between = np.einsum("ij,ij->i", a, b) > 0.0
    keep = off_line | ~between
    return ring[keep] if np.count_nonzero(keep) >= 3 else ring
