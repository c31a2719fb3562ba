"""Outlines moved as a print may lay them down, and the meshing figures to compare checks by."""

from __future__ import annotations

import numpy as np


def turned(outline: np.ndarray, angle: float, centre: float = 0.0, width: float = np.inf) -> np.ndarray:
    """``outline`` (N, 2) mm with its points within ``width`` / 2 rad of body angle ``centre``
    (by default all: the whole outline) turned by ``angle`` rad (counter-clockwise) about the
    origin."""
    body = np.arctan2(outline[:, 1], outline[:, 0])
    near = np.abs(np.angle(np.exp(1j * (body - centre)))) < width / 2.0
    c, s = np.cos(angle), np.sin(angle)
    return np.where(near[:, None], outline @ np.array([[c, s], [-s, c]]), outline)


def mesh_figures(report) -> np.ndarray:
    """A meshing report's figures of merit (SPEC §10): per flank F'i, f'i (um), ripple (%),
    then the least and largest backlash (um on the wheel pitch curve)."""
    return np.array([report.drive.total_um, report.drive.tooth_um, 100.0 * report.drive.ripple,
                     report.coast.total_um, report.coast.tooth_um, 100.0 * report.coast.ripple,
                     1000.0 * float(np.min(report.backlash_mm)), 1000.0 * float(np.max(report.backlash_mm))])
