"""The plan of a batch: the file and every profile it names read and checked before anything
is built, every problem reported at once as ``file:line``."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import ValidationError

from wheelstep_cli.batch.entry_problems import design_line, entry_problem, key_of, line_of
from wheelstep_cli.batch.lookup import Profiles, profile_label
from wheelstep_cli.config.batch_file import DEFAULT_DESIGN, KIND_NAMES, BatchDefaults, BatchEntry, BatchFile
from wheelstep_cli.config.located_yaml import LocatedYaml, YamlSyntaxError, read_located_yaml
from wheelstep_cli.config.printers import Printer
from wheelstep_cli.config.profiles import beside, profile_names
from wheelstep_cli.config.resolve import spec_problems, spec_values
from wheelstep_cli.config.schema import InvalidInput, Issue, dotted, located_issues, section_model, show, yaml_issues
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.kinds import KINDS, PartKind, as_designed, printed_spec


@dataclass(frozen=True)
class Entry:
    """One checked batch entry: a kind built from a design preset with overrides, for a printer."""

    index: int
    name: str
    kind: str
    design: str
    quantity: int
    printer: Printer
    overrides: dict[str, Any]
    spec: Any            # the design as given (kind's spec model)
    printed: Any         # the same, compensated for the printer
    where: str           # batch-file:line of the entry
    override_where: dict[str, str] = field(default_factory=dict)
    allow_interference: bool = False   # build a gear pair even if its teeth interfere

    @property
    def design_label(self) -> str:
        """The design preset's name for reports (a file path is shown by its file name only)."""
        return profile_label(self.design)

    def locate(self, param: str) -> str:
        """file:line of the override named by an error's ``param``, else of the entry."""
        return self.override_where.get(param.replace("-", "_"), self.where)


@dataclass(frozen=True)
class BatchPlan:
    file: Path
    label: str
    sha256: str
    description: str
    entries: list[Entry]
    designs: dict[str, tuple[str, str]]   # profile name -> (file name, sha256)


@dataclass
class _Check:
    """What checking the entries of one file shares."""

    doc: LocatedYaml
    profiles: Profiles
    defaults: BatchDefaults
    bad: set = field(default_factory=set)                 # paths (3 keys at most) with problems
    # entry name (case folded) -> where first used, that name, and whether the file gave it
    names: dict[str, tuple[str, str, bool]] = field(default_factory=dict)

    def flawed(self, path: tuple, key: str) -> bool:
        """Whether ``key`` was given at ``path`` or in the defaults with a problem (reported)."""
        return (path + (key,))[:3] in self.bad or ("defaults", key) in self.bad


def load_batch(path: Path, label: str | None = None) -> BatchPlan:
    """Read and check a batch file and every profile it names; raise InvalidInput listing all issues."""
    label = label or str(path)
    try:
        doc = read_located_yaml(path, label)
    except YamlSyntaxError as err:
        raise InvalidInput(yaml_issues(err)) from None
    found = _structure(doc)
    issues = [issue for loc, issue in found if _entry_index(loc) is None]
    bad = {loc[:3] for loc, _ in found}
    check = _Check(doc, Profiles(path), BatchDefaults(**_clean(doc, ("defaults",), BatchDefaults, bad)), bad)
    raw_parts = doc.data.get("parts") if isinstance(doc.data, dict) else None
    entries, used = [], {}
    for index, raw in enumerate(raw_parts if isinstance(raw_parts, list) else []):
        issues.extend(issue for loc, issue in found if _entry_index(loc) == index)
        if not isinstance(raw, dict):
            continue
        entry = BatchEntry(**_clean(doc, ("parts", index), BatchEntry, bad))
        checked = _check_entry(check, index, entry, issues)
        if checked is not None:
            entries.append(checked)
            used[checked.design_label] = check.profiles.design(doc, (), checked.design, [])[1:]
    if issues:
        raise InvalidInput(issues)
    return BatchPlan(Path(path), label, hashlib.sha256(Path(path).read_bytes()).hexdigest(),
                     str(doc.data.get("description") or ""), entries, used)


def _structure(doc: LocatedYaml) -> list[tuple[tuple, Issue]]:
    """(path, issue) of every problem the batch file's model finds."""
    try:
        BatchFile.model_validate({} if doc.data is None else doc.data)
    except ValidationError as err:
        return located_issues(BatchFile, doc, (), err)
    return []


def _entry_index(loc: tuple) -> int | None:
    return loc[1] if len(loc) >= 2 and loc[0] == "parts" and isinstance(loc[1], int) else None


def _clean(doc: LocatedYaml, path: tuple, model, bad: set) -> dict:
    """The values at ``path`` the model found no problem with."""
    value = doc.data
    for key in path:
        # a file whose top level is a list (or a key where an index is) holds no such values
        if isinstance(value, dict):
            value = value.get(key)
        else:
            in_list = isinstance(value, list) and isinstance(key, int) and 0 <= key < len(value)
            value = value[key] if in_list else None
    if not isinstance(value, dict):
        return {}
    return {k: v for k, v in value.items() if k in model.model_fields and (path + (k,))[:3] not in bad}


def _check_entry(check: _Check, index: int, entry: BatchEntry, issues: list[Issue]) -> Entry | None:
    """Check one entry of ``parts`` (with the defaults); returns an Entry or None (issues appended)."""
    doc, path, before = check.doc, ("parts", index), len(issues)

    def given(key):  # the entry's value, else the default's, and where it was written
        own = getattr(entry, key)
        return (own, path + (key,)) if own is not None else (getattr(check.defaults, key), ("defaults", key))

    kind = None if check.flawed(path, "kind") else _kind(doc, path, *given("kind"), issues)
    name = _name(check, path, index, entry, given("kind")[0], issues)
    quantity = given("quantity")[0] or 1
    printer_name, printer_at = given("printer")
    printer = None
    if check.flawed(path, "printer"):
        pass
    elif printer_name is None:
        issues.append(Issue(doc.where(path), dotted(path), "needs a printer: a printer profile, one of "
                            + ", ".join(profile_names(printer=True))))
    else:
        printer = check.profiles.printer(doc, printer_at, printer_name, issues)
    design_name, design_at = given("design")
    design_name = design_name or DEFAULT_DESIGN
    design = None if check.flawed(path, "design") else check.profiles.design(doc, design_at, design_name, issues)
    overrides = dict(entry.overrides or {})
    if isinstance(overrides.get("law_csv"), str):
        # an entry's law CSV beside the batch file first, as its profiles are
        overrides["law_csv"] = beside(check.profiles.folder, overrides["law_csv"])
    override_where: dict[str, str] = {}
    faulty: set[str] = set()
    if kind is not None:
        override_where, faulty = _check_overrides(doc, path, kind, overrides, issues)
    allow = _allow_interference(doc, path, kind, entry, issues)
    flawed = any(loc[:2] == path for loc in check.bad)
    # overrides a field rule refused stop nothing: the rules of the others are checked below,
    # as they are beside the entry's other problems (its name, quantity, a key of its own)
    others = [issue for issue in issues[before:] if not issue.what.startswith(dotted(path + ("overrides",)))]
    if kind is None or printer is None or design is None:
        return None
    # the overrides a field rule refused are left out, so the rules of the others (the
    # mechanism's, the kind's) are found in the same run
    kept = {key: value for key, value in overrides.items() if key not in faulty}
    spec, printed, problems = _every_problem(kind, design[0], kept, printer, frozenset(faulty))
    where = {key: line for key, line in override_where.items() if key in kept}
    written = {key: (entry.overrides or {}).get(key, value) for key, value in kept.items()}   # as the file has them
    for err in problems:
        issues.append(entry_problem(doc, path, err, where, design_line(design[0], kind, design_name, err), written))
    if problems or faulty or others or flawed:
        issues[before:] = sorted(issues[before:], key=lambda issue: line_of(issue.where))  # in file order
        return None
    return Entry(index, name, kind.name, design_name, quantity, printer, overrides, spec, printed,
                 doc.where(path), override_where, allow)


def _allow_interference(doc, path, kind: PartKind | None, entry: BatchEntry, issues: list[Issue]) -> bool:
    """The entry's ``allow_interference`` (gear pairs only: other kinds have no teeth to mesh)."""
    if entry.allow_interference and kind is not None and kind.mating_check is None:
        at = path + ("allow_interference",)
        issues.append(Issue(doc.where(at), dotted(at), f"= true: only gear-pair entries have teeth to check, not {kind.name}"))
    return bool(entry.allow_interference)


def _kind(doc: LocatedYaml, path: tuple, name, at: tuple, issues: list[Issue]) -> PartKind | None:
    if name is None:
        issues.append(Issue(doc.where(path), dotted(path), "needs a kind: " + ", ".join(KIND_NAMES)))
        return None
    try:
        KINDS[name].pipeline()
    except DesignError as err:
        issues.append(Issue(doc.where(at), dotted(at), str(err.limit)))
        return None
    return KINDS[name]


def _name(check: _Check, path: tuple, index: int, entry: BatchEntry, kind_name, issues) -> str:
    """The entry's name (given, or KIND-N), which no other entry may use."""
    doc = check.doc
    name = entry.name or f"{kind_name}-{index + 1}"
    at = path + ("name",)
    # names its report file: two names one case apart are one file on Windows and macOS
    if name.casefold() in check.names:
        where, earlier, given = check.names[name.casefold()]
        there = where
        if earlier != name:
            there += f" as {show(earlier)} (names are compared ignoring case: they name report files)"
        if not given:
            there += ", the name that entry without one gets (KIND-N: its kind and place)"
        if entry.name:
            issues.append(Issue(doc.where(at), dotted(at), f"= {show(name)}: already used at {there}"))
        else:
            issues.append(Issue(doc.where(path), dotted(path), f"has no name, and {show(name)}, the one it "
                                f"would get, is already used at {there}; give it a `name:`"))
    else:
        check.names[name.casefold()] = (doc.where(path), name, bool(entry.name))
    return name


def _check_overrides(doc, path, kind: PartKind, overrides: dict, issues: list[Issue]
                     ) -> tuple[dict[str, str], set[str]]:
    """Check the overrides against the kind's spec fields; returns the line of each of its
    keys and the keys found at fault (one issue each, appended)."""
    at = path + ("overrides",)
    model = section_model(kind.spec_type())
    faulty: set[str] = set()
    for key, value in overrides.items():
        if value is None and key in model.model_fields:
            # an empty override would do nothing while the manifest lists it as given
            issues.append(Issue(doc.where(at + (key,)), dotted(at + (key,)),
                                "= null: give a value, or leave the key out for the design's"))
            faulty.add(key)
    try:
        model.model_validate({key: value for key, value in overrides.items() if key not in faulty})
    except ValidationError as err:
        for loc, issue in located_issues(model, doc, at, err):
            issues.append(issue)
            faulty.add(loc[len(at)] if len(loc) > len(at) else None)
    return {key: doc.where(at + (key,)) for key in overrides if key in model.model_fields}, faulty


def _every_problem(kind: PartKind, design, overrides: dict, printer: Printer, dropped: frozenset = frozenset()):
    """:func:`_resolve`, with every override at fault: a rule stops at the first input it
    finds at fault, so the entry is checked again without the overrides found so far (their
    design's values instead) while that finds another override at fault, and the user
    fixes them in one go. ``dropped``: overrides already left out (found at fault by a field
    rule), whose stand-in values are not blamed either."""
    spec, printed, problems = _resolve(kind, design, overrides, printer)
    problems = [err for err in problems if not ({key_of(err), *map(key_of, err.alternatives)} & dropped)]
    left = dict(overrides)
    found = list(problems)
    while problems and len(found) < len(overrides):
        blamed = {key_of(err.for_given(left)) for err in problems}
        if not blamed <= set(left):
            break           # a problem of no override's: the others may stem from it
        left = {key: value for key, value in left.items() if key not in blamed}
        removed = dropped | (set(overrides) - set(left))
        # only a rule none of the removed overrides takes part in: the design's values standing
        # in for them must not be blamed on the user's other keys
        problems = [DesignError(given.param, given.value, given.limit)
                    for err in _resolve(kind, design, left, printer)[2]
                    if not ({key_of(err), *map(key_of, err.alternatives)} & removed)
                    and key_of(given := err.for_given(left)) in left]
        found += problems
    found = _with_the_designs(kind, design, overrides, printer, found)
    # in the order the file gives the overrides, an entry's own problems first
    order = {key: k for k, key in enumerate(overrides)}
    found.sort(key=lambda err: order.get(key_of(err.for_given(overrides)), -1))
    return spec, printed, found


def _with_the_designs(kind: PartKind, design, overrides: dict, printer: Printer,
                      found: list[DesignError]) -> list[DesignError]:
    """``found`` and, when those are all the design profile's, its further rule problems in
    its lines' order: its keys found at fault are left out, their defaults standing in, and
    the entry is resolved again while that finds another of the design's keys at fault (as
    for overrides, and as `gears --profile` does). A problem the stand-in defaults take part
    in is not said, its key left out unsaid; one of an override's ends the search."""
    from wheelstep_cli.config.problem_search import WithoutKeys

    sections = (kind.section, "mechanism")
    design_keys = [key for part in sections for key in design.values(part)]
    left: set[str] = set()
    every, latest = list(found), list(found)
    while latest:
        seen = WithoutKeys(design, left)
        for err in latest:
            named = key_of(err.for_given([key for part in sections for key in seen.values(part)]))
            part = next((p for p in sections if named in seen.values(p)), None)
            if key_of(err.for_given(overrides)) in overrides or part is None:
                # an override's, or one of no key the design still gives: it may stem from them
                return found if every == found else _in_design_order(design, sections, design_keys, every)
            left.add(f"{part}.{named}")     # a key the design still gives: the search ends
        latest = _resolve(kind, WithoutKeys(design, left), overrides, printer)[2]
        every += [err for err in latest if not any(f"{part}.{name}" in left for part in sections
                                                   for name in {key_of(err), *map(key_of, err.alternatives)})]
    return _in_design_order(design, sections, design_keys, every)


def _in_design_order(design, sections, design_keys, errors: list[DesignError]) -> list[DesignError]:
    """``errors`` of the design's keys by their lines in its file."""
    def line(err) -> int:
        named = key_of(err.for_given(design_keys))
        return line_of(next((design.where(p, named) for p in sections if named in design.values(p)), None))
    return sorted(errors, key=line)


def _resolve(kind: PartKind, design, overrides: dict, printer: Printer):
    """(spec, printed spec, problems): overrides over the kind's profile section over the
    mechanism section, checked by the spec's model and the kind's domain checks."""
    spec_type = kind.spec_type()
    try:
        values = spec_values(spec_type, kind.section, design, overrides, on_command_line=False)
        spec, problems = spec_problems(spec_type, values)
        if spec is None or problems:
            return None, None, problems
        problems = kind.problems(spec)
        if problems:
            return None, None, _as_printed(kind, spec, printer, problems)
        printed = printed_spec(kind, spec, printer)
        problems = [as_designed(err, spec, printed, printed_beside=False) for err in kind.problems(printed)]
        if not problems:
            _require_height(kind, printed, printer)
    except DesignError as err:
        return None, None, [err]
    return (None, None, problems) if problems else (spec, printed, [])


def _as_printed(kind: PartKind, spec, printer: Printer, problems: list[DesignError]) -> list[DesignError]:
    """``problems`` of ``spec`` with each one the printer-compensated spec also has said with
    the printed limit (a hole drawn larger needs more round it: that limit is the one to meet),
    in the values the user gave."""
    try:
        printed = printed_spec(kind, spec, printer)
    except DesignError:
        return problems
    bound = {err.param: as_designed(err, spec, printed, printed_beside=False) for err in kind.problems(printed)}
    return [bound.get(err.param, err) for err in problems]


def _require_height(kind: PartKind, printed, printer: Printer) -> None:
    """A part taller than its printer prints, refused before it is built (as the plate would
    refuse it after): a gear pair stands on its face, a shoe on its side (its width upright)."""
    from wheelstep_cli.parts.gear_pair import footprint
    from wheelstep_cli.parts.kinds import height_inputs
    from wheelstep_cli.parts.plate_layout import gear_pair_height, gear_pair_stack, require_height

    if kind.name == "gear-pair":
        require_height("pinion", gear_pair_height(printed), printer, "thickness", printed.thickness,
                       footprint(printed), gear_pair_stack(printed), lowers=height_inputs(kind.name, printed))
    elif kind.name == "shoe":
        # as the mesh's float32 vertices hold it (the plate's check sees that)
        require_height("shoe", float(np.float32(printed.width)), printer, "width", printed.width,
                       lowers=height_inputs(kind.name, printed))
