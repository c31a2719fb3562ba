"""Rigid registration of a measured (printed) outline onto its designed outline (SPEC §11).

A part read back from a slicer's G-code lies wherever the slicer (or the user) put it on
the bed, turned by any angle. To check it against the law it must be back in its own
frame: the rigid motion that best lays it on the designed outline. The printer's offset
along the normals is a free unknown of the fit (a grown print is not pulled off centre),
and is returned with the residuals. Lengths in mm, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.geometry.planar import signed_area

#: Point spacing (mm) the outlines are resampled to before fitting: far below the
#: printer's deviation, so the fit sees the shape, not the slicer's point density.
SPACING = 0.02
#: Angular bins of the coarse (radial signature) search: 0.1 deg, well inside the fine
#: fit's reach (a tenth of a tooth pitch on any gear we draw).
BINS = 3600


@dataclass(frozen=True)
class Registration:
    """``moving`` mapped onto ``fixed``: rotation ``angle`` (rad, about the origin) then
    ``shift`` (mm); ``offset`` the mean deviation along the fixed outline's outward normal
    (mm, + grown), ``rms`` and ``largest`` the deviation from that mean (mm)."""

    angle: float
    shift: np.ndarray
    offset: float
    rms: float
    largest: float

    def apply(self, points: np.ndarray) -> np.ndarray:
        c, s = np.cos(self.angle), np.sin(self.angle)
        return np.asarray(points, float) @ np.array([[c, s], [-s, c]]) + self.shift

    def undo(self, points: np.ndarray) -> np.ndarray:
        """``points`` of the fixed frame (N, 2) mm in the moving one: :meth:`apply` undone."""
        c, s = np.cos(self.angle), np.sin(self.angle)
        return (np.asarray(points, float) - self.shift) @ np.array([[c, -s], [s, c]])


def resample_ring(ring: np.ndarray, spacing: float = SPACING) -> np.ndarray:
    """Points every ``spacing`` mm (about) along the closed ring (N, 2)."""
    closed = np.vstack([ring, ring[:1]])
    step = np.hypot(*np.diff(closed, axis=0).T)
    length = np.concatenate([[0.0], np.cumsum(step)])
    count = max(8, int(np.ceil(length[-1] / spacing)))
    at = np.linspace(0.0, length[-1], count, endpoint=False)
    return np.column_stack([np.interp(at, length, closed[:, 0]), np.interp(at, length, closed[:, 1])])


def area_centroid(ring: np.ndarray) -> np.ndarray:
    """Centroid (mm) of the area the closed ring (N, 2) bounds."""
    x, y = ring[:, 0], ring[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * cross.sum()
    return np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6.0 * area)


def _signature(points: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """Largest radius (mm) per angular bin round ``centre``, empty bins interpolated."""
    rel = points - centre
    bins = (np.floor((np.arctan2(rel[:, 1], rel[:, 0]) % (2 * np.pi)) / (2 * np.pi) * BINS)
            .astype(int) % BINS)
    sig = np.full(BINS, -1.0)
    np.maximum.at(sig, bins, np.hypot(rel[:, 0], rel[:, 1]))
    filled = sig >= 0
    index = np.arange(BINS)
    return np.interp(index, index[filled], sig[filled], period=BINS)


def coarse_angle(moving: np.ndarray, fixed: np.ndarray) -> float:
    """The rotation (rad) that best turns ``moving`` (about its centroid) onto ``fixed``
    (about its), to one bin, by circular cross-correlation of their radial signatures."""
    a = _signature(moving, area_centroid(moving))
    b = _signature(fixed, area_centroid(fixed))
    corr = np.fft.irfft(np.fft.rfft(b - b.mean()) * np.conj(np.fft.rfft(a - a.mean())), BINS)
    return 2.0 * np.pi * int(np.argmax(corr)) / BINS


def _normals(ring: np.ndarray) -> np.ndarray:
    """Outward unit normals of a counter-clockwise ring (central differences)."""
    tangent = np.roll(ring, -1, axis=0) - np.roll(ring, 1, axis=0)
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])
    return normal / np.maximum(np.hypot(normal[:, 0], normal[:, 1]), 1e-300)[:, None]


def register(moving: np.ndarray, fixed: np.ndarray, rounds: int = 40) -> Registration:
    """The rigid motion laying the closed outline ``moving`` on ``fixed`` (both (N, 2) mm,
    any orientation): coarse angle from the radial signatures, then point-to-line
    least squares with a free normal offset until the motion moves by less than 0.1 um."""
    from scipy.spatial import cKDTree

    def ccw(ring):
        ring = np.asarray(ring, float)
        return ring if signed_area(ring) > 0 else ring[::-1]

    moving, fixed = resample_ring(ccw(moving)), resample_ring(ccw(fixed))
    normals, tree = _normals(fixed), cKDTree(fixed)
    angle = coarse_angle(moving, fixed)
    c, s = np.cos(angle), np.sin(angle)
    rot = np.array([[c, s], [-s, c]])
    shift = area_centroid(fixed) - area_centroid(moving) @ rot
    for _ in range(rounds):
        placed = moving @ rot + shift
        _, nearest = tree.query(placed)
        n, q = normals[nearest], fixed[nearest]
        centre = placed.mean(axis=0)
        lever = placed - centre
        # d(residual)/d(rotation, shift x, shift y, offset): a small turn about ``centre``
        columns = np.column_stack([lever[:, 0] * n[:, 1] - lever[:, 1] * n[:, 0], n[:, 0], n[:, 1],
                                   -np.ones(len(n))])
        residual = np.einsum("ij,ij->i", placed - q, n)
        step = np.linalg.lstsq(columns, -residual, rcond=None)[0]
        c, s = np.cos(step[0]), np.sin(step[0])
        turn = np.array([[c, s], [-s, c]])
        rot = rot @ turn
        shift = (shift - centre) @ turn + centre + step[1:3]
        if abs(step[0]) * 200.0 + np.hypot(step[1], step[2]) < 1e-7:
            break
    placed = moving @ rot + shift
    _, nearest = tree.query(placed)
    deviation = np.einsum("ij,ij->i", placed - fixed[nearest], normals[nearest])
    offset = float(deviation.mean())
    spread = deviation - offset
    return Registration(float(np.arctan2(rot[0, 1], rot[0, 0])), shift, offset,
                        float(np.sqrt(np.mean(spread ** 2))), float(np.abs(spread).max()))
