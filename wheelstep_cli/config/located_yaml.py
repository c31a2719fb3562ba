"""YAML read with the line of every key and value, so errors can say ``file:line``.

The document is composed into nodes (``yaml.compose``), then turned into plain
Python data while the line (1-based) of each mapping key, sequence item and value is
recorded under its path, e.g. ``("parts", 1, "overrides", "z")``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from wheelstep_cli.errors import DesignError

PathKey = tuple


@dataclass(frozen=True)
class LocatedYaml:
    """Plain data of a YAML file plus the line of every path in it."""

    file: str
    data: Any
    lines: dict[PathKey, int] = field(default_factory=dict)

    def line(self, path: PathKey) -> int:
        """Line (1-based) of ``path``, or of its nearest recorded parent."""
        path = tuple(path)
        while path not in self.lines and path:
            path = path[:-1]
        return self.lines.get(path, 1)

    def where(self, path: PathKey) -> str:
        return f"{self.file}:{self.line(path)}"


class YamlSyntaxError(DesignError):
    """The file is not YAML; ``where`` is ``file:line``."""

    def __init__(self, where: str, problem: str):
        self.where = where
        super().__init__("yaml", where, problem)


def read_located_yaml(path: Path, label: str | None = None) -> LocatedYaml:
    """Read ``path`` as YAML (safe tags only); ``label`` is the file name used in messages."""
    label = label or str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise DesignError("file", label, f"cannot be read ({err})") from None
    return parse_located_yaml(text, label)


def parse_located_yaml(text: str, label: str) -> LocatedYaml:
    """Parse YAML text; syntax errors and duplicate keys raise with ``label:line``."""
    import yaml
    from yaml.constructor import SafeConstructor

    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        line = mark.line + 1 if mark is not None else 1
        raise YamlSyntaxError(f"{label}:{line}", f"is not valid YAML ({err.problem})") from None
    except yaml.YAMLError as err:
        raise YamlSyntaxError(f"{label}:1", f"is not valid YAML ({err})") from None
    lines: dict[PathKey, int] = {}
    if root is None:
        return LocatedYaml(label, None, lines)
    constructor = SafeConstructor()

    def walk(node, path: PathKey):
        lines.setdefault(path, node.start_mark.line + 1)
        if isinstance(node, yaml.MappingNode):
            out = {}
            for key_node, value_node in node.value:
                if not isinstance(key_node, yaml.ScalarNode):
                    raise YamlSyntaxError(f"{label}:{key_node.start_mark.line + 1}",
                                          "keys must be plain names")
                key = constructor.construct_object(key_node, deep=True)
                if key in out:
                    raise YamlSyntaxError(f"{label}:{key_node.start_mark.line + 1}",
                                          f"duplicate key '{key}'")
                lines[path + (key,)] = key_node.start_mark.line + 1
                out[key] = walk(value_node, path + (key,))
            return out
        if isinstance(node, yaml.SequenceNode):
            return [walk(item, path + (i,)) for i, item in enumerate(node.value)]
        try:
            return constructor.construct_object(node, deep=True)
        except yaml.YAMLError as err:
            raise YamlSyntaxError(f"{label}:{node.start_mark.line + 1}", f"bad value ({err})") from None

    return LocatedYaml(label, walk(root, ()), lines)
