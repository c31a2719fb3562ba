"""Top view of a print bed with the parts' footprints, as PNG bytes (matplotlib, Agg)."""

from __future__ import annotations

import io

import numpy as np


def plate_png(bed: tuple[float, float], margin: float, shapes: list[tuple[str, list[list[np.ndarray]]]],
              title: str) -> bytes:
    """PNG of the bed rectangle (mm) with each (label, polygons) filled; polygons on bed coordinates.

    Each polygon is [outer ring, hole rings...]; holes are left open. Deterministic
    bytes: no timestamp or software tag in the PNG.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import PathPatch, Rectangle
    from matplotlib.path import Path as MplPath

    width = 7.0
    fig, ax = plt.subplots(figsize=(width, width * bed[1] / bed[0] + 0.6), dpi=110)
    ax.add_patch(Rectangle((0, 0), bed[0], bed[1], facecolor="#f4f4f0", edgecolor="black", lw=1.2))
    ax.add_patch(Rectangle((margin, margin), bed[0] - 2 * margin, bed[1] - 2 * margin, fill=False,
                           edgecolor="#999999", lw=0.6, ls="--"))
    colours = plt.get_cmap("tab10")
    for number, (label, polygons) in enumerate(shapes):
        verts, codes = [], []
        for polygon in polygons:
            for ring in polygon:
                ring = np.asarray(ring)
                verts.extend(ring.tolist() + [ring[0].tolist()])
                codes.extend([MplPath.MOVETO] + [MplPath.LINETO] * (len(ring) - 1) + [MplPath.CLOSEPOLY])
        if not verts:
            continue
        path = MplPath(np.asarray(verts), codes)
        ax.add_patch(PathPatch(path, facecolor=colours(number % 10), edgecolor="black", lw=0.4,
                               alpha=0.85))
        outer = np.asarray(polygons[0][0])
        centre = (outer.min(axis=0) + outer.max(axis=0)) / 2.0
        ax.text(centre[0], centre[1], label, ha="center", va="center", fontsize=7,
                bbox={"facecolor": "white", "alpha": 0.8, "lw": 0, "pad": 1})
    ax.set_xlim(-5, bed[0] + 5)
    ax.set_ylim(-5, bed[1] + 5)
    ax.set_aspect("equal")
    ax.set_xlabel("X (mm)")
    ax.set_ylabel("Y (mm)")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()
