"""End-to-end timing of `wheelstep gears --z 48`: process start to files written.

Run on demand:  python benchmarks/gears_e2e.py [--runs 7] [-- extra gears options]
Prints the median and spread of wall-clock times over several runs (first run discarded
as a warm-up of the OS file cache). Target (issue #2): median under 1.5 s on 2 cores.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def command() -> list[str]:
    exe = shutil.which("wheelstep")
    return [exe] if exe else [sys.executable, "-m", "wheelstep_cli"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("extra", nargs="*", help="more options for `wheelstep gears`")
    args = parser.parse_args()
    times = []
    with tempfile.TemporaryDirectory() as out:
        argv = command() + ["gears", "--z", "48", "--out", out, *args.extra]
        for i in range(args.runs + 1):
            start = time.perf_counter()
            subprocess.run(argv, check=True, capture_output=True)
            if i:
                times.append(time.perf_counter() - start)
    print(f"wheelstep gears --z 48 {' '.join(args.extra)}: median {statistics.median(times):.3f} s "
          f"(min {min(times):.3f}, max {max(times):.3f}, {args.runs} runs)")


if __name__ == "__main__":
    main()
