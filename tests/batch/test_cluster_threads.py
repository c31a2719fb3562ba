"""Local sweep workers share the cores: each gets its share of the tooth generator's threads."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from wheelstep_cli.batch.cluster import worker_env


def _threads_with(env: dict[str, str]) -> int:
    code = "from wheelstep_cli.gears.threads import THREADS; print(THREADS)"
    out = subprocess.run([sys.executable, "-c", code], env={**os.environ, **env}, capture_output=True,
                         text=True, check=True, timeout=60)
    return int(out.stdout)


def test_wheelstep_threads_sets_the_generators_threads_and_a_bad_value_is_ignored():
    assert _threads_with({"WHEELSTEP_THREADS": "1"}) == 1
    assert _threads_with({"WHEELSTEP_THREADS": "3"}) == 3
    default = max(1, min(4, os.cpu_count() or 1))
    assert _threads_with({"WHEELSTEP_THREADS": "0"}) == default
    assert _threads_with({"WHEELSTEP_THREADS": "many"}) == default


def test_local_workers_split_the_cores_between_them():
    cores = os.cpu_count() or 1
    assert worker_env(1)["WHEELSTEP_THREADS"] == str(cores)
    assert worker_env(cores)["WHEELSTEP_THREADS"] == "1"
    assert worker_env(4 * cores)["OPENBLAS_NUM_THREADS"] == "1"


def test_the_local_cluster_gives_its_workers_their_share():
    from wheelstep_cli.batch.cluster import dask_client

    with dask_client(None, 2, "scheduler") as client:
        seen = client.run(lambda: os.environ.get("WHEELSTEP_THREADS"))
    assert sorted(seen.values()) == [worker_env(2)["WHEELSTEP_THREADS"]] * 2


def _worker_state():
    """What a worker process says about itself: Dask's log level, SIGINT blocked."""
    import logging

    return (logging.getLogger("distributed").getEffectiveLevel(),
            signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, []))


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="threads cannot block signals here")
def test_local_workers_are_quiet_and_leave_ctrl_c_to_the_command():
    """The local cluster's workers print nothing of Dask's below a critical error (its
    complaints while the cluster stops are noise at a terminal) and never see a Ctrl-C (the
    command answers it and stops them in order)."""
    import logging

    from wheelstep_cli.batch.cluster import dask_client

    with dask_client(None, 1, "scheduler") as client:
        seen = list(client.run(_worker_state).values())
    assert seen == [(logging.CRITICAL, True)]
