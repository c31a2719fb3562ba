"""Errors a user can fix: they name the parameter, its value and the limit it breaks."""

from __future__ import annotations


class DesignError(ValueError):
    """An input that cannot give a valid part.

    ``param`` is the parameter's one snake_case name (the YAML key; the command-line flag
    is derived from it, see :func:`wheelstep_cli.config.names.flag_name`), ``value`` what
    was given, ``limit`` what it must satisfy. ``str()`` words it as the command line
    names the parameter (underscores as dashes); a file names it as the key.
    """

    def __init__(self, param: str, value: object, limit: str):
        self.param = param
        self.value = value
        self.limit = limit
        super().__init__(f"{param.replace('_', '-')} = {format_value(value)}: {limit}")


def format_value(value: object) -> str:
    """A value as an error shows it (floats in the shortest form)."""
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def require(condition: bool, param: str, value: object, limit: str) -> None:
    """Raise :class:`DesignError` unless ``condition`` holds."""
    if not condition:
        raise DesignError(param, value, limit)
