"""PrusaSlicer configuration text: the ``; key = value`` lines of its ``Slic3r_PE.config``
(inside a 3MF) and the ``key = value`` lines of a ``.ini`` it loads with ``--load``."""

from __future__ import annotations

from typing import Any


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def slic3r_config_bytes(settings: dict[str, Any], header: str) -> bytes:
    """``Metadata/Slic3r_PE.config`` of a 3MF: a header comment, then ``; key = value``, sorted."""
    lines = [f"; {header}"] + [f"; {key} = {_value(settings[key])}" for key in sorted(settings)]
    return ("\n".join(lines) + "\n").encode("utf-8")


def slicer_ini_bytes(settings: dict[str, Any], header: str) -> bytes:
    """The same settings as a PrusaSlicer ``.ini`` (``prusa-slicer --load FILE.ini``)."""
    lines = [f"# {header}"] + [f"{key} = {_value(settings[key])}" for key in sorted(settings)]
    return ("\n".join(lines) + "\n").encode("utf-8")
