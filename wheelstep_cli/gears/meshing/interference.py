"""Where the posed outlines overlap: points inside, overlapping area, penetration depth.

Lengths in mm, areas in mm^2.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.gears.meshing.outlines import (MeshWindow, RadialBand, Window, band_at, expand,
                                                  pair_chunks, rotate)
from wheelstep_cli.geometry.planar import body_clipped_overlap_areas, clipped_overlap_areas, points_inside


def contains(polygon, body: np.ndarray, band: RadialBand | None, seen=None) -> np.ndarray:
    """Points (own frame of the prepared polygon, mm) inside it.

    A point farther from the axis than every edge seen at its angle is outside (the ray
    out from the axis through it meets no edge beyond it), so only the others are tested.
    ``seen``: :func:`band_at` of the points, when already known.
    """
    maybe = np.ones(len(body), dtype=bool)
    if band is not None:
        r, _, rmax = band_at(body, band) if seen is None else seen
        maybe = r <= rmax + 1e-9
    inside = np.zeros(len(body), dtype=bool)
    inside[maybe] = points_inside(polygon, body[maybe])
    return inside


def overlap_area(p_world: np.ndarray, w_world: np.ndarray, box: MeshWindow) -> np.ndarray:
    """Areas (mm^2) where the posed outlines (poses, N, 2) overlap inside the mesh window."""
    half = box.half_height
    return clipped_overlap_areas(p_world, w_world, (box.x_lo, -half, box.x_hi, half))


def posed_overlap_area(bodies: tuple, points: tuple, theta: np.ndarray, phi: np.ndarray,
                       centre: np.ndarray, box: MeshWindow) -> np.ndarray:
    """:func:`overlap_area` of the pinion posed at ``theta`` and the wheel at ``phi`` (rad)
    about ``centre`` (mm), without posing the whole outlines.

    ``bodies``: the prepared (pinion, wheel) polygons, ``points`` their outlines (N, 2) mm.
    Each outline is cut in its own frame to a rectangle whose posed image holds the window
    grown by its longest edge, then the pieces are posed exactly as the whole outlines
    would be: the same region in the window, a fraction of the points.
    """
    half = box.half_height
    rect = (box.x_lo, -half, box.x_hi, half)
    p_angle = -theta[:, None]          # the very angles, shapes and order of rotate() below
    w_angle = np.pi + phi[:, None]
    turns = ((np.cos(p_angle), np.sin(p_angle)), (np.cos(w_angle), np.sin(w_angle)))
    body_boxes = np.empty((2, len(theta), 4))
    for which, outline in enumerate(points):
        longest = float(np.hypot(*(np.roll(outline, -1, axis=0) - outline).T).max())
        grow = longest + 1e-3 * (1.0 + half)
        corners = np.array([[rect[0] - grow, rect[1] - grow], [rect[2] + grow, rect[1] - grow],
                            [rect[2] + grow, rect[3] + grow], [rect[0] - grow, rect[3] + grow]])
        # the corners in the outline's own frame (inverse pose; only bounds, not exact bits)
        if which == 0:
            body = rotate(corners[None, :, :], -p_angle)
        else:
            body = rotate(corners[None, :, :] - centre, -w_angle)
        body_boxes[which] = np.column_stack([body[..., 0].min(axis=1), body[..., 1].min(axis=1),
                                             body[..., 0].max(axis=1), body[..., 1].max(axis=1)])

    def to_world(which: int, pts: np.ndarray, pose: np.ndarray) -> np.ndarray:
        c, s = turns[which][0][pose, 0], turns[which][1][pose, 0]
        world = np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], axis=-1)
        return world if which == 0 else world + centre

    return body_clipped_overlap_areas(bodies[0], bodies[1], to_world, body_boxes, rect)


#: Search radii (mm) of the penetration depth's near pass, tried in turn before all edges.
DEPTH_RADII = (0.25, 1.0, 4.0)


def depth(points: np.ndarray, pose: np.ndarray, edges: Window, max_pairs: int) -> np.ndarray:
    """Distance (mm) of each point to the nearest window edge of the same pose.

    Exact, and the same bits as measuring every edge of the pose: a point whose nearest
    edge lies within r mm is settled by the edges whose bounding box comes within r of it
    (the nearest is among them, measured by the same formula); the radii of
    ``DEPTH_RADII`` are tried in turn, the few points farther than the last from every
    edge meet all of their pose's edges. Point/edge pairs are measured in chunks of about
    ``max_pairs``.
    """
    best = np.full(len(points), np.inf)
    if len(points) == 0:
        return np.zeros(0)
    todo = np.arange(len(points))
    for radius in DEPTH_RADII:
        near = _near_depth(points[todo], pose[todo], edges, radius, max_pairs)
        best[todo] = near
        todo = todo[~(near <= radius)]
        if len(todo) == 0:
            return best
    best[todo] = _all_depth(points[todo], pose[todo], edges, max_pairs)
    return best


def _segment_distance(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance (mm) of points q (K, 2) to the segments a-b (K, 2)."""
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", q - a, d)
                / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
    return np.hypot(*(a + t[:, None] * d - q).T)


def _all_depth(points: np.ndarray, pose: np.ndarray, edges: Window, max_pairs: int) -> np.ndarray:
    """:func:`depth` measured against every edge of each point's pose."""
    best = np.full(len(points), np.inf)
    # edges come grouped by pose: each point meets its pose's run
    first = np.searchsorted(edges.e_pose, pose, side="left")
    counts = np.searchsorted(edges.e_pose, pose, side="right") - first
    ends = np.cumsum(counts)
    i0 = 0
    while i0 < len(points):
        done = ends[i0 - 1] if i0 else 0
        i1 = max(int(np.searchsorted(ends, done + max_pairs, side="right")), i0 + 1)
        rows, cols = expand(first[i0:i1], counts[i0:i1], np.arange(len(edges.e_pose)))
        rows += i0
        np.minimum.at(best, rows, _segment_distance(points[rows], edges.e0[cols], edges.e1[cols]))
        i0 = i1
    return best


def _near_depth(points: np.ndarray, pose: np.ndarray, edges: Window, radius: float,
                max_pairs: int) -> np.ndarray:
    """Least distance (mm) of each point to the edges of its pose whose bounding box, grown
    by ``radius`` mm, holds it (inf when none does).

    Without a dense table: edges whose grown box meets no point of their pose are dropped
    first (:func:`_edges_by_points`); points are sorted by (pose, x cell of ``radius`` mm,
    y); each edge looks up, in every x cell its grown box spans, the run of points within
    its grown y extent.
    """
    best = np.full(len(points), np.inf)
    if len(points) == 0 or len(edges.e_pose) == 0:
        return best
    near = np.flatnonzero(_edges_by_points(points, pose, edges, radius))
    if len(near) == 0:
        return best
    edges = Window(edges.e_pose[near], edges.e0[near], edges.e1[near], edges.v_pose, edges.v)
    e0, e1 = edges.e0, edges.e1
    x_lo, x_hi = np.minimum(e0[:, 0], e1[:, 0]) - radius, np.maximum(e0[:, 0], e1[:, 0]) + radius
    y_lo, y_hi = np.minimum(e0[:, 1], e1[:, 1]) - radius, np.maximum(e0[:, 1], e1[:, 1]) + radius
    origin = float(min(points[:, 0].min(), x_lo.min()))
    cell = np.floor((points[:, 0] - origin) / radius).astype(np.int64)
    c0 = np.floor((x_lo - origin) / radius).astype(np.int64)
    c1 = np.floor((x_hi - origin) / radius).astype(np.int64)
    cells = int(max(cell.max(), c1.max())) + 1
    y_min = float(min(points[:, 1].min(), y_lo.min()))
    stride = float(max(points[:, 1].max(), y_hi.max())) - y_min + 1.0
    key = (pose.astype(np.int64) * cells + cell) * stride + (points[:, 1] - y_min)
    order = np.argsort(key, kind="stable")
    key_sorted = key[order]
    span = c1 - c0 + 1
    q_edge, k = expand(np.zeros(len(span), dtype=np.intp), span, np.arange(int(span.max())))
    base = (edges.e_pose[q_edge].astype(np.int64) * cells + c0[q_edge] + k) * stride - y_min
    tol = 1e-9 * stride
    first = np.searchsorted(key_sorted, base + y_lo[q_edge] - tol, side="left")
    counts = np.searchsorted(key_sorted, base + y_hi[q_edge] + tol, side="right") - first
    for rows, cols in pair_chunks(first, counts, order, q_edge, max_pairs):
        q = points[rows]
        # the exact grown-box test (the key's rounding only widened the runs)
        keep = ((q[:, 0] >= x_lo[cols]) & (q[:, 0] <= x_hi[cols])
                & (q[:, 1] >= y_lo[cols]) & (q[:, 1] <= y_hi[cols]))
        rows, cols = rows[keep], cols[keep]
        np.minimum.at(best, rows, _segment_distance(points[rows], e0[cols], e1[cols]))
    return best


def _edges_by_points(points: np.ndarray, pose: np.ndarray, edges: Window, radius: float) -> np.ndarray:
    """Per edge, False where no point of its pose lies in its bounding box grown by ``radius``
    mm (found on a coarse grid of the points' cells: an edge is kept when its grown box
    spans an occupied cell, or more than two cells either way)."""
    coarse = 4.0 * radius
    x0, y0 = points.min(axis=0)
    nx, ny = (np.floor((points.max(axis=0) - (x0, y0)) / coarse).astype(np.int64) + 1)
    poses = int(pose.max()) + 1
    while poses * nx * ny > (1 << 22):            # a very spread-out set: coarser cells
        coarse *= 2.0
        nx, ny = (np.floor((points.max(axis=0) - (x0, y0)) / coarse).astype(np.int64) + 1)
    occupied = np.zeros((poses, nx, ny), dtype=bool)
    occupied[pose, np.floor((points[:, 0] - x0) / coarse).astype(np.int64),
             np.floor((points[:, 1] - y0) / coarse).astype(np.int64)] = True
    e0, e1, e_pose = edges.e0, edges.e1, edges.e_pose
    span = []
    for axis, origin, count in ((0, x0, nx), (1, y0, ny)):
        lo = np.floor((np.minimum(e0[:, axis], e1[:, axis]) - radius - origin) / coarse).astype(np.int64)
        hi = np.floor((np.maximum(e0[:, axis], e1[:, axis]) + radius - origin) / coarse).astype(np.int64)
        span.append((np.clip(lo, 0, count - 1), np.clip(hi, 0, count - 1), (hi >= 0) & (lo < count)))
    (ix0, ix1, inx), (iy0, iy1, iny) = span
    live = inx & iny & (e_pose < poses)
    p = np.minimum(e_pose, poses - 1)
    hit = (occupied[p, ix0, iy0] | occupied[p, ix1, iy0] | occupied[p, ix0, iy1]
           | occupied[p, ix1, iy1])
    wide = (ix1 - ix0 > 1) | (iy1 - iy0 > 1)
    return live & (hit | wide)
