"""The results of a sweep as they come: rows buffered a few at a time into Parquet part files
(bounded memory, nothing lost at Ctrl-C but the buffer, which is flushed on the way out),
then merged with the earlier results into ``results.parquet`` and ``results.csv`` in point
order (whatever order the workers finished in), each replaced atomically. The keys of the
rows already there let a rerun skip them.

Deterministic by design: every column but the last, ``seconds`` (the time a point took), is
the same in every run of the same sweep with the same versions, so two runs' files differ
in that column only. The folder's outputs are owned (formats.owned): the record
``.wheelstep-sweep.json`` holds their SHA-256, and a file of the same name that a sweep did
not write is refused unless --force."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any, Iterable

from wheelstep_cli.batch.interrupts import interrupts_deferred
from wheelstep_cli.batch.sweep_point import BAND_FIGURES, FIGURES
from wheelstep_cli.errors import DesignError

RESULTS = "results.parquet"
CSV = "results.csv"
PLOT = "pareto.png"
PARTS = ".sweep-parts"
RECORD = ".wheelstep-sweep.json"
#: Rows held before they are written (and seconds at most between two writes).
FLUSH_ROWS = 16
FLUSH_SECONDS = 5.0


def schema(axes: dict[str, str], band: bool = False):
    """The columns: key and point, the varied parameters (``p_NAME``, typed), the resolved
    design (JSON), outcome and reason, the figures (with ``band``, the tolerance band's),
    versions, and last the seconds the point took (the one column that differs between runs)."""
    import pyarrow as pa

    types = {"int": pa.int64(), "float": pa.float64(), "bool": pa.bool_(), "str": pa.string()}
    fields = [("key", pa.string()), ("index", pa.int64()), ("command", pa.string()),
              ("printer", pa.string())]
    fields += [(f"p_{name}", types[kind]) for name, kind in axes.items()]
    fields += [("parameters", pa.string()), ("outcome", pa.string()), ("reason", pa.string()),
               ("interference", pa.bool_())]
    fields += [(name, pa.float64()) for name in FIGURES]
    fields += [(name, pa.bool_() if name.endswith("_jams") else pa.float64())
               for name in (BAND_FIGURES if band else ())]
    fields += [("versions", pa.string()), ("seconds", pa.float64())]
    return pa.schema(fields)


def axis_kinds(points: Iterable[dict], names: Iterable[str]) -> dict[str, str]:
    """The column type of each varied parameter from all its values (ints with floats: float)."""
    kinds: dict[str, set] = {name: set() for name in names}
    for values in points:
        for name in kinds:
            value = values.get(name)
            kinds[name].add("bool" if isinstance(value, bool) else "int" if isinstance(value, int)
                            else "float" if isinstance(value, float) else "str")
    return {name: ("float" if found <= {"int", "float"} and "float" in found
                   else found.pop() if len(found) == 1 else "str") for name, found in kinds.items()}


def cell(value: Any, kind: str):
    """A parameter value as its column holds it."""
    if value is None:
        return None
    return float(value) if kind == "float" else value if kind != "str" else (
        value if isinstance(value, str) else json.dumps(value))


class ResultStore:
    """Rows appended to part files in ``out/.sweep-parts``; :meth:`consolidate` merges them
    (with the earlier ``results.parquet`` unless ``earlier`` is False: not the sweep's own)."""

    def __init__(self, out: Path, columns, earlier: bool = True):
        self.out, self.schema, self.earlier = Path(out), columns, earlier
        self.parts = self.out / PARTS
        self.buffer: list[dict] = []
        self.last = time.monotonic()
        self.count = len(list(self.parts.glob("part-*.parquet"))) if self.parts.is_dir() else 0
        self._check_earlier()
        self.dropped = 0      # rows the last consolidate left out (see consolidate)

    def _check_earlier(self) -> None:
        import pyarrow.parquet as pq

        results = self.out / RESULTS
        if self.earlier and results.exists() and not pq.read_schema(results).equals(self.schema):
            raise DesignError("out", str(self.out), f"holds {RESULTS} of another sweep (other "
                                                    "columns); give another folder")

    def done_keys(self) -> set[str]:
        """Keys of the rows written already (results and unmerged parts)."""
        import pyarrow.parquet as pq

        keys: set[str] = set()
        for file in self._files():
            keys.update(pq.read_table(file, columns=["key"]).column("key").to_pylist())
        return keys

    def _files(self) -> list[Path]:
        results = self.out / RESULTS
        parts = sorted(self.parts.glob("part-*.parquet")) if self.parts.is_dir() else []
        return ([results] if self.earlier and results.exists() else []) + parts

    def add(self, row: dict) -> None:
        self.buffer.append(row)
        if len(self.buffer) >= FLUSH_ROWS or time.monotonic() - self.last > FLUSH_SECONDS:
            self.flush()

    def flush(self) -> None:
        """Write the buffered rows as one part file (renamed into place when complete)."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        self.last = time.monotonic()
        if not self.buffer:
            return
        self.parts.mkdir(parents=True, exist_ok=True)
        table = pa.Table.from_pylist(self.buffer, schema=self.schema)
        path = self.parts / f"part-{self.count:06d}.parquet"
        staged = path.with_suffix(".tmp")
        pq.write_table(table, staged)
        os.replace(staged, path)
        self.count += 1
        self.buffer = []


    def consolidate(self, points: dict[str, int] | None = None) -> Path:
        """Merge the earlier results and every part file into ``results.parquet`` and
        ``results.csv`` in point order (each replaced atomically, then recorded as the
        sweep's); parts removed. With ``points`` (key -> the point's index in the plan now),
        only those rows, each at its point's index: rows of points left out of the grid, or
        computed by other code or libraries, are dropped (counted in ``self.dropped``). The
        rows are held here at once: at most MAX_POINTS small rows (figures and the design's
        JSON, about 1 kB each; no meshes)."""
        import pyarrow as pa
        import pyarrow.csv as pcsv
        import pyarrow.parquet as pq

        self.flush()
        files = self._files()
        self.out.mkdir(parents=True, exist_ok=True)
        table = (pa.concat_tables([pq.read_table(f, schema=self.schema) for f in files])
                 if files else self.schema.empty_table())
        self.dropped = 0
        if points is not None:
            table, self.dropped = of_points(table, points)
        table = ordered(table)
        staged_pq, staged_csv = self.out / f".{RESULTS}.tmp", self.out / f".{CSV}.tmp"
        pq.write_table(table, staged_pq)
        pcsv.write_csv(table, staged_csv)
        # a Ctrl-C between replacing the results and recording them (or removing the merged
        # parts) would leave results a rerun does not take as the sweep's: it waits until after
        with interrupts_deferred():
            os.replace(staged_pq, self.out / RESULTS)
            os.replace(staged_csv, self.out / CSV)
            record_outputs(self.out, (RESULTS, CSV))
            # the results are the sweep's own now: a later consolidate merges with them
            self.earlier = True
            for file in files:
                if file.parent == self.parts:     # merged now
                    file.unlink()
            if self.parts.is_dir() and not any(self.parts.iterdir()):
                self.parts.rmdir()
        return self.out / RESULTS


def of_points(table, points: dict[str, int]):
    """(the rows of ``points``' keys, each with its point's index; how many other keys)."""
    import pyarrow as pa

    keys = table.column("key").to_pylist()
    # typed: an empty list of indices would be an array of nulls, which take refuses
    kept = table.take(pa.array([i for i, key in enumerate(keys) if key in points], type=pa.int64()))
    column = kept.schema.get_field_index("index")
    index = pa.array([points[key] for key in kept.column("key").to_pylist()],
                     type=kept.schema.field(column).type)
    return (kept.set_column(column, kept.schema.field(column), index),
            len({key for key in keys if key not in points}))


def ordered(table):
    """The rows in point order (then by key), each key once: the first (a row both merged and
    still in a part file, after a crash between the two, is kept once)."""
    table = table.sort_by([("index", "ascending"), ("key", "ascending")])
    seen: set[str] = set()
    first = [i for i, key in enumerate(table.column("key").to_pylist())
             if not (key in seen or seen.add(key))]
    return table if len(first) == table.num_rows else table.take(first)


def owned_results(out: Path, force: bool) -> bool:
    """Refuse (naming --out) before any work a file among the sweep's outputs in ``out`` that
    no sweep wrote with its present content, unless ``force``; True when ``out``'s
    results.parquet is the sweep's own (its rows are kept and skipped by a rerun), False
    when there is none or it is a file forced over (its rows are not read)."""
    from wheelstep_cli.formats.owned import check_collisions, read_record, sha256_of

    record = read_record(out / RECORD)
    check_collisions(out, {out / name: b"" for name in (RESULTS, CSV, PLOT)}, record, force)
    results = out / RESULTS
    return results.is_file() and record.get(RESULTS) == sha256_of(results)


def record_outputs(out: Path, names) -> None:
    """Record the files ``names`` in ``out`` (as they are now) as the sweep's, keeping the
    record's other entries."""
    from wheelstep_cli.formats.atomic import write_bytes_atomic
    from wheelstep_cli.formats.owned import merged_record_bytes, read_record

    files = {out / name: (out / name).read_bytes() for name in names}
    write_bytes_atomic(out / RECORD, merged_record_bytes("wheelstep sweep", out, files,
                                                         read_record(out / RECORD)))


def pareto_order(first, second) -> tuple[list[int], list[bool]]:
    """Row order best first for two objectives (smaller is better): the Pareto front by the
    first objective, then the others by it; and which rows are on the front."""
    import numpy as np

    a, b = np.asarray(first, float), np.asarray(second, float)
    order = np.lexsort((b, a))
    front = np.zeros(len(a), bool)
    best = np.inf
    for i in order:
        if b[i] < best:
            front[i], best = True, b[i]
    ranked = [int(i) for i in order if front[i]] + [int(i) for i in order if not front[i]]
    return ranked, front.tolist()
