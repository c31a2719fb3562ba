"""The Dask cluster sweeps and batches run on: a local one sized to the machine, or an
existing one at a scheduler address (``--scheduler`` or DASK_SCHEDULER_ADDRESS)."""

from __future__ import annotations

import contextlib
import os
import threading

from wheelstep_cli.batch.interrupts import interrupts_deferred, interrupts_kept_from_children
from wheelstep_cli.errors import DesignError

#: Seconds to reach a scheduler before giving up (the whole refusal stays under 15 s).
CONNECT_SECONDS = 6
#: Times a task is retried when its worker dies under it.
RETRIES = 3


@contextlib.contextmanager
def dask_client(scheduler: str | None, workers: int = 0, option: str = "scheduler"):
    """A dask.distributed Client: of ``scheduler`` (or DASK_SCHEDULER_ADDRESS) when given,
    else of a local cluster of ``workers`` processes (0: one per CPU core), 1 task thread each,
    the cores' threads shared between them (:func:`worker_env`).
    An unreachable scheduler is a DesignError naming ``option``."""
    address = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")
    if address:
        with _connect(address, option) as client:
            yield client
        return
    started: dict = {}
    try:
        _start_local(workers or os.cpu_count() or 1, started)
        yield started["client"]
    finally:
        # a Ctrl-C while it stops is held until it has (a cluster cut off half way waits out
        # its timeouts at exit)
        with interrupts_deferred():
            try:
                if "client" in started:
                    started["client"].close()
            finally:
                if "cluster" in started:
                    started["cluster"].close()


def _start_local(count: int, started: dict) -> None:
    """Start a local cluster of ``count`` worker processes and its client into ``started``
    (keys "cluster", "client", as each is up). They start on a thread of their own with SIGINT
    blocked, which their event loop and worker processes inherit for life: a Ctrl-C reaches
    this process only, which stops them in order (a worker never starts a subprocess that
    would need one). This thread waits with a Ctrl-C held until they are up; a second one
    goes through at once, so a start that hangs can be stopped."""
    from distributed import Client, LocalCluster

    def start():
        try:
            with _quiet_workers():
                started["cluster"] = LocalCluster(n_workers=count, threads_per_worker=1, processes=True,
                                                  dashboard_address=None, env=worker_env(count))
            started["client"] = Client(started["cluster"])
        except BaseException as err:      # handed to the waiting thread
            started["error"] = err

    with interrupts_deferred():
        with interrupts_kept_from_children():
            thread = threading.Thread(target=start, name="wheelstep cluster start", daemon=True)
            thread.start()
        while thread.is_alive():
            thread.join(0.1)
    if "error" in started:
        raise started.pop("error")


def _quiet_workers():
    """Settings under which local workers start with Dask's own logging shown only from
    critical errors up: what a worker says as the cluster stops (a heartbeat to a scheduler
    already gone) is noise at a terminal, and every point's failure is in its row. An
    environment variable set before the worker processes start: their logging is set up as
    they import Dask."""
    import dask

    return dask.config.set({"distributed.nanny.pre-spawn-environ.DASK_LOGGING__DISTRIBUTED": "critical"})


def worker_env(workers: int) -> dict[str, str]:
    """Environment of each of ``workers`` local worker processes: the cores shared between
    them (the tooth generator's threads and BLAS's), so that they do not oversubscribe."""
    share = str(max(1, (os.cpu_count() or 1) // workers))
    return {"WHEELSTEP_THREADS": share, "OPENBLAS_NUM_THREADS": share, "OMP_NUM_THREADS": share}


def _connect(address: str, option: str):
    """A Client of the scheduler at ``address`` within :data:`CONNECT_SECONDS`, else a
    DesignError. The attempt runs in a thread with a deadline of its own: a name that does not
    resolve, or a peer that answers but is no scheduler, can take longer than the Client's
    own timeout."""
    from distributed import Client

    box: dict = {}

    def attempt():
        try:
            _probe(address)
            box["client"] = Client(address, timeout=f"{CONNECT_SECONDS}s")
        except BaseException as err:  # whatever the address did, it is not a scheduler we reach
            box["error"] = err

    thread = threading.Thread(target=attempt, daemon=True)
    thread.start()
    thread.join(CONNECT_SECONDS + 1)
    if "client" in box:
        return box["client"]
    raise DesignError(option, address, f"cannot be reached within {CONNECT_SECONDS} s "
                                       f"({_why(box.get('error'))}); give the address `dask "
                                       "scheduler` prints, tcp://HOST:PORT (port 8786 if left out)")


def _why(error: BaseException | None) -> str:
    """What a failed connection attempt says of the address, in a few words."""
    import socket

    if error is None:
        return "no answer"
    if isinstance(error, socket.gaierror):
        return "its host name does not resolve"
    if isinstance(error, ConnectionRefusedError):
        return "nothing listens at that port"
    return type(error).__name__


def _probe(address: str) -> None:
    """Open and close a TCP connection to a ``tcp://`` scheduler (OSError at once when
    refused, rather than the Client's retries until its timeout)."""
    import socket

    from distributed.comm.addressing import parse_address, parse_host_port

    scheme, location = parse_address(address)
    if scheme == "tcp":
        host, port = parse_host_port(location, default_port=8786)
        socket.create_connection((host, port), timeout=CONNECT_SECONDS).close()


@contextlib.contextmanager
def dask_executor(scheduler: str | None, workers: int = 0):
    """A concurrent.futures executor running on Dask (see :func:`dask_client`); a task lost
    with its worker is retried."""
    with dask_client(scheduler, workers) as client:
        yield client.get_executor(retries=RETRIES, pure=False)
