"""A printer profile's ``slicer:`` section checked against PrusaSlicer's own options.

The section is copied into every plate's slicer configuration (3MF ``Slic3r_PE.config``,
``--load`` .ini). PrusaSlicer drops a key it does not know without a word and refuses a
plate whose value it cannot read, so both are refused here, at the profile's line, before
anything is built. The catalogue (``prusa_options.json``: per technology, every key
PrusaSlicer reads and the kind of value it takes: ``["enum", choices...]``, "bool", "text",
or "integer" / "number" / "percent" (a number or a percentage of another setting) / "share"
(a percentage, or a fraction: 0.3 is 30 %), the latter four as ``[kind, least]`` or
``[kind, least or None, most]`` where the slicer's range says so) was read off
PrusaSlicer itself (see ``tests/helpers/prusa_options.py``).
"""

from __future__ import annotations

import functools
import importlib.resources
import json
import math
import re
from typing import Any

from wheelstep_cli.config.schema import nearest_name, show

#: Keys wheelstep writes from the printer section itself (a slicer value would contradict it).
FROM_PRINTER = {"bed_shape": "printer.bed", "max_print_height": "printer.max_height",
                "skirts": "printer.skirts", "skirt_distance": "printer.skirt_distance",
                "brim_width": "printer.brim_width", "printer_technology": "printer.technology"}

#: Keys that would compensate in the slicer what the meshes are already drawn compensated for
#: (twice over): the printer section's fields that do it instead.
COMPENSATED = {"elefant_foot_compensation": "printer.elephant_foot_inset",
               "xy_size_compensation": "printer.hole_compensation and printer.tooth_clearance"}

#: One plain number as PrusaSlicer reads it (a sign, digits, a fraction, an exponent).
_NUMBER = r"-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
#: A value per extruder, comma-separated (spaces allowed after a comma).
_LIST = re.compile(rf"^\s*{_NUMBER}%?(\s*,\s*{_NUMBER}%?)*\s*$")


@functools.lru_cache(maxsize=None)
def catalogue() -> dict:
    """{"source": ..., "fff": {key: kind}, "sla": {key: kind}} (see the module docstring)."""
    text = importlib.resources.files("wheelstep_cli.config").joinpath("prusa_options.json").read_text(
        encoding="utf-8")
    return json.loads(text)


def _numbers(value: Any) -> list[str] | None:
    """The values (text) of a number or a comma-separated list of them; None for anything else."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return [repr(value)]
    if isinstance(value, str) and _LIST.match(value):
        return [v.strip() for v in value.split(",")]
    return None


def _limit(kind, value: Any) -> str | None:
    """What ``value`` must be for an option of ``kind`` (see the module docstring); None when it
    is such a value. A number option takes one value per extruder, comma-separated."""
    name, *bounds = kind if isinstance(kind, list) else [kind]
    if name == "enum":
        return None if value in bounds else "must be one of: " + ", ".join(bounds)
    if name == "text":
        return None
    values = _numbers(value)
    numbers = None if values is None else [float(v.rstrip("%")) for v in values]
    if name == "bool":
        ok = isinstance(value, bool) or (numbers is not None and all(n in (0.0, 1.0) for n in numbers))
        return None if ok else "must be true or false (or 1 / 0)"
    shares = name in ("share", "percent")
    if (numbers is None or not all(math.isfinite(n) for n in numbers)
            or (not shares and any(v.endswith("%") for v in values))):
        return {"integer": "must be a whole number", "share": "must be a percentage such as 15% (or a "
                "fraction such as 0.15)", "percent": "must be a number or a percentage such as 15%"
                }.get(name, "must be a number")
    if name == "integer" and not all(re.fullmatch(r"-?\d+", v) for v in values):
        return "must be a whole number (PrusaSlicer would read only its leading digits)"
    # a share's plain number is a fraction (0.3 is 30 %); its bounds are percentages
    scaled = [n if v.endswith("%") or name != "share" else 100.0 * n for v, n in zip(values, numbers)]
    least, most = (bounds + [None, None])[:2]
    unit = "%" if name == "share" else ""
    if least is not None and any(n < least for n in scaled):
        return f"must be >= {least:g}{unit}"
    if most is not None and any(n > most for n in scaled):
        fraction = " (a number without % is a fraction: 0.3 is 30 %)" if name == "share" else ""
        return f"must be at most {most:g}{unit}{fraction}"
    return None


def _cross_rules(settings: dict[str, Any], technology: str) -> list[tuple[str, str]]:
    """What PrusaSlicer refuses of values together: FDM layers thicker than the nozzle."""
    if technology != "fdm":
        return []
    plain = lambda value: [v for v in _numbers(value) or [] if not v.endswith("%")]  # noqa: E731
    nozzle = plain(settings.get("nozzle_diameter", 0.4))
    if not nozzle:
        return []
    if float(nozzle[0]) <= 0.0:      # the slicer's range starts at 0, which lays down nothing
        return [("nozzle_diameter", f"= {show(settings['nozzle_diameter'])}: must be > 0 mm")]
    problems = []
    for key in ("layer_height", "first_layer_height"):
        layer = plain(settings.get(key))
        if layer and float(layer[0]) > float(nozzle[0]):
            problems.append((key, f"= {show(settings[key])}: must be at most the nozzle diameter "
                                  f"({nozzle[0]} mm, nozzle_diameter); PrusaSlicer refuses a thicker layer"))
    return problems


def slicer_problems(settings: dict[str, Any], technology: str) -> list[tuple[str, str]]:
    """(key, problem) of every setting of a ``slicer:`` section PrusaSlicer would not take for
    a printer of ``technology`` (fdm, resin), in the section's order: an unknown key (with the
    nearest known one), a key the printer section sets, a value of the wrong kind or out of the
    slicer's range, a layer thicker than the nozzle (as ``= value: what it must be``)."""
    flavour = "fff" if technology == "fdm" else "sla"
    known = catalogue()[flavour]
    problems = []
    for key, value in settings.items():
        if key in FROM_PRINTER and key in known:
            problems.append((key, f"is set by {FROM_PRINTER[key]} of this profile; give it there"))
        elif key in COMPENSATED and key in known:
            problems.append((key, f"would compensate again what the meshes are drawn compensated for "
                                  f"({COMPENSATED[key]} of this profile); give it there"))
        elif key not in known:
            near = nearest_name(key, known)
            hint = f"; did you mean {near}?" if near else ""
            what = "FDM" if technology == "fdm" else "resin (SLA)"
            problems.append((key, f"not a PrusaSlicer option of {what} printers{hint}"))
        elif (limit := _limit(known[key], value)) is not None:
            problems.append((key, f"= {show(value)}: {limit}"))
    reported = {key for key, _ in problems}
    return problems + [found for found in _cross_rules(settings, technology) if found[0] not in reported]
