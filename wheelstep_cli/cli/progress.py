"""Progress bars on stderr (rich), for every command that runs long; none with ``-q``."""

from __future__ import annotations

from typing import Callable


class Progress:
    """A context manager holding rich progress bars on stderr.

    ``bars.counter(description)`` gives a ``progress(done, total)`` callback (the meshing
    check's); ``bars(stage, total)`` adds a bar and gives its ``advance()`` (the batch's).
    ``transient`` bars vanish when done; ``enabled=False``, or stderr not a terminal, shows
    nothing.
    """

    def __init__(self, enabled: bool = True, transient: bool = True):
        self.enabled = enabled
        self.transient = transient
        self.bar = None

    def __enter__(self) -> "Progress":
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, TextColumn, TimeElapsedColumn
        from rich.progress import Progress as RichProgress

        console = Console(stderr=True)
        # bars are for a person at a terminal: redirected to a file or a pipe, rich would
        # leave a blank line on stderr, and a refusal must be its only line
        self.bar = RichProgress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                                TimeElapsedColumn(), console=console, transient=self.transient,
                                disable=not (self.enabled and console.is_terminal))
        self.bar.__enter__()
        return self

    def __exit__(self, *exc):
        return self.bar.__exit__(*exc)

    def counter(self, description: str) -> Callable[[int, int], None]:
        """A callback ``(done, total)`` moving one bar."""
        task = self.bar.add_task(description, total=None)
        return lambda done, total: self.bar.update(task, completed=done, total=total)

    def __call__(self, stage: str, total: int) -> Callable[[], None]:
        """A new bar of ``total`` steps; returns the callable advancing it by one."""
        task = self.bar.add_task(stage, total=total)
        return lambda: self.bar.advance(task)


def with_progress(enabled: bool, description: str, check, *args, **kwargs):
    """Run ``check(*args, progress=callback, **kwargs)`` under one transient bar."""
    with Progress(enabled) as bars:
        return check(*args, progress=bars.counter(description), **kwargs)


def terminal_note(enabled: bool, text: str) -> None:
    """``text`` on stderr for a person at a terminal (why the wait that follows), as the bars
    are: redirected, stderr keeps only what the command says (a refusal's one line)."""
    from rich.console import Console

    console = Console(stderr=True, highlight=False)
    if enabled and console.is_terminal:
        console.print(text, markup=False)
