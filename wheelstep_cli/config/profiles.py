"""YAML presets in ``profiles/``: designs (mechanism, gears, shoe) and printers.

A profile is looked up as a path, then as ``NAME.yaml`` in ``./profiles`` and among
the presets shipped with the package (``wheelstep_cli.profiles``, read with
importlib.resources, so they are there after a normal install too). A design profile is
checked by its model (:mod:`wheelstep_cli.config.design`); every problem of the file is
reported at once with its ``file:line``.
"""

from __future__ import annotations

import importlib.resources
from dataclasses import replace
from pathlib import Path
from typing import Any

from wheelstep_cli.config.located_yaml import LocatedYaml, YamlSyntaxError, read_located_yaml
from wheelstep_cli.config.printers import DEFAULT_PRINTER, printer_from_profile
from wheelstep_cli.config.schema import InvalidInput, Issue, yaml_issues
from wheelstep_cli.errors import DesignError


def shipped_profiles() -> Path:
    """Folder of the presets installed with the package: in a source checkout the
    ``profiles/`` folder beside the package (an editable install may map the package data to
    another checkout), else the installed package data."""
    source = Path(__file__).resolve().parents[2] / "profiles"
    if (source / "fdm-0.4-pla.yaml").is_file():
        return source
    return Path(str(importlib.resources.files("wheelstep_cli.profiles")))


def profile_dirs() -> list[Path]:
    """Folders searched for profiles by name, in order."""
    return [Path.cwd() / "profiles", shipped_profiles()]


def find_profile(name_or_path: str, printer: bool | None = None) -> Path:
    """Path of a profile given as a file path or a bare name; when not found, the message
    lists the known profiles of the kind asked for (``printer``: True printer profiles,
    False design profiles, None both)."""
    path = Path(name_or_path)
    if path.suffix in (".yaml", ".yml") and path.is_file():
        return path
    for folder in profile_dirs():
        for suffix in (".yaml", ".yml"):
            candidate = folder / f"{name_or_path}{suffix}"
            if candidate.is_file():
                return candidate
    if path.is_dir():
        raise DesignError("profile", name_or_path, "is a folder, not a profile file")
    if path.is_file():
        # a file by another name: the name decides what it is (a preset is looked up by it)
        raise DesignError("profile", name_or_path, "is not a profile file: a profile is a YAML "
                          "file named *.yaml or *.yml")
    if printer is None:
        known = sorted({p.stem for d in profile_dirs() if d.is_dir() for p in d.glob("*.yaml")})
        what = "profiles"
    else:
        known, what = profile_names(printer), "printer profiles" if printer else "design profiles"
    raise DesignError("profile", name_or_path, f"not found; known {what}: {', '.join(known) or 'none'}")


def _not_sections(data: Any) -> str | None:
    """Why a profile file's top level is no mapping of sections (None: it is one)."""
    if isinstance(data, dict):
        return None
    what = "is empty" if data is None else f"holds a {'list' if isinstance(data, list) else 'single value'}"
    return f"must be a mapping of sections; the file {what}"


def profile_kind(data: Any) -> str | None:
    """The kind of wheelstep YAML file a top-level mapping is, by its sections: 'printer' (a
    ``printer:`` section), else 'design', 'batch' or 'sweep' (a section only that kind's model
    has); None when no section tells."""
    from wheelstep_cli.config.batch_file import BatchFile
    from wheelstep_cli.config.design import DesignProfile
    from wheelstep_cli.config.printers import is_printer_profile
    from wheelstep_cli.config.sweep_model import SweepFile

    if not isinstance(data, dict):
        return None
    if is_printer_profile(data):
        return "printer"
    models = {"design": DesignProfile, "batch": BatchFile, "sweep": SweepFile}
    for kind, model in models.items():
        others = set().union(*(other.model_fields for name, other in models.items() if name != kind))
        if any(key in data for key in model.model_fields if key not in others):
            return kind
    return None


def wrong_kind(data: Any, wanted: str, given: str, goes_in: dict[str, str] | None = None) -> str:
    """Why the file the user named ``given`` (its top-level mapping ``data``) is no ``wanted``
    ('printer', 'design') profile: what it is when its sections tell and what takes it (a
    profile's option from ``goes_in``, kind -> option), then the known profiles wanted."""
    kind = profile_kind(data)
    if kind in ("batch", "sweep"):
        what = f"is a {kind} file, not a {wanted} profile (`wheelstep {kind} {given}` takes it)"
    elif kind is not None:
        what = f"is a {kind} profile, not a {wanted} profile" + (
            f" (a {kind} profile goes in {goes_in[kind]})" if goes_in and kind in goes_in else "")
    else:
        sections = "a printer: section" if wanted == "printer" else "a mechanism:, gears: or shoe: section"
        what = f"is not a {wanted} profile (no {wanted} keys: a {wanted} profile has {sections})"
    return f"{what}; {wanted} profiles: " + ", ".join(profile_names(printer=wanted == "printer"))


def load_profile(name_or_path: str) -> tuple[Path, dict[str, Any]]:
    """Read a profile file; returns its path and its top-level mapping."""
    import yaml

    path = find_profile(name_or_path)
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as err:
        raise DesignError("profile", str(path), f"is not valid YAML ({err})") from None
    if not isinstance(data, dict):
        raise DesignError("profile", str(path), "must be a mapping of sections")
    return path, data


def shadowed_preset(name_or_path: str) -> Path | None:
    """The shipped preset that a profile given by name is read instead of (a ``profiles/``
    folder in the working folder comes first), None when it is the preset itself, a path, or
    no preset has that name."""
    if Path(name_or_path).suffix in (".yaml", ".yml"):
        return None
    try:
        found = find_profile(name_or_path).resolve()
    except DesignError:
        return None
    preset = next((shipped_profiles() / f"{name_or_path}{suffix}" for suffix in (".yaml", ".yml")
                   if (shipped_profiles() / f"{name_or_path}{suffix}").is_file()), None)
    return preset if preset is not None and preset.resolve() != found else None


def profile_record(name_or_path: str) -> dict:
    """What a report says of the design profile a part was made from: the name given (a path:
    its file's name), the file's name, its SHA-256 (the part traced to the file's contents)
    and whether it is the shipped preset."""
    import hashlib

    file = find_profile(name_or_path)
    # a path as its file's name, as a printer's is recorded: no folder of the user's in a report
    given = Path(name_or_path).name if Path(name_or_path).suffix in (".yaml", ".yml") else name_or_path
    return {"given": given, "file": file.name, "sha256": hashlib.sha256(file.read_bytes()).hexdigest(),
            "shipped": file.resolve().parent == shipped_profiles().resolve()}


def profile_label(file: Path) -> str:
    """A profile's path as shown in messages: relative to the working folder when inside it."""
    try:
        return str(Path(file).resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(file)


def profile_names(printer: bool) -> list[str]:
    """Names of the known printer profiles (``printer``) or design profiles (not)."""
    import yaml

    from wheelstep_cli.config.printers import is_printer_profile

    names = set()
    for folder in profile_dirs():
        for file in folder.glob("*.yaml") if folder.is_dir() else []:
            try:
                data = yaml.safe_load(file.read_text(encoding="utf-8")) if file.is_file() else None
            except (yaml.YAMLError, OSError, UnicodeDecodeError):
                continue    # not a profile to offer (a message listing names must not fail on it)
            if isinstance(data, dict) and is_printer_profile(data) == printer:
                names.add(file.stem)
    return sorted(names)


def beside(folder: Path, given: str | None) -> str | None:
    """A file a YAML file names (``given``, a path), looked up beside that file (in
    ``folder``) first, as a batch file's profiles are, and then given as a path from the working
    folder; as given (from the working folder) when it is absolute or not there."""
    if given is None or Path(given).is_absolute() or not (folder / given).is_file():
        return given
    # as a path from the working folder when it lies below it (as the user would name it
    # there): no folder of the user's, such as a temporary one, ends up in the reports
    found = folder / given
    try:
        return str(found.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(found)


def design_from_file(name: str, file: Path, doc: LocatedYaml | None = None):
    """The checked design profile in ``file`` (``doc``: the file already parsed); every
    problem raised at once as InvalidInput with ``file:line``."""
    from wheelstep_cli.config.design import DesignProfile
    from wheelstep_cli.config.printers import is_printer_profile
    from wheelstep_cli.config.schema import validate_file

    if doc is None:
        try:
            doc = read_located_yaml(file, profile_label(file))
        except YamlSyntaxError as err:
            raise InvalidInput(yaml_issues(err)) from None
    if (why := _not_sections(doc.data)) is not None:
        raise DesignError("design", name, why)
    if is_printer_profile(doc.data):
        raise DesignError("design", name, "is not a design profile; design profiles: "
                          + ", ".join(profile_names(printer=False)))
    # a key no design profile has may tell another kind of file (a batch's parts:)
    if not set(doc.data) <= set(DesignProfile.model_fields) and profile_kind(doc.data) in ("batch", "sweep"):
        raise DesignError("design", name, wrong_kind(doc.data, "design", name))
    # an empty value would do nothing (the default stands) while the file seems to set it
    empty = [Issue(doc.where((section, key)), f"{section}.{key}", "= null: give a value, or leave the key out "
                   "for the default") for section, values in doc.data.items() if isinstance(values, dict)
             for key, value in values.items() if value is None and section in DesignProfile.model_fields]
    if empty:
        # said with the file's other problems, which are found without the empty keys
        given = replace(doc, data={section: {k: v for k, v in values.items() if v is not None}
                                   if isinstance(values, dict) and section in DesignProfile.model_fields
                                   else values for section, values in doc.data.items()})
        issues: list = []
        validate_file(DesignProfile, given, issues=issues)
        raise InvalidInput(_with_conflicts(empty + issues, given))
    try:
        profile = validate_file(DesignProfile, doc)
    except InvalidInput as err:
        refused = InvalidInput(_with_conflicts(err.issues, doc))
        refused.partial = _without_issues(name, file, doc, refused.issues)
        raise refused from None
    gears = profile.gears
    if gears is not None and gears.law_csv is not None:
        # the profile's law CSV beside the profile, wherever the command is run from
        gears = gears.model_copy(update={"law_csv": beside(Path(file).parent, gears.law_csv)})
        profile = profile.model_copy(update={"gears": gears})
    profile._where = {(section, key): doc.where((section, key)) for section in ("mechanism", "gears", "shoe")
                      for key in profile.values(section)}
    if conflicts := _conflict_issues(profile.values, doc):
        raise InvalidInput(conflicts)
    profile._shipped = Path(file).resolve().parent == shipped_profiles().resolve()
    return profile


def _without_issues(name: str, file: Path, doc: LocatedYaml, issues: list):
    """The design profile of ``doc`` read without the keys its ``issues`` name (their defaults
    standing in), for the rules between the other values to be said in the same run; None
    when it still cannot be read."""
    from wheelstep_cli.config.design import DesignProfile

    named = {issue.what for issue in issues}
    data = {section: {k: v for k, v in values.items() if f"{section}.{k}" not in named}
            if isinstance(values, dict) and section in DesignProfile.model_fields else values
            for section, values in doc.data.items()}
    if data == doc.data:
        return None
    try:
        return design_from_file(name, file, replace(doc, data=data))
    except DesignError:
        return None


def _with_conflicts(issues: list, doc: LocatedYaml) -> list:
    """``issues`` of a design profile and the mechanism conflicts among its values that are
    plain numbers (:func:`~wheelstep_cli.config.design.mechanism_conflicts`), in the file's
    line order: a file with several problems gets all of them at once."""
    import math

    from wheelstep_cli.config.design import DesignProfile

    named = {issue.what for issue in issues}
    # a section whose lengths have a problem of their own has no mechanism to compare
    unsure = {section for section in ("mechanism", "gears", "shoe")
              if any(f"{section}.{key}" in named for key in ("a", "b", "c", "r_min"))}
    if "mechanism" in unsure or not any(issue.what for issue in issues):
        return issues

    def values(section: str) -> dict:
        given = doc.data.get(section)
        if section not in DesignProfile.model_fields or not isinstance(given, dict) or section in unsure:
            return {}
        return {key: value for key, value in given.items() if f"{section}.{key}" not in named
                and (isinstance(value, str) if key == "law_csv" else
                     isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value))}

    more = _conflict_issues(values, doc)

    def line(issue) -> int:
        tail = str(issue.where).rsplit(":", 1)[-1]
        return int(tail) if tail.isdigit() else 0
    return sorted([*issues, *more], key=line)


def _conflict_issues(values, doc: LocatedYaml) -> list:
    """An issue at its line for each mechanism conflict among a design profile's ``values``
    (``values(section)``: a section's values, mm; config.design.mechanism_conflicts)."""
    from wheelstep_cli.config.design import mechanism_conflicts

    return [Issue(doc.where((section, key)), f"{section}.{key}", f"= {values(section)[key]:g}: {why}")
            for section, key, why in mechanism_conflicts(values)]


def load_design_profile(name_or_path: str):
    """Find and check a design profile (a name or a path) given as a command's ``--profile``,
    see :func:`design_from_file`; a printer profile is refused naming the option it belongs to."""
    file = find_profile(name_or_path, printer=False)
    try:
        return design_from_file(name_or_path, file)
    except DesignError as err:
        if err.param == "file":
            raise _unreadable("profile", name_or_path, err) from None
        if err.param != "design":
            raise
        if not err.limit.startswith("is not a design profile"):
            raise DesignError("profile", name_or_path, err.limit) from None
        raise DesignError("profile", name_or_path, "is a printer profile, not a design profile (a "
                          "printer profile goes in --printer); design profiles: "
                          + ", ".join(profile_names(printer=False))) from None


def _unreadable(option: str, name_or_path: str, err: DesignError) -> DesignError:
    """A profile file that cannot be read (``err``, of its ``file``) said of the ``option``
    that named it, with the file's path when a name found it."""
    same = Path(str(err.value)).resolve() == Path(name_or_path).resolve()
    return DesignError(option, name_or_path, err.limit if same else f"{err.value} {err.limit}")


def load_printer_profile(name_or_path: str):
    """Find and check a printer profile (a name or a path) given as a command's ``--printer``;
    a design profile is refused naming the option it belongs to. Returns a Printer."""
    from wheelstep_cli.config.printers import is_printer_profile

    try:
        file = find_profile(name_or_path, printer=True)
    except DesignError as err:
        raise DesignError("printer", name_or_path, err.limit) from None
    label = profile_label(file)
    try:
        doc = read_located_yaml(file, label)
    except YamlSyntaxError as err:
        raise InvalidInput(yaml_issues(err)) from None
    except DesignError as err:
        raise _unreadable("printer", name_or_path, err) from None
    if (why := _not_sections(doc.data)) is not None:
        raise DesignError("printer", name_or_path, why)
    if not is_printer_profile(doc.data):
        raise DesignError("printer", name_or_path, wrong_kind(doc.data, "printer", name_or_path,
                                                              {"design": "--profile"}))
    name = Path(name_or_path).name if Path(name_or_path).suffix in (".yaml", ".yml") else name_or_path
    return printer_from_profile(name, file, label, doc, given=name_or_path)


def load_printer(name: str = DEFAULT_PRINTER):
    """The printer profile ``name`` (a preset name or a path), checked; see
    :func:`load_printer_profile`."""
    return load_printer_profile(name)
