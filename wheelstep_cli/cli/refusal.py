"""How a run that fails says so: its lines on stderr and, when the command was asked for
``--json``, the same as one JSON object on stdout, so that a script reading stdout gets the
refusal, its exit code and, for bad input, the option, value and remedy."""

from __future__ import annotations

import typer

from wheelstep_cli.config.names import flag_name
from wheelstep_cli.errors import offered_remedies
from wheelstep_cli.formats.jsonio import json_text


def said(lines: list[str], code: int, args: list[str], err: Exception | None = None) -> int:
    """Print ``lines`` (each a whole line, ``wheelstep: error: ...``) on stderr and, with
    ``--json`` among ``args``, ``{"error": {...}}`` on stdout (the exit code, the lines and, for
    bad input, the option, its value, the remedy as options -> values and, as ``remedies``,
    every remedy the line offers, the first being ``remedy``); return ``code``."""
    for line in lines:
        typer.echo(line, err=True)
    if "--json" in args:
        record = {"exit_code": code, "message": "\n".join(lines)}
        if err is not None and hasattr(err, "param"):
            remedies = [{flag_name(name): value for name, value in remedy.items()}
                        for remedy in offered_remedies(err)]
            record.update(option=flag_name(err.param), value=getattr(err, "value", None),
                          remedy=remedies[0] if remedies else {}, remedies=remedies)
        typer.echo(json_text({"error": record}), nl=False)
    return code

