"""Deterministic JSON and CSV encoding for reports and tables."""

from __future__ import annotations

import io
import json
import os
from enum import Enum

import numpy as np


def _plain(value):
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, (np.floating, float)):
        return round(float(value), 9)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (np.bool_,)):
        return bool(value)
    if isinstance(value, Enum):
        return _plain(value.value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def json_text(data) -> str:
    """Indented JSON of plain data (numpy values converted, floats to 9 decimals)."""
    return json.dumps(_plain(data), indent=2) + "\n"


def json_bytes(data) -> bytes:
    return json_text(data).encode("utf-8")


def csv_bytes(header: list[str], rows: np.ndarray, fmt: str | list[str] = "%.6f") -> bytes:
    """CSV with a header line; ``rows`` a 2D numeric array; ``fmt`` one format for every
    column or one per column (``%d`` for a 0/1 flag)."""
    buf = io.StringIO()
    np.savetxt(buf, np.asarray(rows, dtype=float), fmt=fmt, delimiter=",",
               header=",".join(header), comments="")
    return buf.getvalue().encode("utf-8")
