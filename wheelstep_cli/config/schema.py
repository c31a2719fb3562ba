"""Small checks of YAML values against Python type annotations, with ``file:line`` issues."""

from __future__ import annotations

import math
import types
import typing
from dataclasses import dataclass
from typing import Any, Iterable

from wheelstep_cli.errors import DesignError
from wheelstep_cli.config.located_yaml import LocatedYaml


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
        self.issues = list(issues)
        first = self.issues[0]
        super().__init__(first.what, first.where, first.message)

    def lines(self) -> list[str]:
        return [str(issue) for issue in self.issues]


def dotted(path: Iterable) -> str:
    """("parts", 1, "overrides", "z") -> "parts[1].overrides.z"."""
    out = ""
    for key in path:
        out += f"[{key}]" if isinstance(key, int) else (f".{key}" if out else str(key))
    return out


def show(value: Any) -> str:
    return repr(value) if isinstance(value, str) else f"{value:g}" if isinstance(value, float) else str(value)


def type_problem(value: Any, annotation: Any) -> str | None:
    """Why ``value`` (from YAML) does not fit ``annotation``; None when it does."""
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        options = typing.get_args(annotation)
        if value is None and type(None) in options:
            return None
        problems = [type_problem(value, a) for a in options if a is not type(None)]
        return None if any(p is None for p in problems) else problems[0]
    if origin is typing.Literal:
        allowed = typing.get_args(annotation)
        return None if value in allowed else "must be one of: " + ", ".join(map(str, allowed))
    if annotation is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return "must be a number"
        return None if math.isfinite(value) else "must be a finite number"
    if annotation is int:
        return None if isinstance(value, int) and not isinstance(value, bool) else "must be a whole number"
    if annotation is bool:
        return None if isinstance(value, bool) else "must be true or false"
    if annotation is str:
        return None if isinstance(value, str) else "must be text"
    return None


def check_mapping(doc: LocatedYaml, path: tuple, value: Any, allowed: Iterable[str],
                  issues: list[Issue], required: Iterable[str] = ()) -> dict:
    """Check ``value`` is a mapping with only ``allowed`` keys (and the ``required`` ones).

    Returns the mapping (empty when it is not one). Issues are appended.
    """
    allowed = list(allowed)
    if value is None:
        value = {}
    if not isinstance(value, dict):
        issues.append(Issue(doc.where(path), dotted(path), "must be a mapping of keys"))
        return {}
    for key in value:
        if key not in allowed:
            issues.append(Issue(doc.where(path + (key,)), dotted(path + (key,)),
                                "unknown key; allowed: " + ", ".join(allowed)))
    for key in required:
        if key not in value:
            issues.append(Issue(doc.where(path), dotted(path), f"needs the key '{key}'"))
    return value
