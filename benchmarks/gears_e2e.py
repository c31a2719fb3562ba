"""End-to-end timing of `wheelstep gears --z 48`: process start to files written.

Run on demand:  python benchmarks/gears_e2e.py [--runs 7] [--check] [-- extra gears options]
Prints the median and spread of wall-clock times over several runs (first run discarded
as a warm-up of the OS file cache). Runs this checkout's package (`python -m
wheelstep_cli` from the repository root), not whatever `wheelstep` is on the PATH.
``--check`` also times the meshing check of the written meshes alone (sectioning both
meshes + SPEC §10 over 1536 poses), in process. Target (issue 6): end to end under 5 s
on the shared 2-core machine.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def command() -> list[str]:
    return [sys.executable, "-m", "wheelstep_cli"]


def time_check(runs: int) -> None:
    """Median wall time of check_gear_pair on the default pair (built once)."""
    sys.path.insert(0, str(ROOT))
    from wheelstep_cli.parts.gear_pair import GearPairSpec, build_gear_pair
    from wheelstep_cli.parts.mesh_check import check_gear_pair

    pair = build_gear_pair(GearPairSpec())
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        report = check_gear_pair(pair)
        times.append(time.perf_counter() - start)
    summary = report.to_dict()
    print(f"meshing check of the written meshes (section + {summary['samples']} poses): median "
          f"{statistics.median(times):.3f} s (min {min(times):.3f}, max {max(times):.3f}, "
          f"{runs} runs); drive F'i {summary['drive']['F_i_total_um']:.2f} um, f'i "
          f"{summary['drive']['f_i_tooth_um']:.2f} um, ripple "
          f"{summary['drive']['hub_speed_ripple_pct']:.3f} % (3 tooth harmonics), backlash "
          f"{summary['backlash_min_mm']:.4f}..{summary['backlash_max_mm']:.4f} mm")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--check", action="store_true", help="also time the meshing check alone")
    parser.add_argument("extra", nargs="*", help="more options for `wheelstep gears`")
    args = parser.parse_args()
    times = []
    with tempfile.TemporaryDirectory() as out:
        argv = command() + ["gears", "--z", "48", "--out", out, *args.extra]
        for i in range(args.runs + 1):
            start = time.perf_counter()
            subprocess.run(argv, check=True, capture_output=True, cwd=ROOT)
            if i:
                times.append(time.perf_counter() - start)
    print(f"wheelstep gears --z 48 {' '.join(args.extra)}: median {statistics.median(times):.3f} s "
          f"(min {min(times):.3f}, max {max(times):.3f}, {args.runs} runs)")
    if args.check:
        time_check(args.runs)


if __name__ == "__main__":
    main()
