"""STEP (AP214, mm) of extruded gear faces, through the optional ``cad`` extra (build123d).

The side faces are the outlines fitted as cubic B-splines within a stated distance of the
written outline (geometry.spline_fit, 5 um by default), so a CAD kernel meets a few hundred
faces a gear rather than one per outline segment (figures in benchmarks/results.md)."""

from __future__ import annotations

import io
import re

import numpy as np

from wheelstep_cli.geometry.spline_fit import FitSettings, fit_ring

EXTRA = "pip install wheelstep[cad]"
#: the header's time stamp, fixed so the same solid gives the same bytes
TIMESTAMP = "2000-01-01T00:00:00"


def step_available() -> bool:
    """True when build123d (the ``cad`` extra) can be imported."""
    import importlib.util

    return importlib.util.find_spec("build123d") is not None


def face_solid(face, thickness: float, settings: FitSettings = FitSettings()):
    """The build123d solid of a gear face (``outline``, ``holes``: (N, 2) mm) extruded by
    ``thickness`` mm along +Z, each ring as fitted B-spline edges within
    ``settings.tolerance`` mm of it (geometry.spline_fit). Marks are not cut (they are
    engraved in the printed meshes)."""
    from build123d import Edge, Face, Wire, extrude

    def wire(ring):
        return Wire([Edge.make_bspline([(float(x), float(y), 0.0) for x, y in edge.poles],
                                       edge.knots.tolist(), edge.degree)
                     for edge in fit_ring(np.asarray(ring, dtype=float), settings)])

    return extrude(Face(wire(face.outline), [wire(h) for h in face.holes]), amount=float(thickness))


def face_step_bytes(face, thickness: float, settings: FitSettings = FitSettings()) -> bytes:
    """STEP bytes of :func:`face_solid`, in mm, the header's time stamp fixed."""
    from build123d import export_step

    solid = face_solid(face, thickness, settings)
    solid.label = f"wheelstep {face.name}"
    buf = io.BytesIO()
    export_step(solid, buf, timestamp=TIMESTAMP)
    # the writer also names the time of day in FILE_NAME when given a date only: keep it fixed
    return re.sub(rb"(FILE_NAME\('[^']*',')[^']*'", rb"\g<1>" + TIMESTAMP.encode() + rb"'",
                  buf.getvalue(), count=1)
