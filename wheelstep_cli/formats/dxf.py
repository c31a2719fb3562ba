"""DXF of a path made of straight segments and circular arcs (ezdxf, deterministic bytes)."""

from __future__ import annotations

import io
import logging

import numpy as np


def path_dxf_bytes(pieces, polyline: bool = False, layer: str = "FOOT_PATH") -> bytes:
    """DXF R12 in mm of ``pieces`` (objects with ``start``/``end`` points or ``center``,
    ``radius``, ``start``, ``sweep`` counter-clockwise arcs), as LINE and ARC entities or as
    one closed 2D POLYLINE with bulges. R12 (no CLASSES section, whose order ezdxf takes from
    a set) and fixed metadata, so the same path gives the same bytes."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        # ezdxf.new sets the drawing units and logs that R12 does not store them: mm is the
        # documented unit of the file, and the log line is not for the person at the terminal
        quiet = logging.getLogger("ezdxf")
        level, quiet.level = quiet.level, logging.ERROR
        try:
            doc = ezdxf.new("R12", setup=False)
        finally:
            quiet.setLevel(level)
        doc.layers.add(layer)
        msp = doc.modelspace()
        attribs = {"layer": layer}
        if polyline:
            verts = []
            for p in pieces:
                if hasattr(p, "radius"):
                    a = p.start
                    x, y = p.center + p.radius * np.array([np.cos(a), np.sin(a)])
                    verts.append((float(x), float(y), float(np.tan(p.sweep / 4))))
                else:
                    verts.append((float(p.start[0]), float(p.start[1]), 0.0))
            msp.add_polyline2d(verts, format="xyb", close=True, dxfattribs=attribs)
        else:
            for p in pieces:
                if hasattr(p, "radius"):
                    msp.add_arc(tuple(float(v) for v in p.center), float(p.radius),
                                float(np.degrees(p.start)), float(np.degrees(p.start + p.sweep)),
                                dxfattribs=attribs)
                else:
                    msp.add_line(tuple(float(v) for v in p.start), tuple(float(v) for v in p.end),
                                 dxfattribs=attribs)
        buf = io.StringIO()
        doc.write(buf)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
    return buf.getvalue().encode("utf-8")


def polyline_dxf_bytes(points: np.ndarray, layer: str = "SOLE") -> bytes:
    """DXF (R2010, mm) holding ``points`` as one open LWPOLYLINE on ``layer``; deterministic."""
    return _r2010_bytes({layer: [(np.asarray(points, dtype=float), False)]})


def face_dxf_bytes(face) -> bytes:
    """DXF (R2010, $INSUNITS = 4: mm) of a gear face (``outline``, ``holes``, ``marks``:
    (N, 2) mm) as closed LWPOLYLINEs on layers OUTLINE, HOLES and MARKS; deterministic."""
    return _r2010_bytes({"OUTLINE": [(face.outline, True)],
                         "HOLES": [(hole, True) for hole in face.holes],
                         "MARKS": [(mark, True) for mark in face.marks]})


def _r2010_bytes(layers: dict[str, list[tuple[np.ndarray, bool]]]) -> bytes:
    """DXF R2010 in mm of layer -> [(points (N, 2) mm, closed)] as LWPOLYLINEs, fixed metadata."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True  # fixed dates, GUIDs, ezdxf marker
    try:
        doc = ezdxf.new("R2010", units=ezdxf.units.MM)
        msp = doc.modelspace()
        for layer, polylines in layers.items():
            doc.layers.add(layer)
            for points, closed in polylines:
                msp.add_lwpolyline(np.asarray(points, dtype=float).tolist(), format="xy",
                                   close=closed, dxfattribs={"layer": layer})
        # ezdxf registers CLASS entries from a set (hash-seed order): register them sorted first
        for dxftype in sorted(doc.entitydb.dxf_types_in_use()):
            doc.classes.add_class(dxftype)
        stream = io.StringIO()
        doc.write(stream)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
    return doc.encode(stream.getvalue())
