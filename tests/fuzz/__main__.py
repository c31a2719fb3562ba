"""``python -m tests.fuzz --n 5000 --seed 1 --jobs 2``: a long stability-fuzz campaign with a summary.
``python -m tests.fuzz --scan [--commands pitch,teeth]``: every numeric option alone with every
fuzz value instead (``--n`` and ``--seed`` then do not apply).

The seed fixes the invocations; ``--jobs`` runs that many at once (each still its own
subprocess with a timeout and a memory cap); findings are printed in index order.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor

from tests.fuzz.cases import invocations, option_scan
from tests.fuzz.runner import check


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--slow-share", type=float, default=0.1)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--only", default="", help="comma-separated indices to rerun")
    parser.add_argument("--scan", action="store_true", help="each option alone with each value")
    parser.add_argument("--commands", default="", help="with --scan: comma-separated commands")
    args = parser.parse_args(argv)
    if args.scan:
        cases = list(enumerate(option_scan([c for c in args.commands.split(",") if c] or None)))
    else:
        cases = list(enumerate(invocations(args.seed, args.n, args.slow_share)))
    if args.only:
        wanted = {int(i) for i in args.only.split(",")}
        cases = [(i, inv) for i, inv in cases if i in wanted]
    start, findings, commands = time.perf_counter(), Counter(), Counter()
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        # map yields in submission order, so the log is in index order whatever finishes first
        for (i, inv), found in zip(cases, pool.map(lambda case: check(case[1]), cases)):
            commands[inv.args[0]] += 1
            for finding in found:
                findings[finding.split(":")[0]] += 1
                print(f"[{i}] {' '.join(inv.args)[:160]}: {finding}", flush=True)
            if (i + 1) % 100 == 0:
                print(f"... {i + 1} done, {time.perf_counter() - start:.0f} s, findings {dict(findings)}, "
                      f"commands {dict(commands)}", flush=True)
    seconds = time.perf_counter() - start
    what = "option scan" if args.scan else f"seed {args.seed}, n {args.n}"
    print(f"{len(cases)} invocations ({what}, jobs {args.jobs}) in {seconds:.0f} s: "
          f"{sum(findings.values())} findings {dict(findings)}; commands {dict(commands)}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
