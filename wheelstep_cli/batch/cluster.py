"""The Dask cluster sweeps and batches run on: a local one sized to the machine, or an
existing one at a scheduler address (``--scheduler`` or DASK_SCHEDULER_ADDRESS)."""

from __future__ import annotations

import contextlib
import os

from wheelstep_cli.errors import DesignError

#: Seconds to reach a scheduler before giving up (the whole refusal stays under 15 s).
CONNECT_SECONDS = 8
#: Times a task is retried when its worker dies under it.
RETRIES = 3


@contextlib.contextmanager
def dask_client(scheduler: str | None, workers: int = 0, option: str = "scheduler"):
    """A dask.distributed Client: of ``scheduler`` (or DASK_SCHEDULER_ADDRESS) when given,
    else of a local cluster of ``workers`` processes (0: one per CPU core), 1 thread each.
    An unreachable scheduler is a DesignError naming ``option``."""
    from distributed import Client, LocalCluster

    address = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")
    if address:
        try:
            client = Client(address, timeout=f"{CONNECT_SECONDS}s")
        except (OSError, TimeoutError, ValueError) as err:
            raise DesignError(option, address, f"cannot be reached within {CONNECT_SECONDS} s "
                                               f"({type(err).__name__})") from None
        with client:
            yield client
        return
    count = workers or os.cpu_count() or 1
    with LocalCluster(n_workers=count, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        yield client


@contextlib.contextmanager
def dask_executor(scheduler: str | None, workers: int = 0):
    """A concurrent.futures executor running on Dask (see :func:`dask_client`); a task lost
    with its worker is retried."""
    with dask_client(scheduler, workers) as client:
        yield client.get_executor(retries=RETRIES, pure=False)
