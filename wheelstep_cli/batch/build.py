"""Building the entries of a batch: each in a worker process (one failure does not stop the
others), its parts laid on z = 0, compensated for the printer and checked."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from wheelstep_cli.batch.plan import Entry
from wheelstep_cli.config.names import yaml_message
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.kinds import KINDS


@dataclass
class BuiltPart:
    """A checked, printer-compensated part lying on z = 0, with its footprint (mm)."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    volume: float
    expected_volume: float
    triangles: int
    footprint: list[list[np.ndarray]]
    checks: dict[str, bool]

    @property
    def bounds(self) -> np.ndarray:
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @property
    def perimeter(self) -> float:
        """Length (mm) of all footprint rings."""
        return float(sum(np.linalg.norm(np.diff(r, axis=0, append=r[:1]), axis=1).sum()
                         for polygon in self.footprint for r in polygon))


@dataclass
class EntryResult:
    index: int
    parts: list[BuiltPart] = field(default_factory=list)
    report: dict | None = None
    error: str | None = None
    param: str | None = None


def build_entry(entry: Entry) -> EntryResult:
    """Build one entry's parts for its printer (worker-process entry point; never raises)."""
    from wheelstep_cli.geometry.mesh_checks import Part, require_printable
    from wheelstep_cli.geometry.solids import footprint, inset_bottom

    try:
        kind = KINDS[entry.kind]
        built = kind.build_part(entry.printed)
        parts = []
        for part in kind.parts(built):
            part = inset_bottom(part, entry.printer.elephant_foot_height, entry.printer.elephant_foot_inset)
            lift = np.array([0.0, 0.0, -part.bounds[0, 2]])
            part = Part(part.name, part.vertices + lift, part.faces, part.expected_volume)
            check = require_printable(part)
            parts.append(BuiltPart(
                part.name, part.vertices, part.faces, check.volume, check.expected_volume,
                check.triangles, footprint(part),
                {"manifold": True, "watertight": check.watertight,
                 "winding_consistent": check.winding_consistent,
                 "volume_matches_outline": check.volume_error < 1e-3}))
        return EntryResult(entry.index, parts, kind.report_of(built))
    except DesignError as err:
        return EntryResult(entry.index, error=yaml_message(err), param=err.param)
    except Exception as err:  # an unexpected failure must not stop the other entries
        return EntryResult(entry.index, error=f"internal error: {type(err).__name__}: {err}")



class _Serial:
    """In-process stand-in for an executor (``--jobs 1``)."""

    def __enter__(self):
        return None

    def __exit__(self, *exc):
        return False


def executor(jobs: int):
    if jobs <= 1:
        return _Serial()
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    # spawn: safe with manifold3d's threads and the same on every platform
    return ProcessPoolExecutor(max_workers=jobs, mp_context=multiprocessing.get_context("spawn"))


def map_items(pool, function, items, step, lazy: bool = False):
    """Results of ``function`` over ``items`` (any order), calling ``step()`` after each.

    With a pool the work is submitted at once; ``lazy`` (serial only) defers it until the
    results are read, so that the caller can do other work first either way.
    """
    if pool is None:
        results = (_call_and_step(function, item, step) for item in items)
        return results if lazy else list(results)
    futures = {pool.submit(function, item): item for item in items}
    return _collect(futures, step)


def _call_and_step(function, item, step):
    result = function(item)
    step()
    return result


def _collect(futures, step):
    from concurrent.futures import as_completed

    for future in as_completed(futures):
        try:
            result = future.result()
        except Exception as err:  # a worker died (e.g. killed): fail this item only
            item = futures[future]
            if isinstance(item, Entry):
                result = EntryResult(item.index, error=f"worker process failed: {type(err).__name__}: {err}")
            else:
                raise
        step()
        yield result


