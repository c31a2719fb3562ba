"""Batch builds for the print shop: a YAML list of parts -> plates, a manifest and a print sheet.

Stages: :func:`load_batch` (plan.py) reads and checks the whole file (and the profiles it
names) with the configuration models before anything is built, every problem reported as
``file:line``; :func:`run_batch` (run.py) builds the entries in parallel worker processes
(build.py; one failing entry does not stop the others), packs every part times its
quantity onto the beds of its printer and renders the plates (plates.py), and writes
them with the reports, print sheet and manifest (outputs.py) in one atomic step.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from wheelstep_cli.batch.plan import BatchPlan, Entry, load_batch
    from wheelstep_cli.batch.run import BatchOutcome, run_batch

__all__ = ["BatchOutcome", "BatchPlan", "Entry", "load_batch", "run_batch"]

# Loaded on first use: the console script imports batch.interrupts for every command, and
# a single `gears` run should not pay for the batch pipeline's imports.
_HOME = {"BatchPlan": "plan", "Entry": "plan", "load_batch": "plan",
         "BatchOutcome": "run", "run_batch": "run"}


def __getattr__(name: str) -> object:
    if name not in _HOME:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(f"{__name__}.{_HOME[name]}"), name)
