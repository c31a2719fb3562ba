"""Errors a user can fix: they name the parameter, its value and the limit it breaks."""

from __future__ import annotations

import math
import os
from enum import Enum
from pathlib import Path
from typing import Iterable


class DesignError(ValueError):
    """An input that cannot give a valid part.

    ``param`` is the parameter's one snake_case name (the YAML key; the command line shows
    it as the flag the user typed), ``value`` what was given, ``limit`` what it must
    satisfy. A rule that ties several parameters (R_min = a - 4b + c > 0) states itself
    for each of them in ``alternatives`` (name -> (value, limit)), so the error can name
    the one the user gave (:meth:`for_given`).
    """

    def __init__(self, param: str, value: object, limit: str,
                 alternatives: dict[str, tuple[object, str]] | None = None):
        self.param = param
        self.value = value
        self.limit = limit
        self.alternatives = dict(alternatives or {})
        super().__init__(f"{param} = {format_value(value)}: {limit}")

    @property
    def shown_value(self) -> str:
        """The value as the messages print it."""
        return format_value(self.value)

    def for_given(self, given: Iterable[str]) -> "DesignError":
        """This error restated for a parameter the user gave, when it names one they did not."""
        given = {name.replace("-", "_") for name in given}
        if self.param.replace("-", "_") in given:
            return self
        for name, (value, limit) in self.alternatives.items():
            if name.replace("-", "_") in given:
                return self._with_extras(DesignError(name, value, limit))
        return self

    def tied_to(self, inputs: dict[str, object]) -> "DesignError":
        """This error, also stated for each of ``inputs`` (name -> value, None: not set) that
        shares the blame, so :meth:`for_given` can name the one the user gave."""
        # the rule is the other parameter's: said as what this input leads to, not as its limit
        context = f"{tie_context(self.param, self.shown_value)}: {self.limit}"
        alternatives = dict(self.alternatives)
        for name, value in inputs.items():
            if value is not None and name.replace("-", "_") != self.param.replace("-", "_"):
                alternatives.setdefault(name, (value, context))
        return self._with_extras(DesignError(self.param, self.value, self.limit, alternatives))

    def restated(self, limit: str) -> "DesignError":
        """This error with another ``limit`` text, carrying what it carries besides."""
        return self._with_extras(DesignError(self.param, self.value, limit, self.alternatives))

    @property
    def cause(self) -> str:
        """What the refusal found, without what it says was written and its advice."""
        return self.limit.split(NOTHING_WRITTEN)[0]

    def with_advice(self, advice: str, remedy: dict) -> "DesignError":
        """This refusal ("...; nothing written; <advice>") with another advice and its
        ``remedy`` (name -> value), also in each input's statement of it."""
        def advised(text: str) -> str:
            return f"{text.split(NOTHING_WRITTEN)[0]}{NOTHING_WRITTEN}; {advice}"

        other = DesignError(self.param, self.value, advised(self.limit),
                            {name: (value, advised(text)) for name, (value, text) in self.alternatives.items()})
        other.remedy = remedy
        other.remedies = [remedy] if remedy else []   # the old advice's alternatives went with it
        return self._with_extras(other)

    def _with_extras(self, other: "DesignError") -> "DesignError":
        """``other`` carrying what this error carries besides its line (e.g. a remedy)."""
        for key, value in vars(self).items():
            if key not in vars(other):
                setattr(other, key, value)
        return other


#: How an error's limit says that its value is a default nobody gave (the command line then
#: does not mark it again).
NONE_GIVEN = "(none given)"


def tie_context(param: str, shown_value: str) -> str:
    """How an error restated for another input names the parameter its rule is about
    (:meth:`DesignError.tied_to`): ``with it, backlash = 0.239 fails``."""
    return f"with it, {param.replace('_', '-')} = {shown_value} fails"


def offered_remedies(err: Exception) -> list[dict]:
    """Every remedy (name -> value) a refusal offers, in the order its line says them: its
    ``remedies`` when it offers more than one, else its ``remedy``; none for a refusal without."""
    remedy, remedies = getattr(err, "remedy", None), list(getattr(err, "remedies", None) or [])
    if remedy and remedies[:1] != [remedy]:
        return [remedy]     # a remedy set since the alternatives were: the line says that one
    return remedies or [r for r in [remedy] if r]


#: Where a refusal's cause ends (its advice follows).
NOTHING_WRITTEN = "; nothing written"


class CheckRefused(Exception):
    """A check of good input that refuses to write its result (the CLI exits 1: a failed
    check, not bad input), e.g. teeth that interfere; ``remedy`` (name -> value) what writes it
    anyway or fixes it, for a script to read."""

    def __init__(self, text: str, remedy: dict | None = None):
        self.remedy = dict(remedy or {})
        super().__init__(text)


class MeshDefect(Exception):
    """A solid wheelstep built that fails its own check before writing (manifold, watertight,
    volume): wheelstep's defect, not the input's. Not a :class:`DesignError`: no input is
    named or blamed, the CLI exits 1 (a failed check), a sweep counts the point as failed."""

    def __init__(self, part: str, what: str):
        self.part = part
        super().__init__(f"the {part} mesh {what}; nothing written (a defect of wheelstep, not of "
                         "the input: please report the command line)")


def format_value(value: object) -> str:
    """A value as an error shows it and an option takes it: floats in the shortest form,
    a named choice (an Enum) as its word, a switch as on or off."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, Enum):
        return str(value.value)
    return str(value)


def counted(number: int, one: str, many: str) -> str:
    """``number`` and the noun in the right number: 1 part, 2 parts."""
    return f"{number} {one if number == 1 else many}"


def rounded_down(limit: float, places: int = 2) -> str:
    """An upper limit printed to ``places`` decimals, rounded down: a value the user copies
    from the line then passes (rounded to nearest, 64.534 showed as 64.53 but 64.536 as 64.54,
    which fails)."""
    return _rounded(limit, places, math.floor)


def rounded_up(limit: float, places: int = 2) -> str:
    """A lower limit printed to ``places`` decimals, rounded up (see :func:`rounded_down`)."""
    return _rounded(limit, places, math.ceil)


def _rounded(limit: float, places: int, direction) -> str:
    scale = 10.0 ** places
    return f"{direction(limit * scale) / scale:.{places}f}"


def require(condition: bool, param: str, value: object, limit: str) -> None:
    """Raise :class:`DesignError` unless ``condition`` holds."""
    if not condition:
        raise DesignError(param, value, limit)


class Interrupted(Exception):
    """A run stopped by Ctrl-C that says what it leaves behind (the rows merged so far): the
    CLI prints this line in place of its bare 'aborted' and exits 130. Not a
    KeyboardInterrupt, which the command framework would turn into a silent exit code."""


def file_problem(path, err: OSError | None = None) -> str:
    """Why the file at ``path`` cannot be read, in a refusal's words: a folder, no such file,
    or what the system said (``err``)."""
    path = Path(path)
    if path.is_dir():
        return "is a folder, not a file"
    if path.is_symlink() and not path.exists():
        return f"is a link to {os.readlink(path)}, which does not exist"
    if not path.exists():
        return "no such file"
    return f"cannot be read ({err.strerror or err})" if err is not None else "cannot be read"
