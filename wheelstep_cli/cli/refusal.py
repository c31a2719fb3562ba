"""How a run that fails says so: its lines on stderr and, when the command was asked for
``--json``, the same as one JSON object on stdout, so that a script reading stdout gets the
refusal, its exit code and, for bad input, the option, value and remedies, for a file's
problems each problem."""

from __future__ import annotations

import typer

from wheelstep_cli.config.names import flag_name
from wheelstep_cli.errors import offered_remedies
from wheelstep_cli.formats.jsonio import json_text


def said(lines: list[str], code: int, args: list[str], err: Exception | None = None,
         option: str | None = None, every: list[tuple[Exception, str | None, list[str]]] | None = None) -> int:
    """Print ``lines`` (each a whole line, ``wheelstep: error: ...``) on stderr and, with
    ``--json`` among ``args``, ``{"error": {...}}`` on stdout; return ``code``.

    The object has the same keys for every refusal: the exit code, the lines (``message``),
    for bad input the ``option`` (as the line names it: ``option``, else the parameter's
    flag) and its ``value``, the ``remedy`` as options -> values and, as ``remedies``, every
    remedy the line offers, the first being ``remedy`` (None, None, {} and [] where there is
    none); a file's problems (``issues``) each as ``{where, key, message}`` in ``problems``
    ([] for any other refusal), with no option named. Bad input with several problems
    (``every``: each error, the option its line names (None: a file's) and its lines) lists each in
    ``problems``, an option's with ``where`` None and the option as ``key``; ``option``,
    ``value`` and the remedies are the first's."""
    for line in lines:
        typer.echo(line, err=True)
    if "--json" in args:
        record = {"exit_code": code, "message": "\n".join(lines), "option": None, "value": None,
                  "remedy": {}, "remedies": [], "problems": []}
        if err is not None:
            remedies = [{flag_name(name): value for name, value in remedy.items()}
                        for remedy in offered_remedies(err)]
            record.update(remedy=remedies[0] if remedies else {}, remedies=remedies)
        issues = getattr(err, "issues", None)
        if every is not None:
            record["problems"] = [problem for each in every for problem in _problems(*each)]
        elif issues is not None:
            record["problems"] = _problems(err, None, [])
        if issues is None and hasattr(err, "param"):
            # the value as given: a line may show it with what a printer drew beside it
            value = getattr(err, "given_values", {}).get(err.param.replace("-", "_"), getattr(err, "value", None))
            record.update(option=option or flag_name(err.param), value=value)
        typer.echo(json_text({"error": record}), nl=False)
    return code


def _problems(err: Exception, option: str | None, lines: list[str]) -> list[dict]:
    """``{where, key, message}`` of each problem of the bad input ``err`` (said in ``lines``):
    a file's lines each name its key, none an option; an option's line (``option``) has no
    ``where``."""
    issues = getattr(err, "issues", None)
    if issues is not None:
        return [{"where": issue.where, "key": issue.what or None,
                 "message": str(issue)[len(issue.where) + 2:]} for issue in issues]
    return [{"where": None, "key": option, "message": line} for line in lines]
