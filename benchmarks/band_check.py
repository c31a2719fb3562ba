"""Timing of the band check (SPEC §11) against one meshing check, in process.

Run on demand:  python benchmarks/band_check.py [--printer fdm-0.4-pla] [--runs 3]
Builds the default pair once, then times the nominal meshing check and the band's cases
(:func:`wheelstep_cli.parts.tolerance.band_record`) ``--runs`` times and reports the
medians, as CPU time (``time.process_time``: this process, its threads included; the
steady figure on a shared machine) and wall time, with the load average. Target
(issue 14): the band check, the nominal check included, within 5 meshing checks' time.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


class _Clock:
    """CPU and wall seconds of one timed block."""

    def __enter__(self) -> "_Clock":
        self._cpu, self._wall = time.process_time(), time.perf_counter()
        return self

    def __exit__(self, *exc) -> None:
        self.cpu, self.wall = time.process_time() - self._cpu, time.perf_counter() - self._wall


def _load() -> str:
    return "load average %.1f %.1f %.1f" % os.getloadavg()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--printer", default="fdm-0.4-pla")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT))
    from wheelstep_cli.config.profiles import load_printer_profile
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.kinds import build_for_printer
    from wheelstep_cli.parts.tolerance import (NOMINAL, band_cases, case_record, check_case,
                                               mid_play, sectioned_pair)
    try:   # the band's cases as band_record checks them (without the overlap area, when it can)
        from wheelstep_cli.parts.tolerance import case_settings
    except ImportError:
        case_settings = None
    from wheelstep_cli.gears.meshing import MeshingSettings

    printer = load_printer_profile(args.printer)
    pair = build_for_printer("gear-pair", gear_pair_spec(None), None)
    sections = sectioned_pair(pair)
    cases = band_cases(printer.band)
    print(f"before: {_load()}")
    nominal_t, band_t, per_case = [], [], {case.name: [] for case in cases}
    for _ in range(args.runs):
        with _Clock() as one:
            nominal = check_case(sections, NOMINAL)
        nominal_t.append(one)
        started = mid_play(sections, nominal)
        total_cpu = total_wall = 0.0
        for case in cases:
            with _Clock() as clock:
                settings = MeshingSettings() if case_settings is None else case_settings(MeshingSettings())
                record = case_record(case, check_case(started, case, settings))
            per_case[case.name].append((clock.cpu, record["jams"]))
            total_cpu, total_wall = total_cpu + clock.cpu, total_wall + clock.wall
        band_t.append((total_cpu, total_wall))
    med = statistics.median
    one_cpu, one_wall = med(t.cpu for t in nominal_t), med(t.wall for t in nominal_t)
    band_cpu, band_wall = med(b[0] for b in band_t), med(b[1] for b in band_t)
    print(f"one meshing check: CPU {one_cpu:.2f} s, wall {one_wall:.2f} s (median of {args.runs})")
    for name, runs in per_case.items():
        cpu = med(r[0] for r in runs)
        print(f"  {name:28s} CPU {cpu:6.2f} s = {cpu / one_cpu:5.2f} checks"
              f"{' (jams)' if runs[0][1] else ''}")
    print(f"band of {printer.name} ({len(cases)} cases): CPU {band_cpu:.2f} s, wall {band_wall:.2f} s; "
          f"nominal + band = {(one_cpu + band_cpu) / one_cpu:.2f} meshing checks' CPU time "
          f"({(one_wall + band_wall) / one_wall:.2f} by wall time)")
    print(f"after: {_load()}")


if __name__ == "__main__":
    main()
