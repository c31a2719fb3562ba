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
    from build123d import Face, Wire, extrude

    def wire(ring):
        return Wire([_edge(edge) for edge in fit_ring(np.asarray(ring, dtype=float), settings)])

    return extrude(Face(wire(face.outline), [wire(h) for h in face.holes]), amount=float(thickness))


def _edge(spline):
    """The OpenCASCADE edge of a fitted B-spline in the plane z = 0, its knots given with
    their exact multiplicities (build123d's ``Edge.make_bspline`` merges knots closer than
    1e-6, which a fit's knots may be, and then the poles no longer match)."""
    from build123d import Edge
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    try:                       # OCP 7.8 and later (build123d 0.9+) name the arrays this way
        from OCP.collections import Array1_double as Reals, Array1_gp_Pnt as Points, Array1_int as Counts
    except ImportError:        # older OCP: the OpenCASCADE names
        from OCP.TColgp import TColgp_Array1OfPnt as Points
        from OCP.TColStd import TColStd_Array1OfInteger as Counts, TColStd_Array1OfReal as Reals

    knots, counts = np.unique(np.asarray(spline.knots, dtype=float), return_counts=True)
    poles = Points(1, len(spline.poles))
    for i, (x, y) in enumerate(spline.poles, start=1):
        poles.SetValue(i, gp_Pnt(float(x), float(y), 0.0))
    values, multiplicities = Reals(1, len(knots)), Counts(1, len(knots))
    for i, (knot, count) in enumerate(zip(knots, counts), start=1):
        values.SetValue(i, float(knot))
        multiplicities.SetValue(i, int(count))
    curve = Geom_BSplineCurve(poles, values, multiplicities, int(spline.degree))
    return Edge(BRepBuilderAPI_MakeEdge(curve).Edge())


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
