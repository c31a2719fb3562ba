"""``wheelstep batch``: build a YAML list of parts into plates, a manifest and a print sheet."""

from __future__ import annotations

from pathlib import Path

import typer

Opt = typer.Option


def batch(
    file: Path = typer.Argument(..., help="Batch YAML: parts with kind, design, overrides, quantity, printer."),
    out: Path = Opt(Path("wheelstep-batch"), "--out", "-o", help="Output folder."),
    jobs: int = Opt(0, "--jobs", "-j", help="Worker processes; 0 = one per CPU core."),
) -> None:
    """Build every part of a batch file into packed 3MF plates with PNG previews,
    manifest.json and print-sheet.md. Exit 1 if some parts failed, 2 if the file is invalid."""
    import os

    from wheelstep_cli.batch import load_batch, run_batch
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.config.schema import InvalidInput

    if jobs < 0:
        raise DesignError("jobs", jobs, "must be >= 0 (0: one per CPU core)")
    if out.exists() and not out.is_dir():
        raise DesignError("out", str(out), "is a file; give a folder")
    try:
        plan = load_batch(file, str(file))
    except InvalidInput as err:
        for line in err.lines():
            typer.echo(f"wheelstep: error: {line}", err=True)
        raise typer.Exit(2)
    workers = jobs or os.cpu_count() or 1
    workers = max(1, min(workers, len(plan.entries)))
    try:
        with _progress() as progress:
            outcome = run_batch(plan, out, workers, progress)
    except OSError as err:
        raise DesignError("out", str(out), f"cannot be written ({err.strerror or err})") from None
    parts = sum(len(p.items) for p in outcome.plates)
    typer.echo(f"built {len(outcome.built)} of {len(plan.entries)} entries: {parts} parts on "
               f"{len(outcome.plates)} plate{'' if len(outcome.plates) == 1 else 's'} in {out}")
    for plate in outcome.plates:
        typer.echo(f"  {plate.stem}.3mf ({plate.printer.name}): {len(plate.items)} parts")
    if outcome.failed:
        typer.echo(f"{len(outcome.failed)} entries failed:", err=True)
        for entry, where, reason in outcome.failed:
            typer.echo(f"  {entry.name} ({where}): {reason}", err=True)
        raise typer.Exit(1)


class _progress:
    """A rich progress bar on stderr; ``progress(stage, total)`` returns an advance() callable."""

    def __enter__(self):
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                            TimeElapsedColumn(), console=Console(stderr=True), transient=False)
        self.bar.__enter__()
        return self

    def __call__(self, stage: str, total: int):
        task = self.bar.add_task(stage, total=total)
        return lambda: self.bar.advance(task)

    def __exit__(self, *exc):
        return self.bar.__exit__(*exc)


def register(app: typer.Typer) -> None:
    app.command("batch")(batch)
