"""How a batch entry's problems are said: at the override a problem names, else at the entry,
with the design profile it comes from and the line of the key it names there."""

from __future__ import annotations

from wheelstep_cli.config.names import as_keys, in_file_words, remedies_as_keys, yaml_message
from wheelstep_cli.config.schema import Issue, dotted, show
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.kinds import PartKind


def line_of(where: str | None) -> int:
    """The line of a ``file:line`` (0 for None or one that names no line)."""
    line = (where or "").rsplit(":", 1)[-1]
    return int(line) if line.isdigit() else 0


def key_of(err_or_name) -> str:
    """A DesignError's parameter (or a name) as a file's key."""
    return getattr(err_or_name, "param", err_or_name).replace("-", "_")


def design_line(design, kind: PartKind, design_name: str, err: DesignError) -> str:
    """The design profile ``design_name`` as an entry's problem ``err`` says it comes from:
    with the line of the key it names (``rules.yaml:3``) in a user's file (a shipped preset's
    keys are mended by overrides, not in its file)."""
    if design.shipped:
        return design_name
    sections = (kind.section, "mechanism")
    named = key_of(err.for_given([key for part in sections for key in design.values(part)]))
    where = next((design.where(part, named) for part in sections if named in design.values(part)), None)
    return f"{design_name}:{line_of(where)}" if line_of(where) else design_name


def entry_problem(doc, path, err: DesignError, override_where, design_name, overrides) -> Issue:
    """An entry's problem at the override it names, else at the entry with where it came from
    (``design_name``, with the line of the key it names)."""
    err = err.for_given(override_where)
    param = err.param.replace("-", "_")
    if param in override_where:
        # the value as the file gives it (a law CSV's path as written, not as found from here)
        return Issue(override_where[param], dotted(path + ("overrides", param)),
                     f"= {show(overrides.get(param, err.value))}: {remedies_as_keys(in_file_words(err.limit), err)}")
    given = f", with overrides {', '.join(overrides)}" if overrides else ""
    # a remedy is an override the entry adds
    said = remedies_as_keys(yaml_message(err), err, lambda options: f"overrides {{{as_keys(options)}}}")
    return Issue(doc.where(path), dotted(path), f"{said} (from design {design_name}{given})")
