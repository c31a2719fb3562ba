"""Pictures and 2D/CAD exports of a built gear pair: ``--plot``, ``--gif`` (to the paths
given), ``--dxf``, ``--svg``, ``--step`` (pinion.* and wheel.* in the output folder).

Each as path -> bytes; only those asked for. The faces come from :mod:`parts.gear_faces`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from wheelstep_cli.errors import require
from wheelstep_cli.parts.gear_faces import gear_faces


@dataclass(frozen=True)
class GearExtras:
    """What ``gears`` writes besides the meshes: ``plot`` (PNG/SVG path), ``gif`` (GIF path),
    and the per-gear ``dxf``, ``svg`` and ``step`` files in the output folder."""

    plot: Path | None = None
    gif: Path | None = None
    dxf: bool = False
    svg: bool = False
    step: bool = False


def checked_extras(plot: Path | None = None, gif: Path | None = None, dxf: bool = False,
                   svg: bool = False, step: bool = False) -> GearExtras:
    """The extras asked for; refuses (DesignError, before anything is built) ``step`` without
    the optional CAD extra. (The pictures' extensions are their options' own check.)"""
    extras = GearExtras(plot, gif, dxf, svg, step)
    if extras.step:
        # only when asked for: the STEP writer loads scipy's spline fitting (about 1 s)
        from wheelstep_cli.formats.step import EXTRA, step_available

        require(step_available(), "step", "on", f"needs the optional CAD extra: {EXTRA}")
    return extras


def pair_drawing(pair):
    """The :class:`~wheelstep_cli.render.gear_pair_plot.PairDrawing` of a built pair."""
    from wheelstep_cli.render.gear_pair_plot import PairDrawing

    gen = pair.generated
    if gen is not None:
        law, module, teeth = gen.law, gen.module, {"pinion": gen.pinion_teeth, "wheel": gen.wheel_teeth}
    else:
        law, module = pair.law, pair.spec.tooth_form().module
        teeth = {"pinion": pair.spec.z, "wheel": pair.wheel_teeth}
    return PairDrawing(gear_faces(pair), law, pair.mounted_distance, float(module), teeth,
                       float(pair.spec.thickness), crank=pair.spec.law_csv is None)


def picture_files(pair, extras: GearExtras, report,
                  progress: Callable[[int, int], None] | None = None) -> dict[Path, bytes]:
    """``--plot`` and ``--gif`` of the pair: path -> bytes. ``report``: the meshing check's
    per-pose results (gears.meshing.MeshingReport) the GIF shows; ``progress(done, total)``
    after each GIF frame."""
    files: dict[Path, bytes] = {}
    if extras.plot is None and extras.gif is None:
        return files
    drawing = pair_drawing(pair)
    if extras.plot is not None:
        from wheelstep_cli.render.gear_pair_plot import pair_picture

        files[extras.plot] = pair_picture(drawing, extras.plot.suffix.lower()[1:])
    if extras.gif is not None:
        from wheelstep_cli.render.gear_pair_gif import pair_gif

        files[extras.gif] = pair_gif(drawing, report, progress=progress)
    return files


def export_files(pair, extras: GearExtras, out: Path,
                 progress: Callable[[int, int], None] | None = None) -> dict[Path, bytes]:
    """pinion/wheel .dxf, .svg and .step in ``out`` as asked: path -> bytes (mm, each gear in
    its own frame); ``progress(done, total)`` after each STEP solid (the slow one)."""
    files: dict[Path, bytes] = {}
    faces = gear_faces(pair)
    for name, face in faces.items():
        if extras.dxf:
            from wheelstep_cli.formats.dxf import face_dxf_bytes

            files[out / f"{name}.dxf"] = face_dxf_bytes(face)
        if extras.svg:
            from wheelstep_cli.formats.svg import face_svg_bytes

            files[out / f"{name}.svg"] = face_svg_bytes(face)
    if extras.step:
        from wheelstep_cli.formats.step import face_step_bytes

        for done, (name, face) in enumerate(faces.items(), start=1):
            files[out / f"{name}.step"] = face_step_bytes(face, float(pair.spec.thickness))
            if progress is not None:
                progress(done, len(faces))
    return files
