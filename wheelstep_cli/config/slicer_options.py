"""A printer profile's ``slicer:`` section checked against PrusaSlicer's own options.

The section is copied into every plate's slicer configuration (3MF ``Slic3r_PE.config``,
``--load`` .ini). PrusaSlicer drops a key it does not know without a word and refuses a
plate whose value it cannot read, so both are refused here, at the profile's line, before
anything is built. The catalogue (``prusa_options.json``: per technology, every key
PrusaSlicer saves and the kind of value it takes) was read off PrusaSlicer itself (see
``tests/helpers/prusa_options.py``).
"""

from __future__ import annotations

import difflib
import functools
import importlib.resources
import json
import re
from typing import Any

from wheelstep_cli.config.schema import show

#: Keys wheelstep writes from the printer section itself (a slicer value would contradict it).
FROM_PRINTER = {"bed_shape": "printer.bed", "max_print_height": "printer.max_height",
                "skirts": "printer.skirts", "skirt_distance": "printer.skirt_distance",
                "brim_width": "printer.brim_width", "printer_technology": "printer.technology"}

_NUMBERS = re.compile(r"^-?\d+(\.\d+)?(,-?\d+(\.\d+)?)*$")
_PERCENTS = re.compile(r"^-?\d+(\.\d+)?%?(,-?\d+(\.\d+)?%?)*$")


@functools.lru_cache(maxsize=None)
def catalogue() -> dict:
    """{"source": ..., "fff": {key: kind}, "sla": {key: kind}} (see the module docstring)."""
    text = importlib.resources.files("wheelstep_cli.config").joinpath("prusa_options.json").read_text(
        encoding="utf-8")
    return json.loads(text)


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _limit(kind, value: Any) -> str | None:
    """What ``value`` must be for an option of ``kind``; None when it is such a value."""
    if isinstance(kind, list):
        return None if value in kind[1:] else "must be one of: " + ", ".join(kind[1:])
    if kind == "bool":
        ok = isinstance(value, bool) or value in (0, 1)
        return None if ok else "must be true or false (or 1 / 0)"
    if kind == "number":
        ok = _number(value) or (isinstance(value, str) and _NUMBERS.match(value) is not None)
        return None if ok else "must be a number"
    if kind == "percent":
        ok = _number(value) or (isinstance(value, str) and _PERCENTS.match(value) is not None)
        return None if ok else "must be a number or a percentage such as 15%"
    return None


def slicer_problems(settings: dict[str, Any], technology: str) -> list[tuple[str, str]]:
    """(key, problem) of every setting of a ``slicer:`` section PrusaSlicer would not take for
    a printer of ``technology`` (fdm, resin), in the section's order: an unknown key (with the
    nearest known one), a key the printer section sets, a value of the wrong kind (as
    ``= value: what it must be``)."""
    flavour = "fff" if technology == "fdm" else "sla"
    known = catalogue()[flavour]
    problems = []
    for key, value in settings.items():
        if key in FROM_PRINTER:
            problems.append((key, f"is set by {FROM_PRINTER[key]} of this profile; give it there"))
        elif key not in known:
            near = difflib.get_close_matches(key, known, n=1)
            hint = f"; did you mean {near[0]}?" if near else ""
            what = "FDM" if technology == "fdm" else "resin (SLA)"
            problems.append((key, f"not a PrusaSlicer option of {what} printers{hint}"))
        elif (limit := _limit(known[key], value)) is not None:
            problems.append((key, f"= {show(value)}: {limit}"))
    return problems
