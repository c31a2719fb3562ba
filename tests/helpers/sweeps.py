"""A small sweep file and its result rows, shared by the sweep tests."""

from __future__ import annotations

from pathlib import Path

import pyarrow.parquet as pq

# cheap shoes (desk-demo, narrow); socket_depth 60 is deeper than the body: a refused point
SHOES = """\
command: shoe
design: desk-demo
fixed:
  width: 12
grid:
  socket_depth: [10, 60]
  rim: {start: 10, stop: 14, step: 2}
printers: [fdm-0.4-pla]
"""
#: The points of :data:`SHOES` (2 socket depths x 3 rims).
POINTS = 6


def rows(out: Path) -> dict[str, dict]:
    """key -> the row's parameters, outcome, reason and figures (not its time)."""
    table = pq.read_table(out / "results.parquet").to_pylist()
    assert len({r["key"] for r in table}) == len(table)
    return {r["key"]: {k: v for k, v in r.items() if k != "seconds"} for r in table}
