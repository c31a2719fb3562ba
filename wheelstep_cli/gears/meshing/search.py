"""One batch of poses: both outlines posed, contacts searched in two passes, overlap measured.

A first pass looks only for contacts within the settings' reach (rad) and skips
vertices and edges whose radial band cannot meet the other outline that close; a
pose not settled within the reach is searched again over all pairs. Both passes give
the same result where the first settles. Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.gears.meshing.contacts import edge_table, gaps, rotations_to_touch
from wheelstep_cli.gears.meshing.interference import contains, depth, posed_overlap_area
from wheelstep_cli.gears.meshing.outlines import (MeshWindow, Pose, RadialBand, SortedOutline,
                                                  Window, band_at, near_band, posed_window,
                                                  radial_band, sector, sorted_outline, turn)
from wheelstep_cli.gears.meshing.settings import MeshingSettings
from wheelstep_cli.geometry.planar import prepared_polygon


@dataclass(frozen=True)
class Pair:
    """Both outlines prepared for the check, the mesh window and its angular sectors.

    ``pinion_body`` / ``wheel_body``: prepared polygons (one per thread). ``centre``: the
    wheel axis (mm). ``wheel_band``: radial band of the wheel seen by pinion vertices
    within the reach; ``pinion_band``: of the pinion seen by wheel vertices.
    """

    pinion: SortedOutline
    wheel: SortedOutline
    pinion_body: object
    wheel_body: object
    centre: np.ndarray
    box: MeshWindow
    pinion_sector: tuple[float, float] | None
    wheel_sector: tuple[float, float] | None
    wheel_band: RadialBand | None
    pinion_band: RadialBand | None


def prepare(pinion: np.ndarray, wheel: np.ndarray, distance: float, box: MeshWindow,
            settings: MeshingSettings) -> Pair:
    """The :class:`Pair` of two outlines (N, 2) mm at centre distance ``distance`` mm."""
    long_edge = settings.long_edge * box.half_height
    p, w = sorted_outline(pinion, long_edge), sorted_outline(wheel, long_edge)
    centre = np.array([distance, 0.0])
    reach = settings.reach
    # A wheel vertex turning by the reach about the wheel axis moves at most `move` mm, and
    # a point of a wheel edge lies within half its length of the edge's midpoint; seen
    # from the pinion axis (at least `near` mm away in the window) that is an angle of
    # asin(move / near) at most. Likewise a pinion edge's points, from the wheel axis.
    move = reach * float(np.hypot(wheel[:, 0], wheel[:, 1]).max()) + 0.5 * w.e_length
    near = box.x_lo - box.margin - w.e_length
    pinion_band = (radial_band(p, float(np.arcsin(move / near)), settings.band_bins)
                   if 0.0 < move < 0.5 * near else None)
    near_w = distance - box.x_hi - box.margin - p.e_length
    wheel_band = (radial_band(w, reach + float(np.arcsin(0.5 * p.e_length / near_w)),
                              settings.band_bins)
                  if 0.5 * p.e_length < 0.5 * near_w else None)
    return Pair(p, w, prepared_polygon(pinion), prepared_polygon(wheel), centre, box,
                sector(box, np.zeros(2), p.e_length), sector(box, centre, w.e_length),
                wheel_band, pinion_band)


@dataclass(frozen=True)
class Side:
    """The vertices of one outline against the edges of the other, relative to the wheel axis.

    ``inside``: per vertex, inside the other outline; ``near``: per vertex, and
    ``e_near``: per edge, able to meet the other outline within the reach. ``sign``:
    +1 for pinion vertices, -1 for wheel vertices (see :func:`rotations_to_touch`).
    """

    verts: Window
    inside: np.ndarray
    near: np.ndarray
    edges: Window
    e_near: np.ndarray
    sign: float


def posed_sides(pair: Pair, theta: np.ndarray, phi: np.ndarray, reach: float) -> tuple[Side, Side]:
    """Both sides of a batch of poses (pinion angles ``theta``, wheel angles ``phi``, rad)."""
    centre, box = pair.centre, pair.box
    pw = posed_window(pair.pinion, Pose(-theta, None, pair.pinion_sector, theta), box)
    ww = posed_window(pair.wheel, Pose(np.pi + phi, centre, pair.wheel_sector, -np.pi - phi), box)
    # each pose's turns into the wheel's and the pinion's own frames (cosine, sine per pose)
    to_wheel = -(np.pi + phi)
    cw, sw, cp, sp = np.cos(to_wheel), np.sin(to_wheel), np.cos(theta), np.sin(theta)
    # vertices inside the other outline, tested in that outline's own frame
    pv_body = turn(pw.v - centre, cw[pw.v_pose], sw[pw.v_pose])
    wv_body = turn(ww.v, cp[ww.v_pose], sp[ww.v_pose])
    # where the vertices fall in the other outline's band: asked twice below, found once
    pv_seen = band_at(pv_body, pair.wheel_band) if pair.wheel_band is not None else None
    wv_seen = band_at(wv_body, pair.pinion_band) if pair.pinion_band is not None else None
    p_inside = contains(pair.wheel_body, pv_body, pair.wheel_band, pv_seen)
    w_inside = contains(pair.pinion_body, wv_body, pair.pinion_band, wv_seen)
    pw, ww = pw.shifted(centre), ww.shifted(centre)
    # vertices and edges that cannot meet the other outline within the reach (radial bands)
    rho_w = np.hypot(ww.v[:, 0], ww.v[:, 1])
    p_near = near_band(pv_body, 1e-9, pair.wheel_band, pv_seen)
    w_near = near_band(wv_body, reach * rho_w + 1e-9, pair.pinion_band, wv_seen)
    w_half, p_half = (0.5 * np.hypot(*(e.e1 - e.e0).T) for e in (ww, pw))
    mid = lambda e: 0.5 * (e.e0 + e.e1)  # noqa: E731
    # wheel edges: crossed by a pinion vertex that turned at most the reach about the wheel axis
    we_near = near_band(turn(mid(ww) + centre, cp[ww.e_pose], sp[ww.e_pose]),
                        reach * np.sqrt(np.maximum(np.einsum("ij,ij->i", ww.e0, ww.e0),
                                                   np.einsum("ij,ij->i", ww.e1, ww.e1)))
                        + w_half + 1e-9, pair.pinion_band)
    # pinion edges: crossed by a wheel vertex at the same radius and within the reach of angle
    pe_near = near_band(turn(mid(pw), cw[pw.e_pose], sw[pw.e_pose]), p_half + 1e-9,
                        pair.wheel_band)
    # the bands' angular margins allow for short edges only: never skip a longer one
    we_near |= w_half > 0.5 * pair.wheel.e_length
    pe_near |= p_half > 0.5 * pair.pinion.e_length
    return (Side(pw, p_inside, p_near, ww, we_near, 1.0),
            Side(ww, w_inside, w_near, pw, pe_near, -1.0))


def _pose_minima(sides: tuple[Side, Side], poses: int, reach: float, active: np.ndarray,
                 max_pairs: int):
    """(backwards, forwards, unsettled) per pose: the smallest signed gaps (rad) of the
    ``active`` poses within ``reach`` rad, and the poses that reach cannot settle."""
    back, fwd = np.full(poses, np.inf), np.full(poses, np.inf)
    unsettled = np.zeros(poses, dtype=bool)
    for side in sides:
        verts, edges, inside = side.verts, side.edges, side.inside
        sel = active[verts.v_pose]
        esel = active[edges.e_pose]
        if np.isfinite(reach):
            # a far vertex inside the other outline has no exit within reach
            unsettled[verts.v_pose[sel & ~side.near & inside]] = True
            sel &= side.near
            esel &= side.e_near
        table = edge_table(Window(edges.e_pose[esel], edges.e0[esel], edges.e1[esel],
                                  edges.v_pose, edges.v))
        v_back, v_fwd = rotations_to_touch(verts.v[sel], verts.v_pose[sel], table, side.sign,
                                           reach, max_pairs)
        drive, coast = gaps(v_back, v_fwd, inside[sel])
        np.minimum.at(back, verts.v_pose[sel], drive)
        np.minimum.at(fwd, verts.v_pose[sel], coast)
        lost = inside[sel] & np.isinf(v_back) & np.isinf(v_fwd)
        unsettled[verts.v_pose[sel][lost]] = True
    return back, fwd, unsettled


@dataclass(frozen=True)
class PoseContacts:
    """Per pose of a batch: wheel rotations (rad) backwards / forwards to contact (inf: none
    found), interference at the law's angle, overlapping area (mm^2; NaN when not measured),
    penetration (mm)."""

    back: np.ndarray
    fwd: np.ndarray
    interference: np.ndarray
    area: np.ndarray
    depth: np.ndarray


def batch_contacts(pair: Pair, theta: np.ndarray, phi: np.ndarray,
                   settings: MeshingSettings) -> PoseContacts:
    """Contacts and interference of a batch of poses (pinion ``theta``, wheel ``phi``, rad)."""
    poses, reach = len(theta), settings.reach
    sides = posed_sides(pair, theta, phi, reach)
    interference = np.zeros(poses, dtype=bool)
    for side in sides:
        interference[side.verts.v_pose[side.inside]] = True
    searched = np.ones(poses, dtype=bool) if settings.contacts_where_jammed else ~interference
    # first only rotations within the reach: exact wherever a contact lies that close; the
    # other poses again without the limit
    back, fwd, unsettled = _pose_minima(sides, poses, reach, searched, settings.max_pairs)
    redo = searched & (unsettled | ~(back <= reach) | ~(fwd <= reach))
    if redo.any():
        back_all, fwd_all, _ = _pose_minima(sides, poses, np.inf, redo, settings.max_pairs)
        back[redo], fwd[redo] = back_all[redo], fwd_all[redo]
    area = np.zeros(poses) if settings.overlap_area else np.full(poses, np.nan)
    deepest = np.zeros(poses)
    if interference.any() and settings.overlap_area:
        area[interference] = posed_overlap_area((pair.pinion_body, pair.wheel_body),
                                                (pair.pinion.points, pair.wheel.points),
                                                theta[interference], phi[interference],
                                                pair.centre, pair.box)
    if interference.any():
        for side in sides:
            verts, inside = side.verts, side.inside
            np.maximum.at(deepest, verts.v_pose[inside],
                          depth(verts.v[inside], verts.v_pose[inside], side.edges,
                                settings.max_pairs))
    return PoseContacts(back, fwd, interference, area, deepest)
