"""The summary plot of a sweep: every computed design by two objectives, the Pareto front
(smaller is better on both) drawn as a line, as PNG. matplotlib (Agg) imported lazily."""

from __future__ import annotations


def pareto_png(first, second, front, names: tuple[str, str], title: str) -> bytes:
    """A PNG of the designs (``first``, ``second``: their two objectives, ``front``: on the
    Pareto front or not), the front highlighted; deterministic bytes (no PNG timestamp)."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    rest = [(a, b) for a, b, f in zip(first, second, front) if not f]
    best = sorted((a, b) for a, b, f in zip(first, second, front) if f)
    if rest:
        ax.scatter(*zip(*rest), s=14, c="0.6", label="designs")
    if best:
        ax.plot(*zip(*best), "o-", c="tab:red", ms=5, lw=1.2, label=f"Pareto front ({len(best)})")
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1])
    ax.set_title(title)
    ax.grid(alpha=0.3)
    if rest or best:
        ax.legend(loc="best")
    else:
        ax.text(0.5, 0.5, "no design computed both figures", ha="center", transform=ax.transAxes)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90, metadata={"Software": None})
    plt.close(fig)
    return buffer.getvalue()
