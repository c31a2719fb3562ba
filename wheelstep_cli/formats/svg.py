"""SVG of a gear face in millimetres (width/height in mm, viewBox in mm, y up as drawn)."""

from __future__ import annotations

import numpy as np

MARGIN_MM = 2.0


def _path(rings) -> str:
    """SVG path data of closed rings ((N, 2) mm), y mirrored (SVG's y points down)."""
    parts = []
    for ring in rings:
        pts = np.asarray(ring, dtype=float)
        head = f"M{pts[0, 0]:.4f} {-pts[0, 1]:.4f}"
        parts.append(head + "".join(f"L{x:.4f} {-y:.4f}" for x, y in pts[1:]) + "Z")
    return "".join(parts)


def face_svg_bytes(face) -> bytes:
    """SVG 1.1 of a gear face (``name``, ``outline``, ``holes``, ``marks``: (N, 2) mm): the
    outline with its holes as one even-odd filled path (a cutting contour), the marks as
    closed stroked paths; 1 user unit = 1 mm; deterministic."""
    rings = [face.outline, *face.holes, *face.marks]
    pts = np.concatenate([np.asarray(r, dtype=float) for r in rings])
    x0, y0 = pts[:, 0].min() - MARGIN_MM, -pts[:, 1].max() - MARGIN_MM
    w = pts[:, 0].max() - pts[:, 0].min() + 2 * MARGIN_MM
    h = pts[:, 1].max() - pts[:, 1].min() + 2 * MARGIN_MM
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w:.4f}mm" '
             f'height="{h:.4f}mm" viewBox="{x0:.4f} {y0:.4f} {w:.4f} {h:.4f}">',
             f'<title>wheelstep {face.name} (mm)</title>',
             f'<path id="outline" fill="#d9d9d9" fill-rule="evenodd" stroke="#000000" '
             f'stroke-width="0.1" d="{_path([face.outline, *face.holes])}"/>']
    if face.marks:
        lines.append(f'<path id="marks" fill="none" stroke="#c00000" stroke-width="0.2" '
                     f'd="{_path(face.marks)}"/>')
    lines.append("</svg>")
    return ("\n".join(lines) + "\n").encode("utf-8")
