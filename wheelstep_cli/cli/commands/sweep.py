"""``wheelstep sweep``: run a design-space sweep of ``gears`` or ``shoe`` on Dask."""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Annotated, Optional

import typer

from wheelstep_cli.cli.options import DryRun, Force, Json, Out, Quiet, Verbose, opt, require_workers
from wheelstep_cli.cli.output import Output

#: --scheduler, shared with ``batch``.
Scheduler = Annotated[Optional[str], opt(
    "--scheduler", help="Address of an existing Dask scheduler (tcp://HOST:8786); default "
                        "DASK_SCHEDULER_ADDRESS, else a local cluster.")]
Workers = Annotated[int, opt("--workers", help="Worker processes of the local cluster; 0 = one "
                                               "per CPU core (not with --scheduler).")]
#: Most designs --keep best:N writes (each is a set of mesh files).
MAX_KEEP = 50


Keep = Annotated[Optional[str], opt("--keep", help="best:N writes the files of the N best designs "
                                                   "into OUT/best-K/.")]


def sweep(
    file: Path = typer.Argument(..., help="Sweep YAML: command, grid/random axes, fixed values, printers."),
    out: Out = Path("wheelstep-sweep"),
    scheduler: Scheduler = None, workers: Workers = 0,
    keep: Keep = None,
    force: Force = False, json: Json = False, dry_run: DryRun = False, quiet: Quiet = False,
    verbose: Verbose = False,
) -> None:
    """Compute every design of a sweep file (gears or shoe, meshing check included; the
    printer's tolerance band with `tolerance: true`) into OUT/results.parquet, results.csv
    (rows in point order) and pareto.png. A rerun computes only the missing designs. Exit 1
    if some designs of the table were refused (outside the bounds, like `gears` refuses them)
    or failed (their rows say why), by this run or an earlier one; 2 if the input is invalid."""
    from wheelstep_cli.config.sweep_file import load_sweep
    from wheelstep_cli.errors import DesignError

    show = Output(json, quiet, verbose)
    best = _keep_count(keep)
    require_workers("workers", workers, "one per core; a larger cluster goes in --scheduler")
    if workers and (scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")):
        raise DesignError("workers", workers, "sizes the local cluster; not with a scheduler")
    if out.exists() and not out.is_dir():
        raise DesignError("out", str(out), "is a file; give a folder")
    # a file's problems (InvalidInput) are said by the CLI's runner, with --json's object too
    plan = load_sweep(file, str(file))
    earlier = _owned_outputs(out, plan.command, best, show, force)
    _require_ranking(best, plan, show)      # (after it: a refused run prints its one line only)
    if dry_run:
        _dry_run(plan, file, out, show, (earlier, best))
        return
    outcome, written = _computed(plan, out, (scheduler, workers), (earlier, best, force), show)
    show.report({"sweep": str(file), "out": str(out), "points": outcome.total,
                 "skipped": outcome.skipped, "computed": outcome.computed,
                 "failures": outcome.failures, "refused_or_failed_rows": outcome.not_ok,
                 "dropped": outcome.dropped,
                 **show.written_record(written, False)},
                lambda: [f"{_designs(outcome.computed)} computed ({outcome.failures} refused or "
                         f"failed), {outcome.skipped} already in {outcome.results}"
                         + _earlier_not_ok(outcome) + _dropped_text(outcome.dropped, "dropped")])
    show.files(written, False)
    if outcome.not_ok:      # the sweep's table holds refused rows, this run's or an earlier one's
        raise typer.Exit(1)


def _designs(count: int) -> str:
    return f"{count} design" + ("" if count == 1 else "s")


def _earlier_not_ok(outcome) -> str:
    """What the results hold refused or failed besides this run's rows."""
    earlier = outcome.not_ok - outcome.failures
    return f" ({earlier} of them refused or failed)" if earlier > 0 else ""


def _computed(plan, out: Path, cluster: tuple, run: tuple, show: Output):
    """(the sweep's outcome, the files written): the points computed on the cluster
    (``cluster`` = scheduler, workers), plotted, the best kept (``run`` = ``out`` holds an
    earlier run's results, best designs kept, --force). A Ctrl-C is an Interrupted error
    saying where the rows so far are."""
    from wheelstep_cli.batch.interrupts import caused_by_interrupt
    from wheelstep_cli.batch.sweep_run import dask_client, run_sweep
    from wheelstep_cli.batch.sweep_store import CSV, RECORD
    from wheelstep_cli.errors import Interrupted

    earlier, best, force = run
    try:
        with dask_client(*cluster) as client:
            show.detail(f"  {len(plan.points)} points on {len(client.scheduler_info()['workers'])} worker(s)")
            with _Bar(not show.quiet) as bar:
                outcome = run_sweep(plan, out, client, bar.update, earlier)
        written = [outcome.results, out / CSV, _plot(plan, outcome.results, out), out / RECORD]
        return outcome, written + _keep_best(plan, outcome.results, out, best, show, force)
    except BaseException as err:          # a Ctrl-C, also one a library wrapped (the plot's)
        if not caused_by_interrupt(err):
            raise
        # the rows computed so far are merged (run_sweep) before the cluster stops
        raise Interrupted(_interrupted_text(out)) from None


def _interrupted_text(out: Path) -> str:
    """What an interrupted run leaves: the rows merged so far, if it got to any."""
    from wheelstep_cli.batch.sweep_store import RESULTS

    results = out / RESULTS
    if not results.exists():
        return "interrupted before any design was computed"
    return f"interrupted; the rows so far are in {results} (a rerun computes the rest)"


def _dry_run(plan, file: Path, out: Path, show: Output, run: tuple[bool, int]) -> None:
    """Say how many points would be computed (those not in ``out``'s own results) and what
    would be written and removed; nothing is computed or written. ``run`` = (``out`` holds
    an earlier run's results, best designs kept)."""
    from wheelstep_cli.batch.sweep_run import resolve_points
    from wheelstep_cli.batch.sweep_store import CSV, PLOT, RECORD, RESULTS, ResultStore, axis_kinds, schema

    earlier, best = run
    _drop_earlier_best(out, best, show, dry_run=True)

    points = resolve_points(plan)
    columns = schema(axis_kinds([p.values for p in points], plan.axes), plan.tolerance)
    done = ResultStore(out, columns, earlier).done_keys()
    todo = sum(p.key not in done for p in points)
    dropped = len(done - {p.key for p in points})
    # the best designs' folders: their files are named by the designs the run will rank
    files = [out / RESULTS, out / CSV, out / PLOT, out / RECORD,
             *(out / f"best-{k}" for k in range(1, best + 1))]
    show.report({"sweep": str(file), "out": str(out), "points": len(points),
                 "skipped": len(points) - todo, "would_compute": todo, "would_drop": dropped,
                 **show.written_record(files, True)}, lambda: [f"{todo} of {len(points)} designs would be computed"
                                          + _dropped_text(dropped, "would be dropped")])
    show.files(files, True)


def _dropped_text(count: int, verb: str) -> str:
    """What becomes of the earlier rows that are not of the sweep's points now ('' if none)."""
    if not count:
        return ""
    return (f"; {count} earlier row{'s' if count > 1 else ''} {verb} (points no longer in the "
            "sweep, or computed by another wheelstep or library version)")


def _require_ranking(best: int, plan, show: Output) -> None:
    """When the plan's objectives cannot rank its rows (the default objectives of a shoe sweep
    hold the mass, which rows without a printer do not have): refuse --keep, and say so of
    pareto.png, which will show no design."""
    from wheelstep_cli.config.sweep_file import NEEDS_PRINTER
    from wheelstep_cli.errors import DesignError

    if NEEDS_PRINTER not in plan.objectives or any(printer is not None for printer, _ in plan.points):
        return
    why = f"{NEEDS_PRINTER} needs `printers:` in the sweep file"
    if best:
        raise DesignError("keep", f"best:{best}", f"ranks by the objectives {' and '.join(plan.objectives)}; "
                          + why)
    show.warning(f"wheelstep: warning: pareto.png plots {' against '.join(plan.objectives)}, and {why}: "
                 "it will show no design (results.csv holds the volumes)")


#: The files every best design of a command writes, whatever the design (its plates' names
#: depend on how many the design needs).
_BEST_FILES = {"gears": ("pinion.stl", "wheel.stl", "gears.json"),
               "shoe": ("shoe.stl", "shoe.json", "shoe-profile.csv")}


def _owned_outputs(out: Path, command: str, count: int, show: Output, force: bool) -> bool:
    """Before any design is computed, refuse a user's file among the outputs: the results and,
    with --keep best:``count``, where each best design's files go (those folders are filled
    once the whole sweep is done). True when ``out``'s results are the sweep's own."""
    from wheelstep_cli.batch.sweep_store import owned_results

    earlier = owned_results(out, force)
    for rank in range(1, count + 1):
        folder = out / f"best-{rank}"
        show.write_owned(folder, command, {folder / name: b"" for name in _BEST_FILES[command]},
                         True, force, check_only=True)
    return earlier


def _keep_count(keep: str | None) -> int:
    from wheelstep_cli.errors import DesignError

    if keep is None:
        return 0
    match = re.fullmatch(r"best:(\d+)", keep)
    if not match or not 1 <= int(match.group(1)) <= MAX_KEEP:
        raise DesignError("keep", keep, f"must be best:N with N = 1..{MAX_KEEP}")
    return int(match.group(1))


def _plot(plan, results: Path, out: Path) -> Path:
    """pareto.png: the ok designs by the plan's two objectives, the front highlighted."""
    import pyarrow.parquet as pq

    from wheelstep_cli.batch.sweep_store import PLOT, pareto_order, record_outputs
    from wheelstep_cli.errors import format_value
    from wheelstep_cli.formats.atomic import write_bytes_atomic
    from wheelstep_cli.render.sweep_plot import pareto_png

    first, second = plan.objectives
    varied = [name for name in pq.read_schema(results).names if name.startswith("p_")]
    rows = pq.read_table(results, columns=["outcome", "printer", first, second, *varied]).to_pylist()
    ok = [r for r in rows if r["outcome"] == "ok" and r[first] is not None and r[second] is not None]
    a, b = [r[first] for r in ok], [r[second] for r in ok]
    # each design named by the values the sweep varied, as its file's keys (and its printer when
    # it sweeps several: the same values on two printers are two designs)
    printers = len({r["printer"] for r in rows}) > 1
    labels = [" ".join([f"{name[2:]} {format_value(r[name])}" for name in varied]
                       + ([f"on {r['printer']}"] if printers else [])) for r in ok]
    _, front = pareto_order(a, b)
    path = out / PLOT
    write_bytes_atomic(path, pareto_png(a, b, front, (first, second),
                                        f"{Path(plan.label).name}: {len(ok)} of {len(rows)} designs", labels))
    record_outputs(out, (PLOT,))
    return path


def _keep_best(plan, results: Path, out: Path, count: int, show: Output, force: bool) -> list[Path]:
    """The files of the ``count`` best designs, built again with the command's writers."""
    from wheelstep_cli.batch.sweep_point import build_point
    from wheelstep_cli.batch.sweep_run import best_points

    written: list[Path] = []
    best = best_points(plan, results, count) if count else []
    if len(best) < count:
        from wheelstep_cli.errors import counted

        show.warning(f"wheelstep: warning: --keep best:{count} keeps {len(best)}: the results hold "
                     f"{counted(len(best), 'ok design', 'ok designs')} to rank")
    for rank, point in enumerate(best, start=1):
        folder = out / f"best-{rank}"
        built, record = build_point(point)
        if point.command == "gears":
            from wheelstep_cli.parts.gear_pair import gear_pair_files

            files = gear_pair_files(built, folder, "both", record)
        else:
            from wheelstep_cli.parts.shoe import shoe_files

            files = shoe_files(built, folder, "both")
        written += show.write_owned(folder, point.command, files, False, force)
    _drop_earlier_best(out, count, show)
    return written


def _drop_earlier_best(out: Path, count: int, show: Output, dry_run: bool = False) -> None:
    """Remove the best-K folders of an earlier run beyond the ``count`` kept now, as far as
    that run wrote them (per each folder's record; a file changed since, or the user's, is
    kept with its folder). With ``dry_run`` the files are only listed as the real run's
    removals (said with the files)."""
    from wheelstep_cli.formats.atomic import remove_files
    from wheelstep_cli.formats.owned import kept_files, read_record, stale_files

    earlier = [f for f in out.glob("best-*") if f.is_dir() and f.name[5:].isdigit() and int(f.name[5:]) > count]
    for folder in sorted(earlier):
        for record_path in sorted(folder.glob(".wheelstep-*.json")):
            record = read_record(record_path)
            stale = stale_files(folder, {}, record)
            show.kept.extend(kept_files(folder, {}, record))
            # the record goes with the last of its files: one changed since stays listed as ours
            stale += [record_path] if len(stale) == len(record) else []
            if dry_run:
                show.would_remove.extend(stale)
            else:
                remove_files(stale)
                show.removed.extend(stale)
        if dry_run:
            continue
        try:
            folder.rmdir()
            show.detail(f"  removed {folder} (written by an earlier run)")
        except OSError:
            pass        # it holds a file this command did not write: kept


class _Bar:
    """A rich progress bar on stderr: designs done of those to compute, failures, rate."""

    def __init__(self, enabled: bool):
        self.enabled = enabled

    def __enter__(self):
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                            TextColumn("{task.fields[failures]} refused or failed"),
                            TextColumn("{task.fields[rate]}"), TimeElapsedColumn(),
                            console=Console(stderr=True), disable=not self.enabled)
        self.bar.__enter__()
        self.task = self.bar.add_task("sweep", total=None, failures=0, rate="")
        return self

    def __exit__(self, *exc):
        return self.bar.__exit__(*exc)

    def update(self, done: int, failures: int, total: int) -> None:
        elapsed = self.bar.tasks[0].elapsed or 0.0
        rate = f"{60 * done / elapsed:.1f} designs/min" if elapsed > 0 and done else ""
        self.bar.update(self.task, completed=done, total=total, failures=failures, rate=rate)


def register(app: typer.Typer) -> None:
    app.command("sweep")(sweep)
