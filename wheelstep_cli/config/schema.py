"""Problems of input files as ``file:line: name = value: limit``, from the models' validation.

The configuration models (pydantic) check types, bounds, choices and unknown keys; this
module words each of their errors the way the user wrote the input: the dotted path of
the YAML key (``parts[1].overrides.z``) at its line, or the parameter's snake_case name
for values given in code or on the command line.
"""

from __future__ import annotations

import difflib
import functools
import re
import types
import typing
from dataclasses import dataclass
from enum import Enum
from typing import Any, Iterable, Optional

import annotated_types
from pydantic import BaseModel, ValidationError, create_model
from pydantic.fields import FieldInfo

from wheelstep_cli.config.fields import STRICT
from wheelstep_cli.config.located_yaml import LocatedYaml
from wheelstep_cli.config.names import yaml_message
from wheelstep_cli.errors import DesignError


@dataclass(frozen=True)
class Issue:
    """One problem in an input file: where (``file:line``), what (a dotted path), why."""

    where: str
    what: str
    message: str

    def __str__(self) -> str:
        if not self.what:
            return f"{self.where}: {self.message}"
        sep = " " if self.message.startswith("= ") else ": "
        return f"{self.where}: {self.what}{sep}{self.message}"


class InvalidInput(DesignError):
    """Input files with problems; ``issues`` lists every one (each prints on its own line)."""

    def __init__(self, issues: list[Issue]):
        self.issues = _in_file_order(issues)
        first = self.issues[0]
        super().__init__(first.what, first.where, first.message)

    def lines(self) -> list[str]:
        return [str(issue) for issue in self.issues]

    def __str__(self) -> str:
        return "\n".join(self.lines())


def _in_file_order(issues: Iterable[Issue]) -> list[Issue]:
    """``issues`` by line within each file (files in the order they first appear): the
    validator finds them in its fields' order, not the file's."""
    placed = []
    files: dict[str, int] = {}
    for issue in issues:
        name, _, line = issue.where.rpartition(":")
        key = (files.setdefault(name or issue.where, len(files)), int(line) if name and line.isdigit() else 0)
        placed.append((key, issue))
    return [issue for _, issue in sorted(placed, key=lambda item: item[0])]


def dotted(path: Iterable) -> str:
    """("parts", 1, "overrides", "z") -> "parts[1].overrides.z"."""
    out = ""
    for key in path:
        out += f"[{key}]" if isinstance(key, int) else (f".{key}" if out else str(key))
    return out


def nearest_name(name: str, known: Iterable[str]) -> str | None:
    """The known name closest to a mistyped one (for "did you mean"), or None."""
    near = difflib.get_close_matches(name, list(known), n=1)
    return near[0] if near else None


def show(value: Any) -> str:
    """A value as an error line shows it: text quoted, numbers short, and a long mapping or
    list (a JSON report given as a batch file, say) by what it is, not dumped whole."""
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, bool):
        return "true" if value else "false"      # YAML's words (Python's True reads as text there)
    if isinstance(value, float):
        return f"{value:g}"
    text = str(value)
    if len(text) <= SHOWN_LENGTH or not isinstance(value, (dict, list)):
        return text
    if isinstance(value, dict):
        keys = ", ".join(map(str, list(value)[:4])) + (", ..." if len(value) > 4 else "")
        return f"{{a mapping of {len(value)} keys: {keys}}}"
    return f"[a list of {len(value)} items]"


#: Longest value (characters) an error line shows whole.
SHOWN_LENGTH = 60


# ----------------------------------------------------------------------------- models
def _unwrap(tp: Any) -> Any:
    """Optional[X] -> X."""
    args = [a for a in typing.get_args(tp) if a is not type(None)]
    if typing.get_origin(tp) in (typing.Union, types.UnionType) and len(args) == 1:
        return args[0]
    return tp


def _walk(model: type[BaseModel], loc: tuple) -> tuple[Any, FieldInfo | None]:
    """(type, field) found at ``loc`` inside ``model``; the field is the last named one."""
    tp, info = model, None
    for key in loc:
        tp = _unwrap(tp)
        if isinstance(tp, type) and issubclass(tp, BaseModel):
            info = tp.model_fields.get(key) if isinstance(key, str) else None
            if info is None:
                return None, None
            tp = info.annotation
        elif typing.get_origin(tp) is dict:
            tp = typing.get_args(tp)[1]
        elif typing.get_origin(tp) in (list, tuple):
            args = typing.get_args(tp)
            tp = args[0] if args else Any
        else:
            return None, info
    return _unwrap(tp), info


def allowed_keys(model: type[BaseModel], loc: tuple) -> list[str]:
    """Keys of the mapping at ``loc`` (the model's fields, in their order)."""
    tp, _ = _walk(model, loc)
    return list(tp.model_fields) if isinstance(tp, type) and issubclass(tp, BaseModel) else []


@functools.cache
def section_model(spec: type[BaseModel]) -> type[BaseModel]:
    """The model of a partial spec (a profile section, batch overrides): every field of
    ``spec`` with its checks, none required, no cross-field rules (they need all values)."""
    fields = {name: (Optional[info.annotation], FieldInfo.merge_field_infos(info, default=None))
              for name, info in spec.model_fields.items()}
    return create_model(f"{spec.__name__}Section", __config__=STRICT, **fields)


# ----------------------------------------------------------------------------- wording
_TYPES = {
    "number": "must be a number", "float_type": "must be a number", "float_parsing": "must be a number",
    "finite_number": "must be a finite number",
    "int_type": "must be a whole number", "int_from_float": "must be a whole number",
    "int_parsing": "must be a whole number",
    "bool_type": "must be true or false", "bool_parsing": "must be true or false",
    "string_type": "must be text",
    "model_type": "must be a mapping of keys", "dict_type": "must be a mapping of keys",
    "model_attributes_type": "must be a mapping of keys",
}
_BOUNDS = {annotated_types.Gt: (">", "gt"), annotated_types.Ge: (">=", "ge"),
           annotated_types.Lt: ("<", "lt"), annotated_types.Le: ("<=", "le")}


def _choices(tp: Any) -> list[str]:
    if isinstance(tp, type) and issubclass(tp, Enum):
        return [str(m.value) for m in tp]
    return [str(a) for a in typing.get_args(tp)] if typing.get_origin(tp) is typing.Literal else []


def _range(info: FieldInfo | None, error: dict) -> str:
    parts = []
    for item in info.metadata if info is not None else []:
        if type(item) in _BOUNDS:
            sign, attr = _BOUNDS[type(item)]
            parts.append(f"{sign} {getattr(item, attr):g}")
    if not parts:  # a bound of an item (e.g. of a list), not of the field
        ctx = error.get("ctx", {})
        parts = [f"{sign} {ctx[attr]:g}" for sign, attr in _BOUNDS.values() if attr in ctx]
    return " and ".join(parts)


def limit_text(model: type[BaseModel], error: dict) -> str:
    """What the value at the error's location must be, in the words of the errors."""
    tp, info = _walk(model, tuple(error["loc"]))
    extra = (info.json_schema_extra if info is not None else None) or {}
    kind = error["type"]
    if kind in _TYPES:
        return _TYPES[kind]
    if "limit" in extra:
        return extra["limit"]
    if kind in ("enum", "literal_error"):
        return "must be one of: " + ", ".join(_choices(tp) or [str(error.get("ctx", {}).get("expected"))])
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        unit = f" {extra['unit']}" if extra.get("unit") else ""
        return f"must be {_range(info, error)}{unit}"
    return error["msg"]


def field_limit(models: Iterable[type[BaseModel]], name: str) -> str | None:
    """The limit text ("must be ...") a field ``name`` of the first of ``models`` that has one
    states for itself (its bounds alone may be only part of the rule, which other checks
    complete); None when none does."""
    for model in models:
        info = model.model_fields.get(name)
        extra = info.json_schema_extra if info is not None and isinstance(info.json_schema_extra, dict) else {}
        if "limit" in extra:
            return str(extra["limit"])
    return None


#: Keys that belong to another file or section, and where: a "did you mean" of this section's
#: keys would send the user elsewhere (``fit`` read as ``fillet``).
KEYS_ELSEWHERE = {
    "fit": "a fit is the printer's: `fit: auto` (or tight, normal, loose) in the printer profile's "
           "`band:` section (a copy of a preset such as fdm-0.4-pla.yaml, its path as the printer)",
    "printer": "a printer is chosen where the parts are made: `--printer NAME` (a preset or a profile's "
               "path), or a batch entry's `printer:` beside its `design:`",
}


def _issue(model: type[BaseModel], doc: LocatedYaml, loc: tuple, error: dict) -> Issue:
    kind = error["type"]
    if kind == "missing" and isinstance(loc[-1], int):
        # a list too short for its fixed length (a bed of one size): the list's own limit
        given = _value_at(doc.data, loc[:-1])
        limit = limit_text(model, {"loc": tuple(error["loc"])[:-1], "type": "too_short", "msg": "too short"})
        return Issue(doc.where(loc[:-1]), dotted(loc[:-1]), f"= {show(given)}: {limit}")
    if kind == "missing":
        return Issue(doc.where(loc[:-1]), dotted(loc[:-1]), f"needs the key '{loc[-1]}'")
    if kind == "extra_forbidden":
        if str(loc[-1]) in KEYS_ELSEWHERE:
            return Issue(doc.where(loc), dotted(loc), f"unknown key here; {KEYS_ELSEWHERE[str(loc[-1])]}")
        allowed = allowed_keys(model, tuple(error["loc"][:-1]))
        near = nearest_name(str(loc[-1]), allowed)
        hint = f"did you mean {near}? " if near else ""
        return Issue(doc.where(loc), dotted(loc), f"unknown key; {hint}allowed: " + ", ".join(allowed))
    cause = error.get("ctx", {}).get("error")
    if isinstance(cause, DesignError):
        return Issue(doc.where(loc), dotted(loc), yaml_message(cause))
    if _TYPES.get(kind) == "must be a mapping of keys":
        return Issue(doc.where(loc), dotted(loc), _TYPES[kind])
    limit = limit_text(model, error)
    # a number field's refusal of text says how to write the number (not a choice field's)
    note = _as_digits(error["input"]) if limit in ("must be a number", "must be a whole number") else ""
    return Issue(doc.where(loc), dotted(loc), f"= {show(error['input'])}: {limit}{note}")


def _value_at(data, path: tuple):
    """The value of parsed YAML ``data`` at ``path`` (keys and list indices)."""
    for key in path:
        data = data[key]
    return data


#: A number whose exponent has no sign, which YAML 1.1 leaves as text.
_UNSIGNED_EXPONENT = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)[eE]\d+")


def _as_digits(value) -> str:
    """A note for text YAML 1.1 would read as a number other than its digits say (``010`` as
    octal 8, ``4_8`` as 48, ``1:30`` as 90, ``0x30``), which the reader keeps as text: how to
    write the number instead. Empty for anything else."""
    from wheelstep_cli.config.located_yaml import reads_otherwise

    if isinstance(value, str) and _UNSIGNED_EXPONENT.fullmatch(value.strip()):
        # YAML 1.1 reads an exponent without its sign (1e2, 1.0e2) as text
        return " written with the exponent's sign (1.0e+2) or as plain decimal digits (100)"
    return (" written as plain decimal digits (no leading zero, underscore, base prefix or colon)"
            if isinstance(value, str) and reads_otherwise(value) else "")


def located_issues(model: type[BaseModel], doc: LocatedYaml, path: tuple,
                   err: ValidationError) -> list[tuple[tuple, Issue]]:
    """(path in the file, issue) of every error of validating ``doc``'s value at ``path``."""
    out, needed = [], {}
    for error in err.errors():
        loc = path + tuple(error["loc"])
        if error["type"] == "missing":
            # a mapping's missing keys in one line, at the mapping
            needed.setdefault(loc[:-1], []).append(loc[-1])
            if len(needed[loc[:-1]]) > 1:
                continue
        out.append((loc, _issue(model, doc, loc, error)))
    return [(loc, _needs(doc, loc[:-1], needed[loc[:-1]]) if len(needed.get(loc[:-1], ())) > 1
             and issue.message.startswith("needs the key ") else issue) for loc, issue in out]


def _needs(doc: LocatedYaml, at: tuple, keys: list) -> Issue:
    """The mapping at ``at`` lacks several ``keys``: one issue naming them all."""
    return Issue(doc.where(at), dotted(at), "needs the keys " + ", ".join(f"'{key}'" for key in keys))


def file_issues(model: type[BaseModel], doc: LocatedYaml, path: tuple,
                err: ValidationError) -> list[Issue]:
    """Every error of validating ``doc``'s value at ``path`` with ``model``, at its line."""
    return [issue for _, issue in located_issues(model, doc, path, err)]


def yaml_issues(err) -> list[Issue]:
    """The issues of a file that does not read as YAML (config.located_yaml.YamlSyntaxError),
    each at its line: every repeated key at once."""
    return [Issue(where, "", problem) for where, problem in err.problems]


def validate_file(model: type[BaseModel], doc: LocatedYaml, path: tuple = (),
                  issues: list[Issue] | None = None):
    """``doc``'s value at ``path`` as a ``model`` (an empty value as an empty mapping);
    None when it has problems, which are appended to ``issues``."""
    value = doc.data
    for key in path:
        value = value.get(key) if isinstance(value, dict) else None
    try:
        return model.model_validate({} if value is None else value)
    except ValidationError as err:
        if issues is None:
            raise InvalidInput(file_issues(model, doc, path, err)) from None
        issues.extend(file_issues(model, doc, path, err))
        return None


def design_errors(model: type[BaseModel], err: ValidationError) -> list[DesignError]:
    """The errors of building ``model`` from values given by name (code, command line)."""
    out = []
    for error in err.errors():
        cause = error.get("ctx", {}).get("error")
        if isinstance(cause, DesignError):
            out.append(cause)
            continue
        param = ".".join(str(k) for k in error["loc"]) or model.__name__
        if error["type"] == "extra_forbidden":
            limit = "unknown parameter; allowed: " + ", ".join(model.model_fields)
        else:
            limit = limit_text(model, error)
        out.append(DesignError(param, error.get("input"), limit))
    return out


def build(model: type[BaseModel], values: dict[str, Any]):
    """``model(**values)``; the first problem raised as a DesignError naming the parameter."""
    try:
        return model.model_validate(values)
    except ValidationError as err:
        raise design_errors(model, err)[0] from None
