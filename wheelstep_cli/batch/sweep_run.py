"""Running a sweep on Dask (dask.distributed): a local cluster sized to the machine, or an
existing one at a scheduler address. Points are submitted a window at a time (bounded
memory), each retried when its worker is lost; every result, failures included, is a row."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from wheelstep_cli.batch.cluster import RETRIES, dask_client  # noqa: F401  (dask_client: for the CLI)
from wheelstep_cli.batch.interrupts import interrupts_deferred
from wheelstep_cli.batch.sweep_point import Point, evaluate, resolve_point, versions
from wheelstep_cli.batch.sweep_store import ResultStore, axis_kinds, cell, schema
from wheelstep_cli.config.sweep_file import SweepPlan

#: Points in flight per worker (keeps the scheduler fed without holding the whole sweep).
WINDOW_PER_WORKER = 4


@dataclass
class SweepOutcome:
    total: int
    skipped: int
    computed: int
    failures: int
    results: Path
    dropped: int = 0      # rows of the results no longer of the sweep's points (other code, grid)
    not_ok: int = 0       # rows of the sweep's points refused or failed, an earlier run's too


def resolve_points(plan: SweepPlan) -> list[Point]:
    """Every point of the plan with its spec and key (profiles read once, here)."""
    from wheelstep_cli.config.profiles import load_design_profile, load_printer_profile

    profile = load_design_profile(plan.design) if plan.design else None
    printers = {name: load_printer_profile(name) for name in {p for p, _ in plan.points if p}}
    tool = versions()
    return [resolve_point(i, plan.command, profile, name, printers.get(name), values,
                          plan.allow_interference, tool, plan.tolerance)
            for i, (name, values) in enumerate(plan.points)]


def run_sweep(plan: SweepPlan, out: Path, client, progress: Callable[[int, int, int], None]
              = lambda done, failures, total: None, earlier: bool = True) -> SweepOutcome:
    """Compute the points not yet in ``out``'s results (``earlier``: those results are the
    sweep's own, see sweep_store.owned_results) on ``client``; rows written as they come; on
    Ctrl-C the rows so far are merged into a valid results file and it re-raises."""
    from distributed import as_completed

    points = resolve_points(plan)
    kinds = axis_kinds([p.values for p in points], plan.axes)
    store = ResultStore(out, schema(kinds, plan.tolerance), earlier)
    done, index_of = store.done_keys(), {}
    for point in points:            # a point repeated in the plan (same key) sits at its first place
        index_of.setdefault(point.key, point.index)
    todo = [p for p in points if p.key not in done]
    tool = versions()
    failures, finished = 0, 0
    window = max(1, WINDOW_PER_WORKER * max(1, len(client.scheduler_info().get("workers", {}))))
    pending = iter(todo)
    futures = as_completed()
    by_future = {}
    progress(0, 0, len(todo))
    try:
        for point in _take(pending, window):
            by_future[_submit(client, futures, point)] = point
        for future in futures:
            point = by_future.pop(future)
            row = _result(future, point)
            store.add(_row(row, point, kinds, tool))
            finished += 1
            failures += row["outcome"] != "ok"
            progress(finished, failures, len(todo))
            for nxt in _take(pending, 1):
                by_future[_submit(client, futures, nxt)] = nxt
        # inside the guard: a Ctrl-C while merging must still leave a results file
        results = store.consolidate(index_of)
    except KeyboardInterrupt:
        client.cancel(list(by_future))
        store.consolidate(index_of)
        raise
    return SweepOutcome(len(points), len(points) - len(todo), finished, failures, results, store.dropped,
                        _not_ok(results))


def _not_ok(results: Path) -> int:
    """Rows of a consolidated results file (the sweep's points only) not computed ok."""
    import pyarrow.parquet as pq

    return sum(outcome != "ok" for outcome in pq.read_table(results, columns=["outcome"]).column(0).to_pylist())


def _take(iterator, count: int) -> list:
    out = []
    for item in iterator:
        out.append(item)
        if len(out) == count:
            break
    return out


def _submit(client, futures, point: Point):
    future = client.submit(evaluate, point, retries=RETRIES, pure=False)
    futures.add(future)
    return future


def _result(future, point: Point) -> dict:
    """The row a worker computed, or a failed row when the task itself was lost for good
    (e.g. KilledWorker after the retries: this point only) or cancelled (by a scheduler
    restarted under it)."""
    from asyncio import CancelledError

    try:
        # a Ctrl-C is held while the result is fetched: cut, the fetch's wait would leave a
        # cancelled callback that distributed logs as an error
        with interrupts_deferred():
            return future.result()
    except (Exception, CancelledError) as err:
        from wheelstep_cli.batch.sweep_point import FIGURES

        row = dict.fromkeys(FIGURES)
        row.update(key=point.key, index=point.index, outcome="failed", interference=None,
                   reason=f"worker failed: {type(err).__name__}: {err}", seconds=None)
        return row


def _row(row: dict, point: Point, kinds: dict[str, str], tool: str) -> dict:
    """A worker's row with the point's parameters, design and versions (the table's columns)."""
    design = point.spec.model_dump(mode="json") if point.spec is not None else None
    out = {**row, "command": point.command, "printer": point.printer_name,
           "parameters": json.dumps(design, sort_keys=True) if design else None, "versions": tool}
    out.update({f"p_{name}": cell(point.values.get(name), kind) for name, kind in kinds.items()})
    return out


def best_points(plan: SweepPlan, results: Path, count: int) -> list[Point]:
    """The ``count`` best designs of the results (``ok`` rows, Pareto front of the plan's two
    objectives first, by the first objective), as points to build again."""
    import pyarrow.parquet as pq

    from wheelstep_cli.batch.sweep_store import pareto_order

    first, second = plan.objectives
    table = pq.read_table(results, columns=["key", "outcome", first, second]).to_pylist()
    ok = [r for r in table if r["outcome"] == "ok" and r[first] is not None and r[second] is not None]
    order, _ = pareto_order([r[first] for r in ok], [r[second] for r in ok])
    wanted = [ok[i]["key"] for i in order[:count]]
    points = {p.key: p for p in resolve_points(plan)}
    return [points[key] for key in wanted if key in points]
