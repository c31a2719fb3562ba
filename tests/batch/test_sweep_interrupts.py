"""`wheelstep sweep` cut off: a Ctrl-C (at any stage, also a real one to the process group)
leaves a valid results file and says where it is, a rerun computes only the missing points;
a crashing, lost or cancelled point is a failed row, not a lost sweep."""

from __future__ import annotations

import json
import os
import signal
import time
from pathlib import Path

import pyarrow.parquet as pq
import pytest

from tests.helpers.files import write
from tests.helpers.sweeps import POINTS, SHOES, rows
from tests.helpers.terminal import ctrl_c, start_cli


def test_a_ctrl_c_while_merging_keeps_every_row_as_the_sweeps(tmp_path, monkeypatch):
    """A SIGINT while the merged results replace the old ones is held until they are recorded
    and the merged parts removed; the merge run again on the way out (as the sweep does at
    Ctrl-C) keeps every row, and the results stay the sweep's own for a rerun."""
    from wheelstep_cli.batch import sweep_store
    from wheelstep_cli.batch.sweep_store import ResultStore, owned_results, schema

    monkeypatch.setattr(sweep_store, "FLUSH_ROWS", 2)     # several part files to remove
    store = ResultStore(tmp_path, schema({"rim": "float"}), earlier=False)
    for i in range(5):
        store.add({"key": f"k{i}", "index": i, "command": "shoe", "p_rim": float(i),
                   "outcome": "ok", "versions": "v", "seconds": 0.0})
    real_replace = os.replace

    def replace_then_interrupt(src, dst):
        real_replace(src, dst)
        if Path(dst).name == "results.parquet":
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(sweep_store.os, "replace", replace_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        store.consolidate()
    monkeypatch.setattr(sweep_store.os, "replace", real_replace)
    assert owned_results(tmp_path, force=False)           # recorded before the interrupt
    assert not (tmp_path / ".sweep-parts").exists()
    store.consolidate()
    assert sorted(rows(tmp_path)) == [f"k{i}" for i in range(5)]
    assert owned_results(tmp_path, force=False)


def test_rerun_after_interruption_computes_only_the_missing_points(tmp_path, monkeypatch):
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch.sweep_run import run_sweep
    from wheelstep_cli.config.sweep_file import load_sweep

    plan = load_sweep(write(tmp_path / "shoes.yaml", SHOES))
    out = tmp_path / "out"

    def interrupt(done, failures, total):  # Ctrl-C after two rows
        if done == 2:
            raise KeyboardInterrupt

    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as lc, Client(lc) as client:
        with pytest.raises(KeyboardInterrupt):
            run_sweep(plan, out, client, interrupt)
        first = rows(out)                      # a valid results file with the rows so far
        assert len(first) == 2 and not (out / ".sweep-parts").exists()
        outcome = run_sweep(plan, out, client)
    assert (outcome.skipped, outcome.computed) == (2, POINTS - 2)
    final = rows(out)
    assert len(final) == POINTS and first.items() <= final.items()


def test_ctrl_c_during_the_final_merge_still_leaves_the_results(tmp_path, monkeypatch):
    """Every row computed, then Ctrl-C while they are merged: the merge is redone, so the
    results file holds them all (the interruption message promises it)."""
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch import sweep_store
    from wheelstep_cli.batch.sweep_run import run_sweep
    from wheelstep_cli.config.sweep_file import load_sweep

    plan = load_sweep(write(tmp_path / "shoes.yaml", SHOES))
    out = tmp_path / "out"
    merge = sweep_store.ResultStore.consolidate
    calls = []

    def interrupted_once(store, keys=None):
        calls.append(1)
        if len(calls) == 1:
            store.flush()                      # rows on disk as parts, then Ctrl-C
            raise KeyboardInterrupt
        return merge(store, keys)

    monkeypatch.setattr(sweep_store.ResultStore, "consolidate", interrupted_once)
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as lc, Client(lc) as client:
        with pytest.raises(KeyboardInterrupt):
            run_sweep(plan, out, client)
    assert len(calls) == 2 and len(rows(out)) == POINTS and not (out / ".sweep-parts").exists()


def test_ctrl_c_leaves_a_valid_results_file(cli, tmp_path):
    """A real SIGINT to the sweep's process group (the command, its local cluster) once rows
    are on disk: exit 130 with the rows so far in a valid results file, and a rerun computes
    exactly the others."""
    sweep = write(tmp_path / "shoes.yaml", SHOES.replace("stop: 14, step: 2", "stop: 22, step: 1"))
    out = tmp_path / "out"
    run = start_cli("sweep", sweep, "--out", out, "--workers", "1", "-q")
    # interrupted once the first rows are on disk (or it finished): a fixed sleep raced the
    # libraries' loading on a loaded machine
    deadline = time.monotonic() + 300
    while (run.poll() is None and time.monotonic() < deadline
           and not any((out / ".sweep-parts").glob("*.parquet"))):
        time.sleep(0.1)
    if run.poll() is None:
        ctrl_c(run)
    _, err = run.communicate(timeout=120)
    total = 2 * 13
    if run.returncode == 130:             # one line: no 'aborted' after it, no worker's traceback
        assert err.count("\n") == 1 and err.startswith("wheelstep: interrupted"), err
    else:                                 # it finished first (refused points: exit 1)
        assert run.returncode == 1, err
    before = len(rows(out))
    assert before <= total and not (out / ".sweep-parts").exists()
    rerun = cli("sweep", sweep, "--out", out, "--workers", "1", "-q", "--json")
    report = json.loads(rerun.stdout)
    assert (report["skipped"], report["computed"]) == (before, total - before)
    assert len(rows(out)) == total


@pytest.mark.parametrize("wrapped", [False, True])
def test_ctrl_c_after_the_rows_are_merged_says_where_they_are(cli, tmp_path, monkeypatch, wrapped):
    """A Ctrl-C once the cluster has stopped (drawing the plot), also one that the plotting
    library's loading wrapped in an error of its own: the rows are all merged, the run says so
    in one line and exits 130."""
    from wheelstep_cli.cli.commands import sweep as sweep_command

    def interrupt(*args):
        if not wrapped:
            raise KeyboardInterrupt
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as err:   # as Python wraps one in a class body's __set_name__
            raise RuntimeError("Error calling __set_name__") from err

    monkeypatch.setattr(sweep_command, "_plot", interrupt)
    sweep = write(tmp_path / "shoes.yaml", SHOES)
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1", "-q")
    assert result.exit_code == 130
    assert result.stderr == (f"wheelstep: interrupted; the rows so far are in "
                             f"{tmp_path / 'out' / 'results.parquet'} (a rerun computes the rest)\n")
    assert len(rows(tmp_path / "out")) == POINTS


def test_a_ctrl_c_before_any_row_leaves_an_empty_valid_results_file(tmp_path):
    from wheelstep_cli.batch.sweep_store import ResultStore, schema

    store = ResultStore(tmp_path, schema({"rim": "float"}), earlier=False)
    store.consolidate({"k0": 0})          # the merge on the way out of an early Ctrl-C
    assert rows(tmp_path) == {}


def test_a_crashing_point_is_a_row(monkeypatch):
    from wheelstep_cli.batch import sweep_point
    from wheelstep_cli.config.sweep_file import load_sweep  # noqa: F401  (the real module path)

    point = sweep_point.resolve_point(0, "shoe", None, None, None, {"width": 12}, False, "t")
    assert point.refusal is None

    def crash(_point):
        raise ZeroDivisionError("boom")

    monkeypatch.setattr(sweep_point, "build_point", crash)
    row = sweep_point.evaluate(point)
    assert row["outcome"] == "failed" and row["reason"] == "internal error: ZeroDivisionError: boom"


def test_a_task_lost_for_good_is_a_failed_row(tmp_path, monkeypatch):
    """A task that fails as a task (not a refusal its point reports), after its retries: a
    failed row naming the error, the other rows kept."""
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch import sweep_run
    from wheelstep_cli.config.sweep_file import load_sweep

    evaluate = sweep_run.evaluate

    def lost(point):
        if point.index == 1:
            raise RuntimeError("the worker is gone")
        return evaluate(point)

    monkeypatch.setattr(sweep_run, "evaluate", lost)      # in-process workers see the patch
    plan = load_sweep(write(tmp_path / "shoes.yaml", SHOES))
    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as lc, Client(lc) as client:
        outcome = sweep_run.run_sweep(plan, tmp_path / "out", client)
    table = {row["index"]: row for row in pq.read_table(outcome.results).to_pylist()}
    assert len(table) == POINTS
    assert (table[1]["outcome"], table[1]["reason"]) == ("failed", "worker failed: RuntimeError: the worker is gone")
    assert all("worker failed" not in (row["reason"] or "") for i, row in table.items() if i != 1)


def test_a_cancelled_task_is_a_failed_row():
    """A task cancelled under the sweep (a scheduler restarted): a failed row, not a traceback."""
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch import sweep_point
    from wheelstep_cli.batch.sweep_run import _result

    point = sweep_point.resolve_point(0, "shoe", None, None, None, {"width": 12}, False, "t")
    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as lc, Client(lc) as client:
        future = client.submit(time.sleep, 30)
        future.cancel()
        row = _result(future, point)
    assert row["outcome"] == "failed" and row["reason"].startswith("worker failed: "), row
    assert "Cancelled" in row["reason"], row
