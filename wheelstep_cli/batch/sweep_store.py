"""The results of a sweep as they come: rows buffered a few at a time into Parquet part files
(bounded memory, nothing lost at Ctrl-C but the buffer, which is flushed on the way out),
then merged with the earlier results into ``results.parquet`` and ``results.csv``, each
replaced atomically. The keys of the rows already there let a rerun skip them."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any, Iterable

from wheelstep_cli.batch.sweep_point import FIGURES
from wheelstep_cli.errors import DesignError

RESULTS = "results.parquet"
CSV = "results.csv"
PARTS = ".sweep-parts"
#: Rows held before they are written (and seconds at most between two writes).
FLUSH_ROWS = 16
FLUSH_SECONDS = 5.0


def schema(axes: dict[str, str]):
    """The columns: key and point, the varied parameters (``p_NAME``, typed), the resolved
    design (JSON), outcome and reason, the figures, seconds and versions."""
    import pyarrow as pa

    types = {"int": pa.int64(), "float": pa.float64(), "bool": pa.bool_(), "str": pa.string()}
    fields = [("key", pa.string()), ("index", pa.int64()), ("command", pa.string()),
              ("printer", pa.string())]
    fields += [(f"p_{name}", types[kind]) for name, kind in axes.items()]
    fields += [("parameters", pa.string()), ("outcome", pa.string()), ("reason", pa.string()),
               ("interference", pa.bool_())]
    fields += [(name, pa.float64()) for name in FIGURES]
    fields += [("seconds", pa.float64()), ("versions", pa.string())]
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
    """Rows appended to part files in ``out/.sweep-parts``; :meth:`consolidate` merges them."""

    def __init__(self, out: Path, columns):
        self.out, self.schema = Path(out), columns
        self.parts = self.out / PARTS
        self.buffer: list[dict] = []
        self.last = time.monotonic()
        self.count = len(list(self.parts.glob("part-*.parquet"))) if self.parts.is_dir() else 0
        self._check_earlier()

    def _check_earlier(self) -> None:
        import pyarrow.parquet as pq

        results = self.out / RESULTS
        if results.exists() and not pq.read_schema(results).equals(self.schema):
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
        return ([results] if results.exists() else []) + parts

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

    def consolidate(self) -> Path:
        """Merge the earlier results and every part file, one file at a time, into
        ``results.parquet`` and ``results.csv`` (each replaced atomically); parts removed."""
        import pyarrow.csv as pcsv
        import pyarrow.parquet as pq

        self.flush()
        files = self._files()
        self.out.mkdir(parents=True, exist_ok=True)
        staged_pq, staged_csv = self.out / f".{RESULTS}.tmp", self.out / f".{CSV}.tmp"
        with pq.ParquetWriter(staged_pq, self.schema) as writer, \
                pcsv.CSVWriter(staged_csv, self.schema) as csv:
            for file in files:
                source = pq.ParquetFile(file)
                for group in range(source.num_row_groups):
                    table = source.read_row_group(group)
                    writer.write_table(table)
                    csv.write_table(table)
        os.replace(staged_pq, self.out / RESULTS)
        os.replace(staged_csv, self.out / CSV)
        for file in files:
            if file.parent == self.parts:     # merged now
                file.unlink()
        if self.parts.is_dir() and not any(self.parts.iterdir()):
            self.parts.rmdir()
        return self.out / RESULTS


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
