"""One snake_case name per parameter; the command-line flag is derived from it.

Errors (:class:`~wheelstep_cli.errors.DesignError`) carry the snake_case name, which is
also the YAML key. A file names it as the key; the command line as the flag.
"""

from __future__ import annotations


def flag_name(param: str) -> str:
    """The command-line flag of a parameter: ``install_distance`` -> ``--install-distance``."""
    return "--" + param.replace("_", "-")


def yaml_message(err) -> str:
    """A DesignError as a file names it: ``install_distance = 140: must be ...`` (a switch as
    YAML writes it, true or false)."""
    from wheelstep_cli.errors import format_value

    value = str(err.value).lower() if isinstance(err.value, bool) else format_value(err.value)
    return f"{err.param} = {value}: {err.limit}"
