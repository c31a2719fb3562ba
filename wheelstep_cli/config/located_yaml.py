"""YAML read with the line of every key and value, so errors can say ``file:line``.

The document is composed into nodes (``yaml.compose``), then turned into plain
Python data while the line (1-based) of each mapping key, sequence item and value is
recorded under its path, e.g. ``("parts", 1, "overrides", "z")``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from wheelstep_cli.errors import DesignError, file_problem

PathKey = tuple
#: Largest YAML file read, bytes (a batch of hundreds of entries is a few tens of kB).
MAX_BYTES = 1 << 20
#: Most values a document may expand to (aliases included) and deepest nesting: bounds the
#: work a small file full of aliases (a "YAML bomb") can ask for.
MAX_VALUES = 100_000
MAX_DEPTH = 32
MERGE_TAG = "tag:yaml.org,2002:merge"


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
    """The file is not YAML; ``where`` is ``file:line``. ``problems``: every (where, problem)
    found (several when the file reads but repeats keys), the first being this one's."""

    def __init__(self, where: str, problem: str, more: list[tuple[str, str]] | None = None):
        self.where = where
        self.problems = [(where, problem), *(more or [])]
        super().__init__("yaml", where, problem)


def read_located_yaml(path: Path, label: str | None = None) -> LocatedYaml:
    """Read ``path`` as YAML (safe tags only); ``label`` is the file name used in messages."""
    label = label or str(path)
    try:
        data = Path(path).read_bytes()
    except OSError as err:
        raise DesignError("file", label, file_problem(path, err)) from None
    if len(data) > MAX_BYTES:
        raise DesignError("file", label, f"is {len(data)} bytes; at most {MAX_BYTES} are read")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise DesignError("file", label, f"is not UTF-8 text (byte {err.start})") from None
    return parse_located_yaml(text, label)


#: Tags of the plain scalars YAML 1.1 reads as numbers.
NUMBER_TAGS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")
#: The tag YAML 1.1 gives yes / no / on / off as well as true / false.
BOOL_TAG = "tag:yaml.org,2002:bool"
#: A whole number as plain decimal digits (no leading zero, base prefix or separator).
_PLAIN_INTEGER = re.compile(r"[-+]?(0|[1-9][0-9]*)\Z")


def _composed(text: str, label: str):
    """The YAML node tree of ``text`` (None: empty); YamlSyntaxError at ``label:line``."""
    import yaml

    try:
        return yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        line = mark.line + 1 if mark is not None else 1
        raise YamlSyntaxError(f"{label}:{line}", f"is not valid YAML ({_one_line(err.problem)})") from None
    except yaml.YAMLError as err:
        raise YamlSyntaxError(f"{label}:1", f"is not valid YAML ({_one_line(err)})") from None


def parse_located_yaml(text: str, label: str) -> LocatedYaml:
    """Parse YAML text; syntax errors and duplicate keys raise with ``label:line``."""
    import yaml
    from yaml.constructor import SafeConstructor

    root = _composed(text, label)
    lines: dict[PathKey, int] = {}
    if root is None:
        return LocatedYaml(label, None, lines)
    constructor = SafeConstructor()
    count = [0]
    repeated: list[tuple[str, str]] = []    # every repeated key, said together (the first value kept)

    def walk(node, path: PathKey, ancestors: frozenset = frozenset()):
        where = f"{label}:{node.start_mark.line + 1}"
        count[0] += 1
        if id(node) in ancestors:
            raise YamlSyntaxError(where, "holds an alias to itself (a recursive structure)")
        if len(path) > MAX_DEPTH or count[0] > MAX_VALUES:
            raise YamlSyntaxError(where, f"is too large: more than {MAX_VALUES} values or "
                                         f"{MAX_DEPTH} levels of nesting (aliases count as copies)")
        lines.setdefault(path, node.start_mark.line + 1)
        inner = ancestors | {id(node)}
        if isinstance(node, yaml.MappingNode):
            out = {}
            for key_node, value_node in node.value:
                if key_node.tag == MERGE_TAG:
                    raise YamlSyntaxError(f"{label}:{key_node.start_mark.line + 1}",
                                          "merge keys (<<) are not supported: write the keys out")
                if not isinstance(key_node, yaml.ScalarNode):
                    raise YamlSyntaxError(f"{label}:{key_node.start_mark.line + 1}",
                                          "keys must be plain names")
                # `on:`, `yes:` are names (YAML 1.2), not the keys True of YAML 1.1
                key = key_node.value if _truth_word(key_node) else constructor.construct_object(key_node, deep=True)
                if key in out:
                    repeated.append((f"{label}:{key_node.start_mark.line + 1}", f"duplicate key '{key}'"))
                    continue
                lines[path + (key,)] = key_node.start_mark.line + 1
                out[key] = walk(value_node, path + (key,), inner)
            return out
        if isinstance(node, yaml.SequenceNode):
            return [walk(item, path + (i,), inner) for i, item in enumerate(node.value)]
        if _misread_number(node) or _truth_word(node):
            return node.value
        try:
            return constructor.construct_object(node, deep=True)
        except (yaml.YAMLError, ValueError, TypeError) as err:
            raise YamlSyntaxError(where, f"bad value ({_one_line(err)})") from None

    try:
        data = walk(root, ())
    except YamlSyntaxError as err:      # said with the keys repeated before it
        raise YamlSyntaxError(*err.problems[0], err.problems[1:] + repeated) from None
    if repeated:
        raise YamlSyntaxError(*repeated[0], repeated[1:])
    return LocatedYaml(label, data, lines)


def _truth_word(node) -> bool:
    """Whether the scalar ``node`` is yes / no / on / off (any case), which YAML 1.1 reads as
    true or false and YAML 1.2 as the word: it is then kept as the word."""
    return node.tag == BOOL_TAG and node.value.lower() not in ("true", "false")


def _misread_number(node) -> bool:
    """Whether YAML 1.1 would read the scalar ``node`` as a number the text does not mean; it
    is then kept as text, which is what a name means and what a number field refuses with
    its own line."""
    if node.tag in NUMBER_TAGS and ("_" in node.value or ":" in node.value):
        return True     # 4_8 read as 48, 1:30 as 90 (base 60); YAML 1.2 reads both as text
    # 010 read as 8 (octal: a thickness of 010 would print 8 mm), 0x30 and 0b110000 as 48
    return node.tag == NUMBER_TAGS[0] and not _PLAIN_INTEGER.match(node.value)


def reads_otherwise(text: str) -> bool:
    """Whether YAML 1.1 reads the plain scalar ``text`` as a number other than its digits say
    (see :data:`_PLAIN_INTEGER`): such a value is kept as the text it is written as."""
    import yaml

    node = yaml.ScalarNode(yaml.resolver.Resolver().resolve(yaml.ScalarNode, text, (True, False)), text)
    return _misread_number(node)


def _one_line(err: Exception) -> str:
    """PyYAML's message folded to one line."""
    return " ".join(str(err).split())
