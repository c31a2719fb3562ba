"""Independent numpy / shapely work shared between the cores on threads.

numpy and shapely release the GIL in their inner loops, so threads run such work in
parallel without copying the data to other processes.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, Iterable, Iterator, TypeVar

T = TypeVar("T")
R = TypeVar("R")

def _threads() -> int:
    """One per core, at most 4; WHEELSTEP_THREADS (a whole number >= 1) sets it, so that
    processes sharing the cores (sweep workers) do not each start one thread per core."""
    given = os.environ.get("WHEELSTEP_THREADS", "")
    return int(given) if given.isdigit() and int(given) >= 1 else max(1, min(4, os.cpu_count() or 1))


#: Threads that share the work.
THREADS = _threads()


def thread_map(fn: Callable[[T], R], items: Iterable[T], threads: int = THREADS) -> Iterator[R]:
    """``fn`` of every item on ``threads`` threads; the results in the items' order."""
    if threads <= 1:
        # One thread: no pool, so that profiles and tracebacks see the work itself.
        yield from map(fn, items)
        return
    with ThreadPoolExecutor(max_workers=threads) as pool:
        yield from pool.map(fn, items)
