"""Ctrl-C around work that must not be cut in half (wheelstep_cli.batch.interrupts): held,
kept from worker processes, not lost where Python cannot raise it."""

import gc
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from tests.helpers.files import SMALL_BATCH, write
from tests.helpers.terminal import ctrl_c, start_cli

from wheelstep_cli.batch.interrupts import (interrupts_deferred, interrupts_kept_from_children,
                                            interrupts_not_lost)


def test_a_sigint_in_a_deferred_block_is_raised_when_it_ends():
    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
            done.append("after the signal")
    assert done == ["after the signal"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_second_sigint_goes_through_at_once():
    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
            signal.raise_signal(signal.SIGINT)
            done.append("after the second")
    assert done == []
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_second_sigint_is_handed_on_once():
    """To a handler that returns (not Python's, which raises): once, at the second."""
    seen = []
    before = signal.signal(signal.SIGINT, lambda signum, frame: seen.append(signum))
    try:
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
            signal.raise_signal(signal.SIGINT)
            assert len(seen) == 1
        assert len(seen) == 1
    finally:
        signal.signal(signal.SIGINT, before)


def test_a_held_sigint_wins_over_the_blocks_own_failure():
    """The person asked to stop: a block that fails after the Ctrl-C ends in KeyboardInterrupt."""
    with pytest.raises(KeyboardInterrupt):
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
            raise RuntimeError("the cluster failed to start")


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="threads cannot block signals here")
def test_a_sigint_while_children_start_waits_for_the_block_to_end():
    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupts_kept_from_children():
            signal.raise_signal(signal.SIGINT)          # pending: blocked in this thread
            done.append("after the signal")
    assert done == ["after the signal"]
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])


CHILD = textwrap.dedent("""\
    import multiprocessing, signal, sys
    from wheelstep_cli.batch.interrupts import interrupts_kept_from_children

    def child():
        blocked = signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, [])
        sys.exit(0 if blocked else 3)

    if __name__ == "__main__":
        with interrupts_kept_from_children():
            process = multiprocessing.get_context("spawn").Process(target=child)
            process.start()
        process.join()
        sys.exit(process.exitcode)
""")


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="threads cannot block signals here")
def test_a_worker_process_started_in_the_block_never_sees_sigint(tmp_path):
    """In a fresh interpreter, where the first spawned process also starts the standard
    library's resource tracker (which unblocks SIGINT in the thread that starts it)."""
    script = tmp_path / "spawn_one.py"
    script.write_text(CHILD)
    run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr


def test_a_sigint_lost_in_a_garbage_collector_callback_is_raised_again(capsys):
    def callback(phase, info):
        if phase == "start":
            raise KeyboardInterrupt

    gc.callbacks.append(callback)
    try:
        with pytest.raises(KeyboardInterrupt), interrupts_not_lost():
            gc.collect()                      # Python prints and drops the callback's exception
            gc.callbacks.remove(callback)
            deadline = time.monotonic() + 10
            while time.monotonic() < deadline:
                time.sleep(0.01)
    finally:
        if callback in gc.callbacks:
            gc.callbacks.remove(callback)
    assert "Exception ignored" not in capsys.readouterr().err


def _in_group(pgid: int) -> int:
    """How many processes are in process group ``pgid``."""
    count = 0
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                count += os.getpgid(int(entry.name)) == pgid
            except OSError:               # gone meanwhile
                pass
    return count


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="counts the processes in /proc")
def test_ctrl_c_to_a_batch_and_its_workers_is_one_line(tmp_path):
    """A real SIGINT to `batch --jobs 2`'s process group (as a terminal's Ctrl-C) once its
    worker processes run: exit 130 at once, 'aborted' its only line (no worker's traceback),
    nothing written."""
    batch = write(tmp_path / "batch.yaml", SMALL_BATCH)
    out = tmp_path / "out"
    run = start_cli("batch", batch, "--out", out, "--jobs", "2", "-q")
    deadline = time.monotonic() + 300
    # the command, the standard library's resource tracker and the two workers
    while run.poll() is None and time.monotonic() < deadline and _in_group(run.pid) < 4:
        time.sleep(0.05)
    assert run.poll() is None, "the batch finished before its workers were seen"
    ctrl_c(run)
    _, err = run.communicate(timeout=120)
    assert (run.returncode, err) == (130, "wheelstep: aborted\n")
    assert not out.exists()


def test_a_pool_cut_off_does_not_wait_for_its_workers():
    """A Ctrl-C (or an error) while a batch's local pool works: its workers killed, nothing
    waits for their entries (a worker cut off mid-result would keep the wait going for ever)."""
    from wheelstep_cli.batch.build import executor, map_items

    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        with executor(2) as pool:
            results = map_items(pool, time.sleep, [60, 60], lambda: None)
            time.sleep(1.0)
            raise KeyboardInterrupt
    assert time.monotonic() - start < 30      # not the minute the entries take
    del results
