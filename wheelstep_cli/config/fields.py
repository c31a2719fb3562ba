"""Field types shared by the configuration models: numbers as YAML and the CLI give them.

A number is an int or a float (not a bool, not text) and finite. ``Number`` keeps the
value as given (an int stays an int, so reports repeat the user's figures), ``Real``
stores a float, ``Whole`` a whole number (``48`` or ``48.0``, as the command line
takes it). Units and limit texts ride in ``json_schema_extra`` and are used by
:mod:`wheelstep_cli.config.schema` to word an error.
"""

from __future__ import annotations

import math
import numbers
from enum import Enum
from typing import Annotated, Any

from pydantic import BeforeValidator, ConfigDict, Field, WrapValidator
from pydantic_core import PydanticCustomError

#: Configuration of every model: unknown keys refused, values frozen, enums stored as values.
STRICT = ConfigDict(extra="forbid", frozen=True, use_enum_values=True)


def _checked_number(value: Any, handler, keep_int: bool):
    if value is None:
        return handler(value)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise PydanticCustomError("number", "must be a number")
    if not math.isfinite(value):
        raise PydanticCustomError("finite_number", "must be a finite number")
    handler(float(value))  # the bounds of the field
    return int(value) if keep_int and isinstance(value, numbers.Integral) else float(value)


def _keep(value, handler):
    return _checked_number(value, handler, keep_int=True)


def _float(value, handler):
    return _checked_number(value, handler, keep_int=False)


Number = Annotated[float, WrapValidator(_keep)]
Real = Annotated[float, WrapValidator(_float)]


def _whole(value):
    # a float with no fraction is the whole number it writes (YAML reads 48.0 as a float);
    # anything else goes on to the strict int check (text, 48.5 and bools are refused there)
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return value


#: A whole number (a field of it also states ``strict=True``, so text is not read as one).
Whole = Annotated[int, BeforeValidator(_whole)]


def quantity(default: Any = ..., unit: str = "", limit: str | None = None, **bounds) -> Any:
    """A model field with its unit (``mm``, ``deg``) and, if the bounds alone do not say
    it well, the limit text an error shows."""
    extra = {"unit": unit}
    if limit is not None:
        extra["limit"] = limit
    return Field(default, json_schema_extra=extra, **bounds)


def length(default: Any = ..., **bounds) -> Any:
    """A length field in mm."""
    return quantity(default, unit="mm", **bounds)


class Choice(str, Enum):
    """A choice among names, read in any case as the command line reads it (``Tooth`` is
    ``tooth``): a profile and an option say the same thing the same way."""

    @classmethod
    def _missing_(cls, value: object):
        if isinstance(value, str):
            for member in cls:
                if member.value == value.lower():
                    return member
        return None
