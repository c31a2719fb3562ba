"""The summary plot of a sweep: every computed design by two objectives, the Pareto front
(smaller is better on both) drawn as a line, as PNG. matplotlib (Agg) imported lazily."""

from __future__ import annotations


#: Front points labelled at most (a denser front would bury the plot in its labels).
MOST_LABELS = 12


def pareto_png(first, second, front, names: tuple[str, str], title: str, labels=None) -> bytes:
    """A PNG of the designs (``first``, ``second``: their two objectives, ``front``: on the
    Pareto front or not), the front highlighted, each front point named by its ``labels``
    entry (the design's varied values; at most :data:`MOST_LABELS`, spread along the front);
    deterministic bytes (no PNG timestamp)."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    rest = [(a, b) for a, b, f in zip(first, second, front) if not f]
    named = labels if labels is not None else [""] * len(front)
    best = sorted((a, b, n) for a, b, f, n in zip(first, second, front, named) if f)
    if rest:
        ax.scatter(*zip(*rest), s=14, c="0.6", label="designs")
    if best:
        ax.plot([p[0] for p in best], [p[1] for p in best], "o-", c="tab:red", ms=5, lw=1.2,
                label=f"Pareto front ({len(best)})")
        # a label right of the middle runs to the left of its point, so that it stays in the figure
        middle = 0.5 * (min(first) + max(first))
        for a, b, name in labelled(best):
            right = a > middle
            ax.annotate(name, (a, b), textcoords="offset points", xytext=(-4 if right else 4, 4), fontsize=7,
                        color="tab:red", ha="right" if right else "left")
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


def labelled(best: list[tuple]) -> list[tuple]:
    """The front points (``best``: (first, second, label) in front order) that get their label:
    all of them, or :data:`MOST_LABELS` spread evenly along the front, both ends included."""
    if len(best) <= MOST_LABELS:
        return list(best)
    picked = sorted({round(k * (len(best) - 1) / (MOST_LABELS - 1)) for k in range(MOST_LABELS)})
    return [best[k] for k in picked]
