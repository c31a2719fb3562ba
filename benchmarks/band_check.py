"""Timing of the band check (SPEC §11) against one meshing check, in process.

Run on demand:  python benchmarks/band_check.py [--printer fdm-0.4-pla]
Builds the default pair once, then times the nominal meshing check and the band's cases
(:func:`wheelstep_cli.parts.tolerance.band_record`). Target (issue 14): the band check, the
nominal check included, within 5 meshing checks' time.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--printer", default="fdm-0.4-pla")
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT))
    from wheelstep_cli.config.profiles import load_printer_profile
    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.parts.kinds import build_for_printer
    from wheelstep_cli.parts.tolerance import NOMINAL, band_record, check_case, sectioned_pair

    printer = load_printer_profile(args.printer)
    pair = build_for_printer("gear-pair", gear_pair_spec(None), None)
    sections = sectioned_pair(pair)
    start = time.perf_counter()
    nominal = check_case(sections, NOMINAL)
    one = time.perf_counter() - start
    start = time.perf_counter()
    record = band_record(sections, printer.band, printer.name, nominal)
    band = time.perf_counter() - start
    print(f"one meshing check {one:.2f} s; band of {printer.name} ({len(record['cases'])} cases) "
          f"{band:.2f} s; nominal + band = {(one + band) / one:.2f} meshing checks")


if __name__ == "__main__":
    main()
