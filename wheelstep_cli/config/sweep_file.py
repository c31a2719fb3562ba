"""A sweep file: which command's parameters to vary, how (a grid, or seeded random samples
within bounds), what stays fixed and on which printer presets; read and checked whole, every
problem at once as ``file:line``.

The points are the product of the grid axes and the printers, times ``samples`` random
draws when ``random:`` is given (each draw combined with every grid point). At most
:data:`MAX_POINTS` points.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from wheelstep_cli.config.located_yaml import LocatedYaml, YamlSyntaxError, read_located_yaml
from wheelstep_cli.config.schema import (InvalidInput, Issue, dotted, file_issues, section_model, show,
                                         validate_file, yaml_issues)
from wheelstep_cli.config.specs import GearPairSpec, ShoeSpec
from wheelstep_cli.config.sweep_model import MAX_POINTS, OBJECTIVES, Bounds, RandomAxes, Range, SweepFile
from wheelstep_cli.errors import DesignError

#: The spec of each command a sweep can run, and the design-profile section of its options.
COMMANDS = {"gears": (GearPairSpec, "gears"), "shoe": (ShoeSpec, "shoe")}
#: The figures each command's designs are ranked by when the file names none (of OBJECTIVES).
DEFAULT_OBJECTIVES = {"gears": ["drive_f_i_um", "backlash_max_mm"], "shoe": ["volume_mm3", "mass_g"]}
#: The figures each command's rows hold (a shoe has no teeth to measure).
COMMAND_OBJECTIVES = {"gears": OBJECTIVES, "shoe": ("volume_mm3", "mass_g")}
#: The figure that needs a printer: the volume times the printer's material density.
NEEDS_PRINTER = "mass_g"


@dataclass(frozen=True)
class SweepPlan:
    """A checked sweep: the command, its design profile, the printers and every point's values."""

    label: str
    command: str
    design: str | None
    objectives: tuple[str, str]
    allow_interference: bool
    axes: tuple[str, ...]                 # names of the parameters that vary, in file order
    points: tuple[tuple[str | None, dict[str, Any]], ...]   # (printer preset, given values)
    tolerance: bool = False               # each gear pair also checked over its printer's band


def load_sweep(path: Path, label: str | None = None) -> SweepPlan:
    """Read and check a sweep file; InvalidInput lists every problem with its line."""
    label = label or str(path)
    try:
        doc = read_located_yaml(path, label)
    except YamlSyntaxError as err:
        raise InvalidInput(yaml_issues(err)) from None
    issues: list[Issue] = []
    sweep = validate_file(SweepFile, doc, (), issues)
    data = _found_beside(Path(path).parent, doc.data if isinstance(doc.data, dict) else {})
    if sweep is not None:
        sweep = sweep.model_copy(update={key: data.get(key) for key in ("design", "printers")})
    random = None
    if isinstance(data.get("random"), dict):
        random = validate_file(RandomAxes, doc, ("random",), issues)
    grid = _grid(doc, data.get("grid"), issues)
    command = data.get("command")
    if command in COMMANDS:
        _check_values(doc, COMMANDS[command][0], command, data, grid, random, issues)
    _check_objectives(doc, data.get("objectives"), command, bool(data.get("printers")), issues)
    _check_printers(doc, data.get("printers"), issues)
    _check_profile_files(doc, data.get("design"), data.get("printers"), issues)
    _check_bands(doc, command, data.get("printers"), data.get("tolerance") is True, issues)
    if command == "shoe" and data.get("allow_interference") is True:
        issues.append(Issue(doc.where(("allow_interference",)), "allow_interference",
                            "= true: keeps gear pairs whose teeth interfere (command: gears); a shoe has no teeth"))
    if issues:
        raise InvalidInput(issues)
    # counted before the points are listed (a product of long axes would not fit in memory)
    count = math.prod([len(sweep.printers or [None]), random.samples if random else 1,
                       *(len(a) if isinstance(a, list) else _range_count(a) for a in grid.values())])
    if count > MAX_POINTS:
        raise InvalidInput([Issue(doc.where(()), "", f"the sweep has {count} points; at most "
                                                     f"{MAX_POINTS}")])
    points = _points(sweep, grid, random)
    objectives = tuple(sweep.objectives or DEFAULT_OBJECTIVES[sweep.command])
    axes = tuple(grid) + tuple(random.bounds if random else ())
    return SweepPlan(label, sweep.command, sweep.design, objectives, sweep.allow_interference,
                     axes, tuple(points), sweep.tolerance)


def _grid(doc: LocatedYaml, raw, issues: list[Issue]) -> dict[str, list | Range]:
    """The grid axes that are a list of values or a valid Range (the others: issues)."""
    axes: dict[str, list | Range] = {}
    for key, axis in (raw.items() if isinstance(raw, dict) else []):
        at = ("grid", key)
        if isinstance(axis, list):
            axes[key] = axis
        elif isinstance(axis, dict):
            found = validate_file(Range, doc, at, issues)
            if found is not None and _range_count(found) > MAX_POINTS:
                # said before its values are listed: a tiny step would exhaust the memory
                issues.append(Issue(doc.where(at), dotted(at), f"range {show(found.start)}..{show(found.stop)} "
                                    f"step {show(found.step)} holds {_count_text(_range_count(found))} values; a sweep "
                                    f"has at most {MAX_POINTS} points"))
            elif found is not None:
                axes[key] = found
        else:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(axis)}: must be a list of values "
                                                           "or {start, stop, step}"))
    return axes


def _check_values(doc: LocatedYaml, spec, command: str, data: dict, grid: dict,
                  random: RandomAxes | None, issues: list[Issue]) -> None:
    """Every named parameter is the command's, named once, every value within its field's limits."""
    fields = section_model(spec)
    seen: dict[str, str] = {}
    fixed = data.get("fixed") if isinstance(data.get("fixed"), dict) else {}
    named = [("fixed", k, [v]) for k, v in fixed.items()]
    named += [("grid", k, _axis_values(v)) for k, v in grid.items()]
    if random is not None:
        named += [(("random", "bounds"), k, [b.low, b.high]) for k, b in random.bounds.items()]
    for section, key, values in named:
        at = (section if isinstance(section, tuple) else (section,)) + (key,)
        if key not in fields.model_fields:
            issues.append(Issue(doc.where(at), dotted(at), f"unknown parameter of {command}; "
                                "allowed: " + ", ".join(fields.model_fields)))
            continue
        if key in seen:
            issues.append(Issue(doc.where(at), dotted(at), f"already given at {seen[key]}"))
            continue
        seen[key] = doc.where(at)
        issues.extend(_value_issues(doc, fields, at, key, grid.get(key), values))
    for key, b in (random.bounds.items() if random is not None else []):
        if b.low > b.high:
            at = ("random", "bounds", key)
            issues.append(Issue(doc.where(at), dotted(at), f"low {show(b.low)} > high {show(b.high)}"))
    held = _distinct_draws(random) if random is not None and not issues else None
    if held is not None and random.samples > held:
        at = ("random", "samples")
        issues.append(Issue(doc.where(at), dotted(at), f"= {random.samples}: more than the {held} "
                            f"different point{'s' if held != 1 else ''} the bounds hold (whole numbers, "
                            f"or decimals to 9 places); at most {held}"))


def _value_issues(doc, fields, at: tuple, key: str, axis, values: list) -> list[Issue]:
    """The problems of the values of one parameter (an empty range, one out of limits)."""
    if isinstance(axis, Range) and not values:
        return [Issue(doc.where(at), dotted(at), f"range {show(axis.start)}..{show(axis.stop)} step "
                                                  f"{show(axis.step)} holds no value")]
    if isinstance(axis, list) and not axis:
        return [Issue(doc.where(at), dotted(at), "must list at least one value")]
    if isinstance(axis, Range) and len({_point_key(v) for v in values}) < len(values):
        # kept to 12 decimals, values closer than that are one point: a row where several were asked for
        return [Issue(doc.where(at), dotted(at), f"step {show(axis.step)} is too fine: its values round "
                                                  "alike to 12 decimals (one point where several are asked "
                                                  "for); give a coarser step")]
    first: dict = {}
    for i, value in enumerate(axis if isinstance(axis, list) else []):
        same = _point_key(value)
        if same in first:
            # the two would be one point: computed once, one row, where two were asked for
            earlier = first[same]
            return [Issue(doc.where(at + (i,)), dotted(at + (i,)), f"= {show(value)}: repeats "
                          f"{dotted(at + (earlier,))} = {show(axis[earlier])}; list each value once")]
        first[same] = i
    for i, value in enumerate(values):
        try:
            fields.model_validate({key: value})
        except ValidationError as err:
            where = at + (i,) if isinstance(axis, list) else at
            return [Issue(doc.where(where), dotted(where), issue.message)
                    for issue in file_issues(fields, LocatedYaml(doc.file, {key: value}), (), err)][:1]
    return []


def _check_objectives(doc: LocatedYaml, names, command, printers: bool, issues: list[Issue]) -> None:
    """Each objective is a figure the command's rows hold: one of its figures, and the mass
    only where the sweep names printers (a row without one has no mass)."""
    for i, name in enumerate(names if isinstance(names, list) else []):
        at = ("objectives", i)
        if i and name in names[:i]:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: names objectives[{names.index(name)}] again; "
                                "a front of one figure is its least value: name two different figures"))
        elif name not in OBJECTIVES:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: must be one of: "
                                + ", ".join(OBJECTIVES)))
        elif command in COMMAND_OBJECTIVES and name not in COMMAND_OBJECTIVES[command]:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: is not a figure of "
                                f"command: {command}; its figures: " + ", ".join(COMMAND_OBJECTIVES[command])))
        elif name == NEEDS_PRINTER and not printers:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: needs `printers:` (the "
                                "mass is the volume times the printer's material density)"))


def _found_beside(folder: Path, data: dict) -> dict:
    """``data`` with its design profile and printer profiles given as YAML paths looked up
    beside the sweep file (in ``folder``) first, as a batch file's are."""
    from wheelstep_cli.config.profiles import beside

    def found(name):
        return beside(folder, name) if isinstance(name, str) and name.endswith((".yaml", ".yml")) else name

    out = {**data, "design": found(data.get("design"))}
    if isinstance(data.get("printers"), list):
        out["printers"] = [found(name) for name in data["printers"]]
    return out


def _check_printers(doc: LocatedYaml, names, issues: list[Issue]) -> None:
    """Each printer is a known printer preset or a YAML file."""
    from wheelstep_cli.config.profiles import profile_names

    known = profile_names(printer=True)
    listed = names if isinstance(names, list) else []
    for i, name in enumerate(listed):
        at = ("printers", i)
        if isinstance(name, str) and name not in known and not name.endswith((".yaml", ".yml")):
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: unknown printer preset; "
                                "known: " + ", ".join(known)))
        elif isinstance(name, str) and name in listed[:i]:
            # its points would be the same points: computed once, their rows once
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: repeats "
                                f"{dotted(('printers', listed.index(name)))}; list each printer once"))


def _check_profile_files(doc: LocatedYaml, design, printers, issues: list[Issue]) -> None:
    """The design profile and the printers given as files can be read as profiles of their
    kind: said at their line of the sweep file (a profile's own problems at its own lines),
    before any point is listed. Printers given by name are :func:`_check_printers`'."""
    from wheelstep_cli.config.profiles import load_design_profile, load_printer_profile

    named = [(("design",), design, load_design_profile)] if isinstance(design, str) else []
    named += [(("printers", i), name, load_printer_profile)
              for i, name in enumerate(printers if isinstance(printers, list) else [])
              if isinstance(name, str) and name.endswith((".yaml", ".yml"))]
    for at, name, load in named:
        try:
            load(name)
        except InvalidInput as err:
            issues.extend(err.issues)
        except DesignError as err:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: {err.limit}"))


def _check_bands(doc: LocatedYaml, command, names, tolerance: bool, issues: list[Issue]) -> None:
    """The printers' bands, each profile read once: ``tolerance: true`` is for gear pairs, on
    printers that have a band (none given: the default printer's); and a gear sweep's
    printers name no fit (a sweep does not search each point's fit, a fit costs dozens of
    meshing checks, so its rows would not be the pairs `gears` writes for that printer)."""
    from wheelstep_cli.config.printers import DEFAULT_PRINTER
    from wheelstep_cli.config.profiles import load_printer_profile

    if command != "gears":
        if tolerance:
            issues.append(Issue(doc.where(("tolerance",)), "tolerance", "= true: the band check "
                                                                        "is of gear pairs (command: gears)"))
        return
    given = names if isinstance(names, list) and names else []
    for i, name in enumerate(given or ([DEFAULT_PRINTER] if tolerance else [])):
        try:
            band = load_printer_profile(name).band if isinstance(name, str) else True
        except (DesignError, InvalidInput):   # an unknown or bad printer: _check_printers says it
            continue
        at = ("printers", i) if given else ("tolerance",)
        if tolerance and band is None:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: has no dimensional "
                                "band for tolerance: true; add a `band:` section to its profile"))
        if given and getattr(band, "fit", None) is not None:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: its band names fit: "
                                f"{band.fit}, which a sweep does not search for each design; "
                                "sweep on a copy of the profile without `fit:`, then fit the designs "
                                f"you keep with `wheelstep gears --printer {name}`"))


def _point_key(value) -> tuple:
    """A key equal for two axis values that make the same point (8 and 8.0; not True and 1);
    a value that cannot be a key (a list, a mapping) by its text."""
    try:
        hash(value)
    except TypeError:
        return ("text", repr(value))
    return (type(value) is bool, value)


def _range_count(axis: Range) -> float:
    """How many values a range holds (0 when stop is before start; inf when too many to count,
    a step of 1e-320 or a span of 1e308 overflowing)."""
    steps = (axis.stop - axis.start) / axis.step
    return max(math.floor(steps + 1e-9) + 1, 0) if math.isfinite(steps) else math.inf


def _count_text(count: float) -> str:
    return str(count) if math.isfinite(count) else "too many"


def _axis_values(axis: list | Range) -> list:
    """The values of a grid axis; a range's computed without float drift."""
    if isinstance(axis, list):
        return list(axis)
    count = _range_count(axis)
    whole = all(isinstance(v, int) for v in (axis.start, axis.stop, axis.step))
    values = [axis.start + i * axis.step for i in range(count)]
    return values if whole else [round(v, 12) for v in values]


def _points(sweep: SweepFile, grid: dict, random: RandomAxes | None) -> list[tuple[str | None, dict]]:
    """Every (printer, values) point: printers x grid product x random draws."""
    import numpy as np

    grid = [[(k, v) for v in _axis_values(axis)] for k, axis in grid.items()]
    combos = [dict(c) for c in itertools.product(*grid)]
    draws: list[dict] = [{}]
    if random is not None:
        rng = np.random.default_rng(random.seed)
        # each draw a new point: whole-number bounds repeat values (one row where two were asked for)
        draws, seen = [], set()
        while len(draws) < random.samples:
            draw = {k: _draw(rng, b) for k, b in random.bounds.items()}
            if (same := tuple(_point_key(v) for v in draw.values())) not in seen:
                seen.add(same)
                draws.append(draw)
    printers = sweep.printers or [None]
    return [(printer, {**sweep.fixed, **combo, **draw})
            for printer in printers for combo in combos for draw in draws]


def _distinct_draws(random: RandomAxes) -> int:
    """How many different points the random bounds hold: whole numbers, or decimals kept to
    the 9 decimals a draw is rounded to (low = high: one)."""
    return math.prod(b.high - b.low + 1 if isinstance(b.low, int) and isinstance(b.high, int)
                     else math.floor(round((b.high - b.low) * 1e9, 6)) + 1 for b in random.bounds.values())


def _draw(rng, bounds: Bounds):
    """One uniform value in the bounds: a whole number if both bounds are whole numbers."""
    if isinstance(bounds.low, int) and isinstance(bounds.high, int):
        return int(rng.integers(bounds.low, bounds.high + 1))
    return round(float(rng.uniform(bounds.low, bounds.high)), 9)
