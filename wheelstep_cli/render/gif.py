"""GIF bytes of a matplotlib animation (the figure is closed afterwards)."""

from __future__ import annotations

import os
import tempfile


def animation_gif(fig, frame, frames, fps: int, metadata: dict | None = None) -> bytes:
    """Render ``frame`` over ``frames`` (a count or a sequence) on ``fig`` at ``fps`` frames per
    second into GIF bytes; ``metadata`` {} writes none (the Pillow writer needs a file path,
    so a temporary file carries the bytes)."""
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    anim = FuncAnimation(fig, frame, frames=frames, blit=False)
    fd, tmp = tempfile.mkstemp(suffix=".gif")
    os.close(fd)
    try:
        anim.save(tmp, writer=PillowWriter(fps=fps, metadata=metadata))
        with open(tmp, "rb") as fh:
            return fh.read()
    finally:
        os.unlink(tmp)
        plt.close(fig)
