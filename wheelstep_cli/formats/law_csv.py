"""Transmission-law samples from a CSV file: rows ``driving_deg, driven_deg`` (degrees)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from wheelstep_cli.errors import DesignError, file_problem, require


#: A plain decimal number as a law CSV writes one (no underscores, no nan or inf).
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def _row(cells: list[str], line: int) -> tuple[float, float] | None:
    """The (driving, driven) degrees of a row's cells, None for a header line; a row that is
    neither a header nor two plain numbers is a DesignError's text (raised as ValueError)."""
    numeric = [bool(_NUMBER.fullmatch(c)) for c in cells]
    if not numeric[0]:
        return None                      # a header line (names, or a note such as 'period,360')
    bad = next((c for c, ok in zip(cells, numeric) if not ok), None)
    if bad is not None:
        raise ValueError(f"line {line}: {bad!r} is not a plain number")
    if len(cells) != 2:
        raise ValueError(f"line {line}: has {len(cells)} values; a row is 'driving_deg, driven_deg'")
    return float(cells[0]), float(cells[1])


def read_law_csv(path, param: str = "law_csv"):
    """Read the rows (header lines first; ``;`` or ``,``) and build the tabulated law. A line
    that is neither, or a header line after the first row, is refused naming its line: a
    typo skipped would change the law."""
    from wheelstep_cli.gears.laws import law_from_samples

    try:
        data = Path(path).read_bytes()
    except OSError as err:
        raise DesignError(param, str(path), file_problem(path, err)) from None
    require(len(data) <= 1 << 22, param, str(path), "is larger than 4 MiB; one period of samples is enough")
    try:
        text = data.decode("utf-8-sig").replace("\x1a", "")   # a spreadsheet's BOM, an old end-of-file mark
    except UnicodeDecodeError:
        raise DesignError(param, str(path), "is not UTF-8 text") from None
    rows, lines, written = [], [], []
    for number, line in enumerate(text.splitlines(), start=1):
        line = line.split("#", 1)[0]     # a comment, on its own line or after a row
        cells = [c.strip() for c in line.replace(";", ",").split(",")]
        while cells and not cells[-1]:
            cells.pop()                  # a spreadsheet's trailing separators
        if not cells:
            continue                     # a blank or comment line
        try:
            row = _row(cells, number)
        except ValueError as err:
            raise DesignError(param, str(path), str(err)) from None
        if row is None and rows:
            raise DesignError(param, str(path), f"line {number}: {line.strip()[:40]!r} is not a row "
                                                "of two plain numbers (headers and notes go before the rows)")
        if row is not None:
            rows.append(row)
            lines.append(number)
            written.append(cells)
    require(len(rows) >= 8, param, str(path), "needs at least 8 numeric rows 'driving_deg, driven_deg'")
    data = np.array(rows)
    _period_as_written(data, written)
    _require_period(data, lines, param, str(path))
    try:
        return law_from_samples(data[:, 0], data[:, 1], param)
    except DesignError as err:      # said of the file as given (its limit says what was found)
        if err.param != param:
            raise
        raise DesignError(param, str(path), err.limit) from None


def _period_as_written(data: np.ndarray, written: list[list[str]]) -> None:
    """Set each column's last row (deg) to exactly one period (360/k deg, k whole) past its
    first where the span the rows give is that period to the decimals the column is written
    with (360/7 written to 2 decimals spans 51.43 deg): the period of closed gears is exact,
    a rounded span is not. The column's finest written step sets the slack (a first row
    written 0 is exact, not 0 +- 0.5). A span farther off is left for :func:`_require_period`
    to refuse."""
    for column in range(2):
        span = float(data[-1, column] - data[0, column])
        if span <= 0.0:
            continue
        k = max(1, round(360.0 / span))
        slack = 0.5 * min(_written_step(cells[column]) for cells in written)
        if abs(span - 360.0 / k) <= slack:
            data[-1, column] = data[0, column] + 360.0 / k


def _written_step(cell: str) -> float:
    """The unit of the last decimal a plain number is written to (deg): '51.43' -> 0.01."""
    from decimal import Decimal

    return 10.0 ** int(Decimal(cell).as_tuple().exponent)


def _require_period(data: np.ndarray, lines: list[int], param: str, path: str) -> None:
    """Refuse rows (deg) that do not run over one period of closed gears (see
    :func:`~wheelstep_cli.gears.laws.period_fault`), naming the lines."""
    from wheelstep_cli.gears.laws import period_fault

    fault = period_fault(data[:, 0], data[:, 1])
    if fault is None:
        return
    name, at, span = fault
    column = data[:, 0 if name == "driving" else 1]
    if at is not None:
        raise DesignError(param, path, f"line {lines[at]}: the {name} angle {column[at]:g} deg does not "
                                       f"increase past {column[at - 1]:g} deg (line {lines[at - 1]}); both "
                                       "angles increase strictly over one period")
    raise DesignError(param, path, f"the {name} angle spans {span:g} deg from line {lines[0]} to line "
                                   f"{lines[-1]}; it must span 360/k deg (k whole: closed gears), the last "
                                   "row repeating the first one period on")
