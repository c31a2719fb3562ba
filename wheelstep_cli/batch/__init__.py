"""Batch builds for the print shop: a YAML list of parts -> plates, a manifest and a print sheet.

Stages: :func:`load_batch` reads and checks the whole file (and the profiles it names)
before anything is built, every problem reported as ``file:line``; :func:`run_batch`
builds the entries in parallel worker processes (one failing entry does not stop the
others), packs every part times its quantity onto the beds of its printer, renders the
plates (3MF + PNG) and writes everything in one atomic step.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from wheelstep_cli.errors import DesignError
from wheelstep_cli.config.located_yaml import LocatedYaml, read_located_yaml
from wheelstep_cli.config.printers import Printer, is_printer_profile, printer_from_profile
from wheelstep_cli.config.schema import InvalidInput, Issue, check_mapping, dotted, show, type_problem
from wheelstep_cli.parts.kinds import KINDS, PartKind, printed_spec

TOP_KEYS = ("description", "defaults", "parts")
ENTRY_KEYS = ("name", "kind", "design", "overrides", "quantity", "printer")
DEFAULT_KEYS = ("kind", "design", "printer", "quantity")
MAX_QUANTITY = 200
NAME_PATTERN = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")
MECHANISM_KEYS = ("a", "b", "c", "r_min")
MANIFEST = "manifest.json"


# ----------------------------------------------------------------------------- the plan
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
    spec: Any            # the design as given (kind's Spec dataclass)
    printed: Any         # the same, compensated for the printer
    where: str           # batch-file:line of the entry
    override_where: dict[str, str] = field(default_factory=dict)

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


def load_batch(path: Path, label: str | None = None) -> BatchPlan:
    """Read and check a batch file and every profile it names; raise InvalidInput listing all issues."""
    from wheelstep_cli.config.located_yaml import YamlSyntaxError
    from wheelstep_cli.config.profiles import find_profile as find_named_profile

    def find_profile(name: str) -> Path:  # a profile given as a relative .yaml path: next to the batch file
        given = Path(name)
        nearby = Path(path).parent / given
        if given.suffix in (".yaml", ".yml") and not given.is_absolute() and nearby.is_file():
            return nearby
        return find_named_profile(name)

    label = label or str(path)
    try:
        doc = read_located_yaml(path, label)
    except YamlSyntaxError as err:
        raise InvalidInput([Issue(err.where, "", err.limit)]) from None
    issues: list[Issue] = []
    top = check_mapping(doc, (), doc.data, TOP_KEYS, issues, required=("parts",))
    defaults = check_mapping(doc, ("defaults",), top.get("defaults"), DEFAULT_KEYS, issues)
    parts = top.get("parts")
    if "parts" in top and (not isinstance(parts, list) or not parts):
        issues.append(Issue(doc.where(("parts",)), "parts", "must be a list of at least one part"))
        parts = []
    printers: dict[str, Printer | None] = {}
    designs: dict[str, tuple[LocatedYaml, str] | None] = {}
    entries: list[Entry] = []
    names: dict[str, str] = {}
    for index, raw in enumerate(parts or []):
        entry = _check_entry(doc, index, raw, defaults, printers, designs, names, issues, find_profile)
        if entry is not None:
            entries.append(entry)
    if issues:
        raise InvalidInput(issues)
    used = {}
    for entry in entries:
        located, sha = designs[entry.design]
        used[entry.design_label] = (Path(located.file).name, sha)
    return BatchPlan(Path(path), label, hashlib.sha256(Path(path).read_bytes()).hexdigest(),
                     str(top.get("description", "")), entries, used)


def _check_entry(doc, index, raw, defaults, printers, designs, names, issues, find_profile):
    """Check one entry of ``parts``; returns an Entry or None (issues appended)."""
    path = ("parts", index)
    before = len(issues)
    raw = check_mapping(doc, path, raw, ENTRY_KEYS, issues)
    values = {**defaults, **raw}

    def origin(key):  # where a value came from: the entry itself or the defaults section
        return path + (key,) if key in raw else ("defaults", key)

    kind_name = values.get("kind")
    kind: PartKind | None = None
    if kind_name is None:
        issues.append(Issue(doc.where(path), dotted(path), "needs a kind: " + ", ".join(KINDS)))
    elif kind_name not in KINDS:
        issues.append(Issue(doc.where(origin("kind")), dotted(origin("kind")),
                            f"= {show(kind_name)}: unknown kind; allowed: {', '.join(KINDS)}"))
    else:
        kind = KINDS[kind_name]
        try:
            kind.pipeline()
        except DesignError as err:
            issues.append(Issue(doc.where(origin("kind")), dotted(origin("kind")), str(err.limit)))
            kind = None

    name = values.get("name", f"{kind_name}-{index + 1}")
    if not isinstance(name, str) or not NAME_PATTERN.match(name):
        issues.append(Issue(doc.where(origin("name")), dotted(origin("name")),
                            f"= {show(name)}: must be letters, digits, '.', '_' or '-'"))
    elif name in names:
        issues.append(Issue(doc.where(origin("name")), dotted(origin("name")),
                            f"= {show(name)}: already used at {names[name]}"))
    else:
        names[name] = doc.where(path)

    quantity = values.get("quantity", 1)
    if isinstance(quantity, bool) or not isinstance(quantity, int):
        issues.append(Issue(doc.where(origin("quantity")), dotted(origin("quantity")),
                            f"= {show(quantity)}: must be a whole number"))
    elif not 1 <= quantity <= MAX_QUANTITY:
        issues.append(Issue(doc.where(origin("quantity")), dotted(origin("quantity")),
                            f"= {quantity}: must be between 1 and {MAX_QUANTITY}"))

    printer = None
    if values.get("printer") is None:
        issues.append(Issue(doc.where(path), dotted(path), "needs a printer: a printer profile, one of "
                            + ", ".join(_profile_names(printer=True))))
    else:
        printer = _printer(doc, origin("printer"), values["printer"], printers, issues, find_profile)
    design_name = values.get("design", "bntu-2024")
    design = _design(doc, origin("design"), design_name, designs, issues, find_profile)

    overrides = raw.get("overrides") or {}
    spec = printed = None
    override_where: dict[str, str] = {}
    if kind is not None:
        keys = kind.spec_keys()
        overrides = check_mapping(doc, path + ("overrides",), raw.get("overrides"), keys, issues)
        types = kind.field_types()
        for key, value in overrides.items():
            if key in types:
                override_where[key] = doc.where(path + ("overrides", key))
                problem = type_problem(value, types[key])
                if problem:
                    issues.append(Issue(override_where[key], dotted(path + ("overrides", key)),
                                        f"= {show(value)}: {problem}"))
        layers = _design_layers(kind, design, issues) if design is not None else None
        if len(issues) == before and layers is not None and printer is not None:
            spec, printed = _resolve_spec(doc, path, kind, design_name, layers, overrides,
                                          override_where, printer, issues)
    if len(issues) > before:
        return None
    return Entry(index, name, kind.name, design_name, quantity, printer, dict(overrides), spec, printed,
                 doc.where(path), override_where)


def _lookup_profile(doc, path, name, cache, issues, find_profile, load):
    """A profile named at ``path`` of the batch, read once per name: ``load(name, file, located)``
    turns it into the cached value; problems become issues (None is cached then)."""
    if not isinstance(name, str):
        issues.append(Issue(doc.where(path), dotted(path), f"= {show(name)}: must be a profile name"))
        return None
    if name not in cache:
        cache[name] = None
        try:
            file = find_profile(name)
            cache[name] = load(name, file, read_located_yaml(file, _label(file)))
        except InvalidInput as err:
            issues.extend(err.issues)
        except DesignError as err:
            if err.param == "yaml":
                issues.append(Issue(str(err.value), "", err.limit))
            else:
                issues.append(Issue(doc.where(path), dotted(path), f"= {show(name)}: {err.limit}"))
    return cache[name]


def _load_printer(name: str, file: Path, located: LocatedYaml) -> Printer:
    if not is_printer_profile(located.data):
        raise DesignError("printer", name, "is a design profile, not a printer profile; "
                          "printer profiles: " + ", ".join(_profile_names(printer=True)))
    return printer_from_profile(profile_label(name), file, _label(file), located)


def _load_design(name: str, file: Path, located: LocatedYaml) -> tuple[LocatedYaml, str]:
    if is_printer_profile(located.data) or not isinstance(located.data, dict):
        raise DesignError("design", name, "is not a design profile; design profiles: "
                          + ", ".join(_profile_names(printer=False)))
    return located, hashlib.sha256(file.read_bytes()).hexdigest()


def _printer(doc, path, name, cache, issues, find_profile) -> Printer | None:
    printer = _lookup_profile(doc, path, name, cache, issues, find_profile, _load_printer)
    if printer is None and not any(i.where == doc.where(path) for i in issues):
        issues.append(Issue(doc.where(path), dotted(path), f"= {show(name)}: the printer profile has errors (above)"))
    return printer


def _design(doc, path, name, cache, issues, find_profile) -> LocatedYaml | None:
    found = _lookup_profile(doc, path, name, cache, issues, find_profile, _load_design)
    return None if found is None else found[0]


def _design_layers(kind: PartKind, design: LocatedYaml, issues: list[Issue]):
    """(mechanism values, kind-section values) from a design profile, checked."""
    before = len(issues)
    data = design.data
    types = kind.field_types()
    mechanism = check_mapping(design, ("mechanism",), data.get("mechanism"), MECHANISM_KEYS, issues)
    section = check_mapping(design, (kind.section,), data.get(kind.section), types, issues)
    for where, values in ((("mechanism",), mechanism), ((kind.section,), section)):
        for key, value in values.items():
            expected = types.get(key, float)
            problem = type_problem(value, expected)
            if problem:
                issues.append(Issue(design.where(where + (key,)), dotted(where + (key,)),
                                    f"= {show(value)}: {problem}"))
    if len(issues) > before:
        return None
    return mechanism, section


def _resolve_spec(doc, path, kind, design_name, layers, overrides, override_where, printer, issues):
    """Design values: overrides over the kind's profile section over the mechanism section."""
    mechanism, section = layers
    keys = kind.spec_keys()
    merged = {k: v for k, v in mechanism.items() if k in keys}
    merged.update(section)
    merged.update(overrides)
    spec_type = kind.spec_type()
    if ("r_min" in mechanism and "r_min" not in keys and "c" in keys and "c" not in mechanism
            and "c" not in section and "c" not in overrides):
        defaults = spec_type()
        a, b = merged.get("a", getattr(defaults, "a")), merged.get("b", getattr(defaults, "b"))
        merged["c"] = mechanism["r_min"] - a + 4 * b
    where = doc.where(path)
    try:
        spec = spec_type(**merged)
        kind.precheck(spec)
        printed = printed_spec(kind, spec, printer.hole_compensation, printer.tooth_clearance)
        kind.precheck(printed)
    except DesignError as err:
        err = err.for_given(override_where)
        param = err.param.replace("-", "_")
        if param in override_where:
            issues.append(Issue(override_where[param], dotted(path + ("overrides", param)),
                                f"= {show(err.value)}: {err.limit}"))
        else:
            given = f", with overrides {', '.join(overrides)}" if overrides else ""
            issues.append(Issue(where, dotted(path), f"{err} (from design {design_name}{given})"))
        return None, None
    return spec, printed


def profile_label(name: str) -> str:
    """A profile's name as recorded in outputs: bare names as they are, paths by file name only
    (so no folder, e.g. a temporary one, ends up in the manifest or the 3MF metadata)."""
    given = Path(name)
    return given.name if given.suffix in (".yaml", ".yml") or len(given.parts) > 1 else name


def _label(file: Path) -> str:
    """A profile's path as shown in messages: relative to the working folder when inside it."""
    try:
        return str(file.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(file)


def _profile_names(printer: bool) -> list[str]:
    from wheelstep_cli.config.profiles import profile_dirs

    import yaml

    names = set()
    for folder in profile_dirs():
        for file in folder.glob("*.yaml") if folder.is_dir() else []:
            try:
                data = yaml.safe_load(file.read_text(encoding="utf-8"))
            except yaml.YAMLError:
                continue
            if is_printer_profile(data) == printer:
                names.add(file.stem)
    return sorted(names)


# ----------------------------------------------------------------------------- building
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
        return EntryResult(entry.index, error=str(err), param=err.param)
    except Exception as err:  # an unexpected failure must not stop the other entries
        return EntryResult(entry.index, error=f"internal error: {type(err).__name__}: {err}")


# ----------------------------------------------------------------------------- plates
@dataclass
class PlacedPart:
    label: str
    entry: str
    part: BuiltPart
    x: float          # translation on the bed, mm
    y: float
    rotated: bool
    metadata: dict[str, str]

    def vertices(self) -> np.ndarray:
        v = self.part.vertices
        return np.column_stack([-v[:, 1], v[:, 0], v[:, 2]]) if self.rotated else v

    def footprint(self) -> list[list[np.ndarray]]:
        turn = (lambda r: np.column_stack([-r[:, 1], r[:, 0]])) if self.rotated else (lambda r: r)
        return [[turn(r) + (self.x, self.y) for r in polygon] for polygon in self.part.footprint]


@dataclass
class Plate:
    number: int
    printer: Printer
    items: list[PlacedPart]

    @property
    def stem(self) -> str:
        return f"plate-{self.number}"


def plate_threemf(plate: Plate) -> tuple[int, bytes]:
    """(plate number, 3MF bytes) of a packed plate (worker-process entry point)."""
    from wheelstep_cli.formats.threemf import PlateObject, threemf_bytes

    objects = []
    for item in plate.items:
        vertices = item.vertices()
        lo = vertices.min(axis=0)
        objects.append(PlateObject(item.label, vertices, item.part.faces,
                                   (item.x - lo[0], item.y - lo[1], -lo[2]), item.metadata))
    printer = plate.printer
    return plate.number, threemf_bytes(objects, {
        "Title": f"wheelstep {plate.stem} ({printer.name})", "Application": "wheelstep batch",
        "printer": printer.name, "material": printer.material})


def plate_picture(plate: Plate) -> bytes:
    """Top-view PNG of a packed plate: the bed with the parts' footprints."""
    from wheelstep_cli.render.plate_png import plate_png

    shapes = []
    for item in plate.items:
        polygons = item.footprint()
        lo = np.min([r.min(axis=0) for p in polygons for r in p], axis=0)
        label = item.label.replace(" ", "\n", 1)  # entry name over part name
        shapes.append((label, [[r - lo + (item.x, item.y) for r in p] for p in polygons]))
    printer = plate.printer
    return plate_png(printer.bed, printer.margin, shapes,
                     f"{plate.stem}: {printer.name} ({printer.bed[0]:g} x {printer.bed[1]:g} mm), "
                     f"{len(plate.items)} parts")


def _metadata(entry: Entry, part: str, copy: int) -> dict[str, str]:
    """3MF metadata of one placed part: where it comes from and its design parameters."""
    meta = {"entry": entry.name, "kind": entry.kind, "part": part, "copy": f"{copy} of {entry.quantity}",
            "design_profile": entry.design_label, "printer_profile": entry.printer.name}
    for name, value in dataclasses.asdict(entry.printed).items():
        if value is not None:
            meta[f"design.{name}"] = f"{value:g}" if isinstance(value, float) else str(value)
    for name, value in entry.printer.geometry().items():
        meta[f"printer.{name}"] = f"{value:g}"
    return meta


def plan_plates(entries: list[Entry], results: dict[int, EntryResult]) -> tuple[list[Plate], dict[int, str]]:
    """Pack every built part times its quantity onto beds, per printer.

    Returns the plates (numbered across printers in order of first use) and, per entry
    index, the reason an entry had to be dropped (a part larger than the bed).
    """
    from wheelstep_cli.geometry.packing import fits_bed, pack_boxes

    dropped: dict[int, str] = {}
    for entry in entries:
        result = results[entry.index]
        if result.error:
            continue
        printer = entry.printer
        for part in result.parts:
            size = part.bounds[1, :2] - part.bounds[0, :2]
            if fits_bed(tuple(size), printer.bed, printer.margin) is None:
                dropped[entry.index] = (
                    f"part '{part.name}' ({size[0]:.1f} x {size[1]:.1f} mm) does not fit the bed of "
                    f"printer '{printer.name}' ({printer.bed[0]:g} x {printer.bed[1]:g} mm with "
                    f"{printer.margin:g} mm margins)")
                break
    plates: list[Plate] = []
    order = list(dict.fromkeys((e.printer.name, e.printer.sha256) for e in entries))
    for printer_key in order:
        items: list[tuple[Entry, BuiltPart, int]] = []
        for entry in entries:
            result = results[entry.index]
            if (entry.printer.name, entry.printer.sha256) != printer_key or result.error \
                    or entry.index in dropped:
                continue
            for copy in range(1, entry.quantity + 1):
                items.extend((entry, part, copy) for part in result.parts)
        if not items:
            continue
        printer = items[0][0].printer
        sizes = [tuple(p.bounds[1, :2] - p.bounds[0, :2]) for _, p, _ in items]
        placements = pack_boxes(sizes, printer.bed, printer.margin)
        beds: dict[int, list[PlacedPart]] = {}
        for (entry, part, copy), spot in zip(items, placements):
            label = f"{entry.name} {part.name}" + (f" #{copy}" if entry.quantity > 1 else "")
            beds.setdefault(spot.bed, []).append(PlacedPart(
                label, entry.name, part, spot.x, spot.y, spot.rotated, _metadata(entry, part.name, copy)))
        for bed in sorted(beds):
            plates.append(Plate(len(plates) + 1, printer, beds[bed]))
    return plates, dropped


# ----------------------------------------------------------------------------- running
@dataclass
class BatchOutcome:
    written: list[Path]
    plates: list[Plate]
    failed: list[tuple[Entry, str, str]]     # entry, where (file:line), reason
    built: list[Entry]


def run_batch(plan: BatchPlan, out: Path, jobs: int = 1,
              progress: Callable[[str, int], Any] | None = None) -> BatchOutcome:
    """Build, pack, render and write a checked batch; ``progress(stage, total)`` -> advance()."""
    from wheelstep_cli.formats.atomic import remove_files, write_files_atomic

    advance = progress or (lambda stage, total: (lambda: None))
    with _executor(jobs) as pool:
        step = advance("building parts", len(plan.entries))
        results: dict[int, EntryResult] = {}
        for result in _map(pool, build_entry, plan.entries, step):
            results[result.index] = result
        plates, dropped = plan_plates(plan.entries, results)
        step = advance("writing plates", 2 * len(plates))
        # 3MF files in the workers; meanwhile this (otherwise idle) process draws the pictures,
        # so matplotlib is imported once, as with --jobs 1
        threemfs = _map(pool, plate_threemf, plates, step, lazy=True)
        pictures = {}
        for plate in plates:
            pictures[plate.number] = plate_picture(plate)
            step()
        rendered = {number: (data, pictures[number]) for number, data in threemfs}

    failed, built = [], []
    for entry in plan.entries:
        result = results[entry.index]
        if result.error:
            failed.append((entry, entry.locate(result.param or ""), result.error))
        elif entry.index in dropped:
            failed.append((entry, entry.where, dropped[entry.index]))
        else:
            built.append(entry)
    files: dict[Path, bytes] = {}
    for plate in plates:
        threemf, png = rendered[plate.number]
        files[out / f"{plate.stem}.3mf"] = threemf
        files[out / f"{plate.stem}.png"] = png
    for entry in built:
        files[out / "reports" / f"{entry.name}.json"] = _entry_report_bytes(entry, results[entry.index])
    from wheelstep_cli.render.print_sheet import print_sheet_bytes

    files[out / "print-sheet.md"] = print_sheet_bytes(plan, plates, built, results, failed)
    files[out / MANIFEST] = _manifest_bytes(plan, out, files, plates, built, results, failed)
    stale = _previous_outputs(out) - {p.relative_to(out).as_posix() for p in files}
    written = write_files_atomic(files)
    remove_files(out / name for name in sorted(stale))
    return BatchOutcome(written, plates, failed, built)


class _Serial:
    """In-process stand-in for an executor (``--jobs 1``)."""

    def __enter__(self):
        return None

    def __exit__(self, *exc):
        return False


def _executor(jobs: int):
    if jobs <= 1:
        return _Serial()
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    # spawn: safe with manifold3d's threads and the same on every platform
    return ProcessPoolExecutor(max_workers=jobs, mp_context=multiprocessing.get_context("spawn"))


def _map(pool, function, items, step, lazy: bool = False):
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


def _previous_outputs(out: Path) -> set[str]:
    """Files listed by an earlier batch's manifest in ``out`` (so they can be replaced cleanly)."""
    try:
        data = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        names = set(data.get("outputs", {})) | {MANIFEST}
    except (OSError, ValueError, AttributeError):
        return set()
    return {n for n in names if isinstance(n, str) and ".." not in Path(n).parts and not Path(n).is_absolute()}


def part_summary(part: BuiltPart, printer: Printer) -> dict:
    """Volume, bounding box, mass estimates and checks of one built part."""
    from wheelstep_cli.render.print_sheet import estimated_mass

    lo, hi = part.bounds
    return {"volume_mm3": part.volume, "bounding_box_mm": [lo, hi], "size_mm": hi - lo,
            "triangles": part.triangles, "solid_mass_g": part.volume / 1000.0 * printer.density,
            "estimated_mass_g": estimated_mass(part, printer), "checks": part.checks}


def _entry_report_bytes(entry: Entry, result: EntryResult) -> bytes:
    from wheelstep_cli.formats.jsonio import json_bytes

    return json_bytes({
        "entry": entry.name, "kind": entry.kind, "design_profile": entry.design_label,
        "printer_profile": entry.printer.name, "quantity": entry.quantity,
        "parameters": dataclasses.asdict(entry.spec),
        "printed_parameters": dataclasses.asdict(entry.printed),
        "printer_geometry": entry.printer.geometry(),
        "printed_parts": {p.name: part_summary(p, entry.printer) for p in result.parts},
        "design_report": result.report,
    })


def tool_versions() -> dict[str, str]:
    """Versions of the tool, Python and the libraries that shape the output."""
    import platform
    from importlib import metadata

    from wheelstep_cli import __version__

    versions = {"wheelstep": __version__, "python": platform.python_version()}
    for dist in ("numpy", "scipy", "shapely", "manifold3d", "matplotlib", "PyYAML", "typer", "rich"):
        try:
            versions[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            versions[dist] = "not installed"
    return versions


def _manifest_bytes(plan, out, files, plates, built, results, failed) -> bytes:
    from wheelstep_cli.formats.jsonio import json_bytes

    printers = {}
    for entry in plan.entries:
        printers[entry.printer.name] = {"file": entry.printer.file_name, "sha256": entry.printer.sha256}
    checks_ok = all(all(p.checks.values()) for e in built for p in results[e.index].parts)
    return json_bytes({
        "tool": "wheelstep batch",
        "versions": tool_versions(),
        "inputs": {
            "batch": {"file": plan.file.name, "sha256": plan.sha256},
            "design_profiles": {n: {"file": f, "sha256": s} for n, (f, s) in sorted(plan.designs.items())},
            "printer_profiles": dict(sorted(printers.items())),
        },
        "entries": [
            {"name": e.name, "kind": e.kind, "design_profile": e.design_label, "printer_profile": e.printer.name,
             "quantity": e.quantity, "overrides": e.overrides, "line": int(e.where.rsplit(":", 1)[1]),
             "status": "built" if e in built else "failed",
             **({"parts": {p.name: {"volume_mm3": p.volume, "triangles": p.triangles, "checks": p.checks}
                           for p in results[e.index].parts}} if e in built else {})}
            for e in plan.entries],
        "failed": [{"name": e.name, "where": f"{plan.file.name}:{where.rsplit(':', 1)[1]}", "reason": reason}
                   for e, where, reason in failed],
        "plates": [{"file": f"{p.stem}.3mf", "picture": f"{p.stem}.png", "printer_profile": p.printer.name,
                    "parts": [i.label for i in p.items]} for p in plates],
        "checks": {"meshes_printable": checks_ok, "every_part_on_a_bed": not any(
            "does not fit" in reason for _, _, reason in failed),
            "validated_before_build": True},
        "outputs": {p.relative_to(out).as_posix(): hashlib.sha256(data).hexdigest()
                    for p, data in sorted(files.items(), key=lambda kv: kv[0].as_posix())},
    })
