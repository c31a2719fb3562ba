"""Benchmark: a 20-entry batch with --jobs 2 against --jobs 1 (target: >= 1.6x faster).

Run from the project root:  python benchmarks/batch_jobs.py [--repeat 2]
Each run is a fresh `python -m wheelstep_cli batch` process (start-up included). The
machine's load average is printed before and after, since other work on the same cores
skews the figure. Outputs of both job counts are compared byte for byte.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def batch_text() -> str:
    """20 distinct entries (no two builds alike): gear pairs and shoes of both design presets."""
    entries = []
    for i in range(6):
        entries.append(f"  - {{name: bntu-gears-{i}, kind: gear-pair, design: bntu-2024, "
                       f"printer: fdm-0.4-petg, overrides: {{thickness: {8 + i}}}}}")
    for i in range(6):
        entries.append(f"  - {{name: demo-gears-{i}, kind: gear-pair, design: desk-demo, "
                       f"printer: fdm-0.4-pla, overrides: {{thickness: {4 + i}}}}}")
    for i in range(4):
        entries.append(f"  - {{name: bntu-shoe-{i}, kind: shoe, design: bntu-2024, "
                       f"printer: fdm-0.4-petg, overrides: {{width: {36 + i}}}}}")
    for i in range(4):
        entries.append(f"  - {{name: demo-shoe-{i}, kind: shoe, design: desk-demo, "
                       f"printer: fdm-0.4-pla, quantity: 2, overrides: {{width: {16 + i}}}}}")
    return "parts:\n" + "\n".join(entries) + "\n"


def run(batch: Path, out: Path, jobs: int) -> tuple[float, float]:
    """(wall-clock seconds, CPU seconds of the process and its workers) of one batch run."""
    import resource

    cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "wheelstep_cli", "batch", str(batch), "--out", str(out),
                    "--jobs", str(jobs)], cwd=ROOT, check=True, capture_output=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - cpu.ru_utime) + (after.ru_stime - cpu.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=2, help="runs per job count; the fastest counts")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        batch = folder / "bench.yaml"
        batch.write_text(batch_text())
        load_before = os.getloadavg()
        times = {1: [], 2: []}
        for _ in range(args.repeat):
            for jobs in (1, 2):
                times[jobs].append(run(batch, folder / f"out-{jobs}", jobs))
        load_after = os.getloadavg()
        same = all((folder / "out-1" / p.relative_to(folder / "out-2")).read_bytes() == p.read_bytes()
                   for p in (folder / "out-2").rglob("*") if p.is_file())
    best1, best2 = min(t for t, _ in times[1]), min(t for t, _ in times[2])
    print(f"cores: {os.cpu_count()}   load average before: {load_before[0]:.2f} {load_before[1]:.2f} "
          f"{load_before[2]:.2f}   after: {load_after[0]:.2f} {load_after[1]:.2f} {load_after[2]:.2f}")
    print("20 entries (32 parts), wall-clock seconds per run:")
    for jobs, best in ((1, best1), (2, best2)):
        runs = "  ".join(f"{t:.2f} (cpu {c:.2f}, {c / t:.2f} cores)" for t, c in times[jobs])
        print(f"  --jobs {jobs}: {runs}   best {best:.2f}")
    print(f"speed-up (best/best): {best1 / best2:.2f}x   (target >= 1.6x)   outputs identical: {same}")
    print("cores = cpu/wall: how much of the machine a run got; with other work on the cores "
          "--jobs 2 cannot get its 2")


if __name__ == "__main__":
    main()
