"""The files the mechanism commands write besides their report: tables (CSV), drawings
(DXF), plots (PNG) and animations (GIF), each as path -> bytes; only those asked for
(a path given) are made."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from wheelstep_cli.formats.jsonio import csv_bytes


def kinematics_files(design, kin, plot: Path | None, law: str = "the crank law") -> dict[Path, bytes]:
    """The hub-speed plot of a ``CrankMechanism`` and its ``HubKinematics`` (gears on ``law``)."""
    from wheelstep_cli.render.mechanism_plots import kinematics_png

    return {} if plot is None else {plot: kinematics_png(design, kin, law)}


def stairs_files(study, plot: Path | None) -> dict[Path, bytes]:
    """The climb/descent plot of a ``StairStudy``."""
    from wheelstep_cli.render.mechanism_plots import stair_study_png

    return {} if plot is None else {plot: stair_study_png(study)}


def linkage_files(study, csv: Path | None, plot: Path | None, gif: Path | None,
                  gif_frames: int) -> dict[Path, bytes]:
    """Of a ``LinkageStudy``: the foot path at every sample (CSV), the path and speed plot
    (PNG) and an animation of one crank turn in ``gif_frames`` frames at most (GIF)."""
    from wheelstep_cli.mechanism.linkage.study import path_table

    files = {}
    if csv is not None:
        files[csv] = csv_bytes(*path_table(study))
    if plot is not None:
        from wheelstep_cli.render.mechanism_plots import linkage_png

        files[plot] = linkage_png(study.leg, study.solution, study.gait, study.rpm)
    if gif is not None:
        from wheelstep_cli.render.mechanism_plots import linkage_gif

        frames = min(gif_frames, study.request.samples)
        files[gif] = linkage_gif(study.leg, study.solution, study.gait, frames)
    return files


def trajectory_files(study, csv: Path | None, dxf: Path | None, polyline: bool,
                     plot: Path | None) -> dict[Path, bytes]:
    """Of a ``TrajectoryStudy``: the samples (CSV: x, y, piece), the path as DXF (line and
    arcs, or one closed ``polyline`` with arc bulges) and a plot (PNG)."""
    path = study.path
    files = {}
    if csv is not None:
        files[csv] = csv_bytes(["x_mm", "y_mm", "piece"], np.column_stack([study.points, study.pieces]),
                               ["%.6f", "%.6f", "%d"])
    if dxf is not None:
        from wheelstep_cli.formats.dxf import path_dxf_bytes

        files[dxf] = path_dxf_bytes(path.pieces, polyline=polyline)
    if plot is not None:
        from wheelstep_cli.render.mechanism_plots import trajectory_png

        title = (f"foot path: H = {path.support_length:g}, r1 = {path.r1:g}, r2 = {path.r2:g}, "
                 f"r3 = {path.r3:.2f}, h_max = {path.h_max:.2f} mm")
        files[plot] = trajectory_png(path, study.points, study.pieces, title)
    return files
