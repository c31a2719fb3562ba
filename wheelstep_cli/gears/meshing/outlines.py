"""Outlines prepared for the meshing check: sorted by body angle, cut to the mesh window.

An outline's vertices and edges are ordered by their body angle once, so a pose
cuts out the parts inside the mesh window's angular sector with a binary search
instead of posing the whole outline. Radial bands (per body-angle bin, the least
and greatest distance of the outline from its axis) let the first search pass skip
vertices and edges that cannot meet the other outline within the reach.
Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MeshWindow:
    """The box round the line of centres in which contacts are looked for (mm, world frame).

    Vertices count between ``x_lo`` and ``x_hi`` within ``half_height`` of the line of
    centres; edges are taken from the box widened by ``margin`` on every side.
    """

    x_lo: float
    x_hi: float
    half_height: float
    margin: float


def rotate(points: np.ndarray, angle) -> np.ndarray:
    """Rotate (..., 2) points by ``angle`` rad counter-clockwise about the origin.

    ``angle`` is a scalar or broadcasts against ``points[..., 0]``.
    """
    return turn(points, np.cos(angle), np.sin(angle))


def turn(points: np.ndarray, cos: np.ndarray, sin: np.ndarray) -> np.ndarray:
    """:func:`rotate` by angles given by their cosines and sines (broadcasting against
    ``points[..., 0]``): a batch's few pose angles are looked up once, not per point."""
    x, y = points[..., 0], points[..., 1]
    return np.stack([cos * x - sin * y, sin * x + cos * y], axis=-1)


def wrap(angle: np.ndarray) -> np.ndarray:
    """Angles (rad) into (-pi, pi]."""
    return np.pi - np.mod(np.pi - angle, 2.0 * np.pi)


def expand(first: np.ndarray, counts: np.ndarray, table: np.ndarray):
    """(owner, table[first[owner] + k]) for k < counts[owner], owners in order."""
    owner = np.repeat(np.arange(len(first)), counts)
    offsets = np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts)
    return owner, table[first[owner] + offsets]


def pair_chunks(first: np.ndarray, counts: np.ndarray, order: np.ndarray, q_edge: np.ndarray,
                max_pairs: int):
    """The candidate (row, edge) pairs of sorted-key runs in chunks of about ``max_pairs``:
    query j (of edge ``q_edge[j]``) holds rows ``order[first[j]:first[j] + counts[j]]``.
    Yields (rows, cols) per chunk, so memory stays bounded whatever the outline sizes."""
    ends = np.cumsum(counts)
    i0 = 0
    while i0 < len(counts):
        done = ends[i0 - 1] if i0 else 0
        i1 = max(int(np.searchsorted(ends, done + max_pairs, side="right")), i0 + 1)
        queries, rows = expand(first[i0:i1], counts[i0:i1], order)
        yield rows, q_edge[queries + i0]
        i0 = i1


@dataclass(frozen=True)
class Window:
    """Edges and vertices (mm) of one outline inside the mesh window, for a batch of poses.

    Flat arrays, grouped by pose: every edge (start ``e0``, end ``e1``) and vertex ``v``
    carries the index of its pose in ``e_pose`` / ``v_pose``.
    """

    e_pose: np.ndarray
    e0: np.ndarray
    e1: np.ndarray
    v_pose: np.ndarray
    v: np.ndarray

    def shifted(self, offset: np.ndarray) -> "Window":
        """The same window with every point moved by ``-offset`` (mm)."""
        return Window(self.e_pose, self.e0 - offset, self.e1 - offset, self.v_pose,
                      self.v - offset)


@dataclass(frozen=True)
class SortedOutline:
    """One outline with its vertices and edges ordered by body angle, to cut windows out fast.

    ``points`` (N, 2) mm. ``v_angle``: the vertices' body angles (rad) sorted, listed
    twice (the second time + 2 pi) so that an angular range never wraps; ``v_index``
    their vertices. ``e_angle``, ``e_index``: the same for the start angles of the short
    edges (edge i runs from vertex i to i + 1), ``e_sweep`` the largest angle (rad) and
    ``e_length`` the largest length (mm) of a short edge. ``e_always``: the other edges
    (long, or passing near the axis), tested in every pose.
    """

    points: np.ndarray
    v_angle: np.ndarray
    v_index: np.ndarray
    e_angle: np.ndarray
    e_index: np.ndarray
    e_sweep: float
    e_length: float
    e_always: np.ndarray


def sorted_outline(points: np.ndarray, long_edge: float) -> SortedOutline:
    """Prepare an outline (N, 2) mm for :func:`posed_window`; edges over ``long_edge`` mm
    are always tested."""
    nxt = np.roll(points, -1, axis=0)
    a0 = np.arctan2(points[:, 1], points[:, 0])
    # a segment not through the axis sees its angle change monotonically, by less than pi
    sweep = wrap(np.arctan2(nxt[:, 1], nxt[:, 0]) - a0)
    length = np.hypot(nxt[:, 0] - points[:, 0], nxt[:, 1] - points[:, 1])
    short = (length <= long_edge) & (np.abs(sweep) <= 0.5)
    v_angle = np.mod(a0, 2.0 * np.pi)
    v_order = np.argsort(v_angle, kind="stable")
    e_start = np.mod(np.where(sweep >= 0.0, a0, a0 + sweep), 2.0 * np.pi)
    idx = np.flatnonzero(short)
    e_order = idx[np.argsort(e_start[idx], kind="stable")]
    twice = lambda a: np.concatenate([a, a + 2.0 * np.pi])  # noqa: E731
    return SortedOutline(points, twice(v_angle[v_order]), np.tile(v_order, 2),
                         twice(e_start[e_order]), np.tile(e_order, 2),
                         float(np.abs(sweep[idx]).max(initial=0.0)),
                         float(length[idx].max(initial=0.0)), np.flatnonzero(~short))


def sector(box: MeshWindow, axis: np.ndarray, extra: float) -> tuple[float, float] | None:
    """World angles (lo, hi) rad, seen from ``axis``, of the edge box widened by ``extra`` mm.

    None when that box holds the axis (then every angle is in view).
    """
    grow = box.margin + extra + 1e-9
    x0, x1, y = box.x_lo - grow, box.x_hi + grow, box.half_height + grow
    if x0 <= axis[0] <= x1 and -y <= axis[1] <= y:
        return None
    centre = np.arctan2(-axis[1], 0.5 * (x0 + x1) - axis[0])
    corners = np.array([[x0, -y], [x0, y], [x1, -y], [x1, y]]) - axis
    rel = wrap(np.arctan2(corners[:, 1], corners[:, 0]) - centre)
    return float(centre + rel.min()), float(centre + rel.max())


def _in_sector(angle2: np.ndarray, index2: np.ndarray, lo: np.ndarray, width: float):
    """(pose, index) of the entries whose sorted, doubled angles lie in [lo[pose], lo + width]."""
    lo = np.mod(lo - 1e-9, 2.0 * np.pi)
    first = np.searchsorted(angle2, lo, side="left")
    last = np.searchsorted(angle2, lo + width + 2e-9, side="right")
    return expand(first, last - first, index2)


@dataclass(frozen=True)
class Pose:
    """How a batch of poses places an outline in the world (rad, mm).

    ``angle`` (poses,): rotation about its axis; ``shift``: its axis in the world (None:
    the origin); ``sector``: world angles seen from the axis holding every window vertex
    and an end of every short window edge (None: all angles); ``body_offset`` (poses,):
    body angle minus world angle.
    """

    angle: np.ndarray
    shift: np.ndarray | None
    sector: tuple[float, float] | None
    body_offset: np.ndarray


def _candidates(outline: SortedOutline, pose: Pose):
    """(pose, index) of the vertices and of the edges in the pose's sector, grouped by pose."""
    poses, n = len(pose.angle), len(outline.points)
    if pose.sector is None:
        v_pose, v_idx = np.repeat(np.arange(poses), n), np.tile(np.arange(n), poses)
        return v_pose, v_idx, v_pose, v_idx
    lo = pose.sector[0] + pose.body_offset
    width = pose.sector[1] - pose.sector[0]
    v_pose, v_idx = _in_sector(outline.v_angle, outline.v_index, lo, width)
    e_pose, e_idx = _in_sector(outline.e_angle, outline.e_index, lo - outline.e_sweep,
                               width + outline.e_sweep)
    if len(outline.e_always):
        e_pose = np.concatenate([e_pose, np.repeat(np.arange(poses), len(outline.e_always))])
        e_idx = np.concatenate([e_idx, np.tile(outline.e_always, poses)])
        order = np.argsort(e_pose, kind="stable")
        e_pose, e_idx = e_pose[order], e_idx[order]
    return v_pose, v_idx, e_pose, e_idx


def posed_window(outline: SortedOutline, pose: Pose, box: MeshWindow) -> Window:
    """Window parts of a closed outline placed by ``pose``.

    Vertices: those inside the box. Edges: those whose bounding box meets the box
    widened by its margin on every side, so every edge through the box is there,
    however long, and the outline round a vertex is in view within the margin. Only
    the candidates of the pose's sector are posed and tested.
    """
    n = len(outline.points)
    v_pose, v_idx, e_pose, e_idx = _candidates(outline, pose)
    c, s = np.cos(pose.angle), np.sin(pose.angle)
    px, py = outline.points[:, 0], outline.points[:, 1]

    def pose_xy(cw, sw, idx):
        x, y = px[idx], py[idx]
        wx, wy = cw * x - sw * y, sw * x + cw * y
        if pose.shift is not None:
            wx, wy = wx + pose.shift[0], wy + pose.shift[1]
        return wx, wy

    xlo, xhi, half, margin = box.x_lo, box.x_hi, box.half_height, box.margin
    vx, vy = pose_xy(c[v_pose], s[v_pose], v_idx)
    vertex = np.flatnonzero((vx >= xlo) & (vx <= xhi) & (np.abs(vy) <= half))
    ce, se = c[e_pose], s[e_pose]
    x, y = pose_xy(ce, se, e_idx)
    x1, y1 = pose_xy(ce, se, (e_idx + 1) % n)
    edge = np.flatnonzero((np.minimum(x, x1) <= xhi + margin) & (np.maximum(x, x1) >= xlo - margin)
                          & (np.minimum(y, y1) <= half + margin) & (np.maximum(y, y1) >= -half - margin))
    # only the kept points are gathered into (M, 2) arrays (the same values, fewer copies)
    return Window(e_pose[edge], np.column_stack([x[edge], y[edge]]), np.column_stack([x1[edge], y1[edge]]),
                  v_pose[vertex], np.column_stack([vx[vertex], vy[vertex]]))


@dataclass(frozen=True)
class RadialBand:
    """Least (``rmin``) and greatest (``rmax``) distance (mm) from its axis of the outline's
    edges seen near each body-angle bin (inf / -inf where no edge is that near)."""

    rmin: np.ndarray
    rmax: np.ndarray

    @property
    def bins(self) -> int:
        """Body-angle bins over the full turn (count)."""
        return len(self.rmin)


def radial_band(outline: SortedOutline, half_width: float, bins: int) -> RadialBand | None:
    """The outline's radial band over ``bins`` body-angle bins, each seeing the edges within
    ``half_width`` rad of it. None when the bins would not narrow anything down."""
    if not half_width < 0.5:
        return None
    points = outline.points
    nxt = np.roll(points, -1, axis=0)
    d = nxt - points
    dd = np.einsum("ij,ij->i", d, d)
    t_near = np.clip(-np.einsum("ij,ij->i", points, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    lo = np.hypot(points[:, 0] + t_near * d[:, 0], points[:, 1] + t_near * d[:, 1])
    hi = np.maximum(np.hypot(points[:, 0], points[:, 1]), np.hypot(nxt[:, 0], nxt[:, 1]))
    a0 = np.arctan2(points[:, 1], points[:, 0])
    sweep = wrap(np.arctan2(nxt[:, 1], nxt[:, 0]) - a0)
    start = np.where(sweep >= 0.0, a0, a0 + sweep)
    sweep = np.where(lo > 1e-9 * np.maximum(hi, 1.0), np.abs(sweep), 2.0 * np.pi)
    width = 2.0 * np.pi / bins
    grow = half_width + 1e-6
    b0 = np.floor(np.mod(start - grow, 2.0 * np.pi) / width).astype(np.intp)
    count = np.minimum(np.floor((sweep + 2.0 * grow) / width).astype(np.intp) + 2, bins)
    return RadialBand(_over_ranges(np.minimum, lo, b0, count, bins, np.inf),
                      _over_ranges(np.maximum, hi, b0, count, bins, -np.inf))


def _over_ranges(op: np.ufunc, values: np.ndarray, first: np.ndarray, count: np.ndarray,
                 bins: int, empty: float) -> np.ndarray:
    """Per bin of a circle of ``bins``, ``op`` (np.minimum or np.maximum) of the ``values``
    whose bin ranges ``first`` .. ``first + count - 1`` (mod bins, 1 <= count <= bins) hold
    it; ``empty`` where none does.

    Each range is the union of two power-of-two blocks (its first and its last 2^L bins,
    2^L <= count < 2^(L+1)): the values are folded into per-level block tables, two entries
    per range, and each level then into the halves below it. The same values meet in each
    bin as when every bin of every range is visited, so min and max come out the same.
    """
    first = np.mod(first, bins)
    level = np.floor(np.log2(count)).astype(np.intp)
    # an exact power of two: log2 rounding cannot give a block longer than the range
    level -= (np.left_shift(1, level) > count).astype(np.intp)
    top = int(level.max(initial=0))
    span = 2 * bins          # ranges end before first + bins <= 2 bins: no wrap inside a table
    tables = np.full((top + 1, span), empty)
    for at in (first, first + count - np.left_shift(1, level)):
        op.at(tables, (level, at), values)
    for lvl in range(top, 0, -1):
        half = 1 << (lvl - 1)
        op(tables[lvl - 1], tables[lvl], out=tables[lvl - 1])
        op(tables[lvl - 1, half:], tables[lvl, :span - half], out=tables[lvl - 1, half:])
    return op(tables[0, :bins], tables[0, bins:])


def band_at(body: np.ndarray, band: RadialBand):
    """(distance from the axis, rmin, rmax) of the band at points (own frame of the band's
    outline, mm)."""
    bins = band.bins
    r = np.hypot(body[:, 0], body[:, 1])
    angle = np.arctan2(body[:, 1], body[:, 0])
    # into [0, 2 pi) as np.mod would put it (arctan2 lies in [-pi, pi]), then its bin
    np.add(angle, 2.0 * np.pi, out=angle, where=angle < 0.0)
    cell = (angle / (2.0 * np.pi / bins)).astype(np.intp)
    cell[cell >= bins] -= bins
    return r, band.rmin[cell], band.rmax[cell]


def near_band(body: np.ndarray, slack: np.ndarray | float, band: RadialBand | None,
              seen=None) -> np.ndarray:
    """Points (own frame of the band's outline, mm) within ``slack`` mm of its radial band;
    ``seen``: :func:`band_at` of the points, when already known."""
    if band is None:
        return np.ones(len(body), dtype=bool)
    r, rmin, rmax = band_at(body, band) if seen is None else seen
    return (r + slack >= rmin) & (r - slack <= rmax)
