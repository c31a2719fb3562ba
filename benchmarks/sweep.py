"""Benchmark: designs per minute of a gear-pair sweep on a local Dask cluster of 1 and of 2
workers (target: 2 workers >= 1.7x), and the memory peak of the client and of each worker.

Run from the project root:  python benchmarks/sweep.py [--points 8]
The cluster is started before the clock runs (its start-up is not a design's cost); each
worker count computes the same points into a fresh folder. The load average is printed
before and after: other work on the same cores skews the figures.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def sweep_text(points: int) -> str:
    """``points`` distinct desk-demo gear pairs (face widths 4, 5, ... mm)."""
    return ("command: gears\ndesign: desk-demo\ngrid:\n"
            f"  thickness: {{start: 4, stop: {3 + points}, step: 1}}\n")


def _peak_kb() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def measure(plan, workers: int, out: Path, threads: int | None = None) -> dict:
    """Designs per minute and memory peaks (MB) of the sweep on ``workers`` local workers, each
    with ``threads`` threads of its own (None: the cores shared between them, as sweep does)."""
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch.cluster import worker_env
    from wheelstep_cli.batch.sweep_run import run_sweep

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                      env=worker_env(workers) if threads is None else
                      {k: str(threads) for k in worker_env(workers)}) as cluster, Client(cluster) as client:
        start = time.perf_counter()
        outcome = run_sweep(plan, out, client)
        wall = time.perf_counter() - start
        peaks = client.run(_peak_kb)
    return {"workers": workers, "designs": outcome.computed, "failures": outcome.failures,
            "seconds": wall, "per_minute": 60 * outcome.computed / wall,
            "worker_peak_mb": max(peaks.values()) / 1024, "client_peak_mb": _peak_kb() / 1024}


def main() -> None:
    from wheelstep_cli.config.sweep_file import load_sweep

    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--points", type=int, default=8)
    parser.add_argument("--threads", type=int, default=None,
                        help="threads per worker (default: the cores shared between the workers)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        file = Path(tmp) / "sweep.yaml"
        file.write_text(sweep_text(args.points))
        plan = load_sweep(file)
        print(f"load average before: {os.getloadavg()}")
        runs = [measure(plan, workers, Path(tmp) / f"out-{workers}", args.threads) for workers in (1, 2)]
        print(f"load average after: {os.getloadavg()}")
    for run in runs:
        print(f"{run['workers']} worker(s): {run['designs']} designs ({run['failures']} refused or "
              f"failed) in {run['seconds']:.1f} s = {run['per_minute']:.1f} designs/min; memory "
              f"peak {run['worker_peak_mb']:.0f} MB per worker, {run['client_peak_mb']:.0f} MB client")
    print(f"speed-up 2 vs 1 worker: {runs[1]['per_minute'] / runs[0]['per_minute']:.2f}x")


if __name__ == "__main__":
    main()
