"""Transmission-law samples from a CSV file: rows ``driving_deg, driven_deg`` (degrees)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from wheelstep_cli.errors import DesignError, require


def read_law_csv(path, param: str = "law_csv"):
    """Read the rows (header lines allowed; ``;`` or ``,``) and build the tabulated law."""
    from wheelstep_cli.gears.laws import law_from_samples

    try:
        data = Path(path).read_bytes()
    except OSError as err:
        raise DesignError(param, str(path), f"cannot be read ({err.strerror or err})") from None
    require(len(data) <= 1 << 22, param, str(path), "is larger than 4 MiB; one period of samples is enough")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise DesignError(param, str(path), "is not UTF-8 text") from None
    rows = []
    for line in text.splitlines():
        cells = [c.strip() for c in line.replace(";", ",").split(",") if c.strip()]
        if len(cells) < 2:
            continue
        try:
            rows.append((float(cells[0]), float(cells[1])))
        except ValueError:
            continue  # a header line
    require(len(rows) >= 8, param, str(path), "needs at least 8 numeric rows 'driving_deg, driven_deg'")
    data = np.array(rows)
    return law_from_samples(data[:, 0], data[:, 1], param)
