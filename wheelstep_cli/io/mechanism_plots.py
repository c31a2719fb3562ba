"""PNG plots and GIF animations of the mechanism analyses (stairs, linkages, trajectories).

Each function takes plain arrays/dataclasses and returns the file's bytes, so the
command can write every output atomically. matplotlib (Agg) is imported lazily.
"""

from __future__ import annotations

import io

import numpy as np


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    _plt().close(fig)
    return buf.getvalue()


def stairs_png(climb: np.ndarray, descent: np.ndarray, climb_path: np.ndarray,
               descent_path: np.ndarray, title: str) -> bytes:
    """Climb/descent kinematics (rows of phi[rad], X01, dX01, d2X01, Y01, dY01, d2Y01) and hub paths."""
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    for col, (name, kin) in enumerate((("climb", climb), ("descent", descent))):
        ax = axes[0, col]
        deg = np.degrees(kin[:, 0])
        ax.plot(deg, kin[:, 1], label="X01 (mm)")
        ax.plot(deg, kin[:, 4], label="Y01 (mm)")
        ax.plot(deg, kin[:, 2], "--", label="dX01/dphi (mm/rad)")
        ax.plot(deg, kin[:, 5], "--", label="dY01/dphi (mm/rad)")
        ax.set_xlabel("hub angle phi (deg)")
        ax.set_ylabel("mm, mm/rad")
        ax.set_title(f"{name}: one cycle (landing to landing + 90 deg)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    for col, (name, path) in enumerate((("climb", climb_path), ("descent", descent_path))):
        ax = axes[1, col]
        ax.plot(path[:, 0], path[:, 1], color="C3")
        ax.plot(path[0, 0], path[0, 1], "o", color="C3", label="first landing")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("hub x (mm)")
        ax.set_ylabel("hub y above the first tread (mm)")
        ax.set_title(f"hub path, {name}, successive steps")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    return _png(fig)
