"""Rotations to contact: for vertex/edge pairs, the wheel rotation that makes them touch.

Seen from the wheel axis, a vertex at radius rho sweeps the circle of that radius
relative to the other outline; where that circle crosses an edge, the vertex touches
it. Pairs are found by sorting, never in dense vertex x edge tables, and in chunks of
bounded size. Points relative to the wheel axis; angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.gears.meshing.outlines import Window, expand, pair_chunks, wrap


@dataclass(frozen=True)
class EdgeTable:
    """Per-edge quantities about the wheel axis: the crossing quadratic's coefficients, the
    radial extent [lo, hi] (mm) and the angular extent [start, start + sweep] (rad)."""

    e0: np.ndarray
    d: np.ndarray
    dd: np.ndarray
    ed: np.ndarray
    ee: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    start: np.ndarray
    sweep: np.ndarray
    pose: np.ndarray


def edge_table(edges: Window) -> EdgeTable:
    """The :class:`EdgeTable` of window edges given relative to the wheel axis (mm)."""
    e0, e1 = edges.e0, edges.e1
    d = e1 - e0
    dd = np.einsum("ij,ij->i", d, d)
    ed = np.einsum("ij,ij->i", e0, d)
    ee = np.einsum("ij,ij->i", e0, e0)
    t_near = np.clip(-ed / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    lo = np.hypot(e0[:, 0] + t_near * d[:, 0], e0[:, 1] + t_near * d[:, 1])
    hi = np.sqrt(np.maximum(ee, np.einsum("ij,ij->i", e1, e1)))
    a0 = np.arctan2(e0[:, 1], e0[:, 0])
    sweep = wrap(np.arctan2(e1[:, 1], e1[:, 0]) - a0)
    start = np.where(sweep >= 0.0, a0, a0 + sweep)
    # an edge through the axis is seen at every angle
    sweep = np.where(lo > 1e-12 * np.maximum(hi, 1.0), np.abs(sweep), 2.0 * np.pi)
    return EdgeTable(e0, d, dd, ed, ee, lo, hi, start, sweep, edges.e_pose)


def _angle_bins(own: np.ndarray, edges: EdgeTable, reach: float):
    """Angle bins for the pair search: (bins, each edge's first bin, its bin count, each
    vertex's bin). One bin for everything when ``reach`` is inf."""
    two_pi = 2.0 * np.pi
    if not np.isfinite(reach):
        count = len(edges.lo)
        return (1, np.zeros(count, dtype=np.intp), np.ones(count, dtype=np.intp),
                np.zeros(len(own), dtype=np.intp))
    bins = int(np.ceil(two_pi / (2.0 * reach)))
    width = two_pi / bins
    lo_angle = np.mod(edges.start - reach - 1e-9, two_pi)
    b0 = np.floor(lo_angle / width).astype(np.intp)
    b1 = np.floor((lo_angle + edges.sweep + 2.0 * reach + 2e-9) / width).astype(np.intp)
    span = np.minimum(b1 - b0 + 1, bins)
    v_bin = np.floor(np.mod(own, two_pi) / width).astype(np.intp) % bins
    return bins, b0, span, v_bin


def near_pairs(radius: np.ndarray, own: np.ndarray, r_pose: np.ndarray, edges: EdgeTable,
               reach: float, max_pairs: int):
    """Chunks (rows, cols) of the vertex/edge pairs that can touch within ``reach`` (rad).

    Pairs of the same pose whose edge's radial extent holds the vertex's radius (mm) and,
    when ``reach`` is finite, whose edge's angular extent comes within ``reach`` of the
    vertex's angle ``own``; every such pair is there. Without a dense table: vertices
    are sorted by (pose, angle bin, radius); each edge looks up, in every bin its
    angular extent (widened by ``reach``) touches, the contiguous run of vertices whose
    radius lies in its radial extent. Chunks hold at most about ``max_pairs`` pairs, so
    memory stays bounded whatever the outline sizes.
    """
    if len(radius) == 0 or len(edges.lo) == 0:
        return
    two_pi = 2.0 * np.pi
    bins, b0, span, v_bin = _angle_bins(own, edges, reach)
    stride = 2.0 * max(float(edges.hi.max()), float(radius.max())) + 1.0
    tol = 1e-9 * stride
    key = (r_pose * bins + v_bin) * stride + radius
    order = np.argsort(key)
    key_sorted = key[order]
    del key
    q_edge, k = expand(np.zeros(len(edges.lo), dtype=np.intp), span, np.arange(int(span.max())))
    base = (edges.pose[q_edge] * bins + (b0[q_edge] + k) % bins) * stride
    del k
    first = np.searchsorted(key_sorted, base + (edges.lo[q_edge] - tol), side="left")
    counts = np.searchsorted(key_sorted, base + (edges.hi[q_edge] + tol), side="right") - first
    del base
    slack = reach + 1e-9
    for rows, cols in pair_chunks(first, counts, order, q_edge, max_pairs):
        keep = (edges.lo[cols] <= radius[rows]) & (edges.hi[cols] >= radius[rows])
        if np.isfinite(reach):
            # the crossing lies in the edge's angular extent, within reach of the vertex
            keep &= (np.mod(own[rows] - edges.start[cols] + slack, two_pi)
                     <= edges.sweep[cols] + 2.0 * slack)
        yield rows[keep], cols[keep]


def rotations_to_touch(v: np.ndarray, v_pose: np.ndarray, edges: EdgeTable, sign: float,
                       reach: float, max_pairs: int):
    """Smallest wheel rotations (rad) bringing each vertex onto an edge: (backwards, forwards).

    ``v`` relative to the wheel axis (mm); a vertex at radius rho meets an edge where the
    circle of radius rho crosses it. ``sign`` = +1 for pinion vertices (they move
    +delta relative to the wheel when the wheel turns back by delta), -1 for wheel
    vertices. Only rotations up to ``reach`` are looked for (all of them when inf);
    inf where none is met. ``max_pairs`` bounds the pairs held at once.
    """
    back = np.full(len(v), np.inf)
    fwd = np.full(len(v), np.inf)
    radius = np.hypot(v[:, 0], v[:, 1])
    own = np.arctan2(v[:, 1], v[:, 0])
    for rows, cols in near_pairs(radius, own, v_pose, edges, reach, max_pairs):
        a, b, c = edges.dd[cols], edges.ed[cols], edges.ee[cols] - radius[rows] ** 2
        disc = np.sqrt(np.maximum(b * b - a * c, 0.0))
        e0, d = edges.e0[cols], edges.d[cols]
        divisor, proper = np.where(a > 0, a, 1.0), a > 0
        for root in (-1.0, 1.0):
            t = (-b + root * disc) / divisor
            ok = (t >= 0.0) & (t <= 1.0) & proper
            t, r = t[ok], rows[ok]
            angle = np.arctan2(e0[ok, 1] + t * d[ok, 1], e0[ok, 0] + t * d[ok, 0])
            delta = wrap(sign * (angle - own[r]))  # > 0: met turning the wheel backwards
            np.minimum.at(back, r[delta >= 0], delta[delta >= 0])
            np.minimum.at(fwd, r[delta <= 0], -delta[delta <= 0])
    if np.isfinite(reach):
        back[back > reach] = np.inf
        fwd[fwd > reach] = np.inf
    return back, fwd


def gaps(back: np.ndarray, fwd: np.ndarray, inside: np.ndarray):
    """Signed drive and coast gaps (rad) of vertices from their rotations to touch.

    A vertex outside has the rotation to its first touch in each direction; a vertex
    inside counts as penetrating the flank it is nearer to (smaller exit rotation): on
    the drive side that gives a negative drive gap, on the coast side a negative coast
    gap.
    """
    # drive-side penetration is the one the wheel clears by turning forwards
    drive = np.where(inside, np.where(fwd <= back, -fwd, np.inf), back)
    coast = np.where(inside, np.where(back < fwd, -back, np.inf), fwd)
    return drive, coast
