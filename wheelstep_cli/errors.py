"""Errors a user can fix: they name the parameter, its value and the limit it breaks."""

from __future__ import annotations


class DesignError(ValueError):
    """An input that cannot give a valid part.

    ``param`` is the user-facing parameter name (CLI option without dashes,
    same as the YAML key), ``value`` what was given, ``limit`` what it must satisfy.
    """

    def __init__(self, param: str, value: object, limit: str):
        self.param = param
        self.value = value
        self.limit = limit
        super().__init__(f"{param} = {_fmt(value)}: {limit}")


def _fmt(value: object) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def require(condition: bool, param: str, value: object, limit: str) -> None:
    """Raise :class:`DesignError` unless ``condition`` holds."""
    if not condition:
        raise DesignError(param, value, limit)
