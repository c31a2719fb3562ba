"""``python -m tests.fuzz --n 5000 --seed 1``: a long stability-fuzz campaign with a summary."""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter

from tests.fuzz.cases import invocations
from tests.fuzz.runner import check


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--slow-share", type=float, default=0.1)
    args = parser.parse_args(argv)
    start, findings, commands = time.perf_counter(), Counter(), Counter()
    for i, inv in enumerate(invocations(args.seed, args.n, args.slow_share)):
        commands[inv.args[0]] += 1
        for finding in check(inv):
            findings[finding.split(":")[0]] += 1
            print(f"[{i}] {' '.join(inv.args)[:160]}: {finding}", flush=True)
    seconds = time.perf_counter() - start
    print(f"{args.n} invocations (seed {args.seed}) in {seconds:.0f} s: "
          f"{sum(findings.values())} findings {dict(findings)}; commands {dict(commands)}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
