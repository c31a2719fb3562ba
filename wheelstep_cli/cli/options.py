"""Option declarations shared by the commands, and parsers of option text.

Each option is declared once here as an ``Annotated`` type; a command names it in its
signature (``a: A = None``). Defaults are shown in one style everywhere,
``[default: 48]``: Typer prints it for options with a concrete default, and
:func:`opt` appends it to the help of options whose default is ``None`` (filled from a
profile or the built-in design).
"""

from __future__ import annotations

import math
import os
from enum import Enum
from pathlib import Path
from typing import Annotated, Optional

import numpy as np
import typer

from wheelstep_cli.config.printers import Fit
from wheelstep_cli.errors import DesignError, require


#: Largest magnitude any number option takes (mm, m, deg, rpm, ...): far beyond every real
#: design, and small enough that no computation downstream overflows.
MAX_MAGNITUDE = 1e6


def finite(ctx: typer.Context, param: typer.CallbackParam, value):
    """Refuse NaN, infinities and absurd magnitudes in any number option, so no rule downstream
    has to meet them."""
    numbers = value if isinstance(value, (list, tuple)) else [value]
    for number in numbers:
        if isinstance(number, float):
            _check_number(number, param.name)
    return value


def _check_number(number: float, param: str) -> None:
    require(math.isfinite(number) and abs(number) <= MAX_MAGNITUDE, param, number,
            f"must be a finite number of magnitude at most {MAX_MAGNITUDE:g}")


def opt(*names: str, help: str, shown: str | None = None, **kwargs):
    """A ``typer.Option`` whose numbers must be finite; ``shown`` is the default to print for an
    option defaulting to None."""
    text = help if shown is None else f"{help}  [default: {shown}]"
    kwargs.setdefault("callback", finite)
    # a choice typed in capitals (--format STL) is the choice: file extensions are often written so
    kwargs.setdefault("case_sensitive", False)
    return typer.Option(*names, help=text, **kwargs)


class MeshFormat(str, Enum):
    """Which mesh files a part command writes."""

    stl = "stl"
    threemf = "3mf"
    both = "both"


# --- the crank mechanism (SPEC §2), mm
A = Annotated[Optional[float], opt("--a", help="Hub axis to crank axes, mm.", shown="60")]
B = Annotated[Optional[float], opt("--b", help="Crank length, mm.", shown="100")]
C = Annotated[Optional[float], opt("--c", help="Shoe strut length, mm.",
                                   shown="R_min - a + 4b = 360")]
RMin = Annotated[Optional[float], opt("--rmin", "--r-min",
                                      help="Smallest sole curvature radius R_min = a - 4b + c, "
                                           "mm; sizes c.", shown="20")]
# --- the gear pair
Z = Annotated[Optional[int], opt("--z", help="Pinion tooth count; the wheel gets z*n.",
                                 shown="48")]
Turns = Annotated[Optional[int], opt("--turns", "-n", help="Pinion turns per carrier turn, 2 or 4.",
                                     shown="the profile's gears.turns, else 2")]
CenterDistance = Annotated[Optional[float], opt(
    "--center-distance", help="Centre distance the pitch curves roll at, mm (generated teeth; "
                              "paper teeth: the sectors' L_p).",
    shown="the installed distance; paper 0.5 less, 143.5")]
# --- where values and files come from and go
Blend = Annotated[Optional[float], opt(
    "--blend", help="Half-width (carrier deg) of the ratio blend at each handover: the law the "
                    "teeth are cut for and checked against (generated teeth).", shown="0")]
LawCsv = Annotated[Optional[Path], opt(
    "--law-csv", help="CSV of driving angle, driven angle (deg) over one period: this law instead "
                      "of the crank law (generated teeth).")]
Profile = Annotated[Optional[str], opt("--profile",
                                       help="Design preset: a name in profiles/ or a YAML path.")]
Printer = Annotated[Optional[str], opt(
    "--printer", help="Printer profile (a name in profiles/ or a YAML path): draw the part as it "
                      "must be printed there (holes + hole compensation, gear teeth + tooth "
                      "clearance, elephant-foot inset or its edge chamfer), as batch does.",
    shown="none: the geometry as designed")]
Out = Annotated[Path, opt("--out", "-o", help="Output folder.")]
AllowInterference = Annotated[bool, opt(
    "--allow-interference", help="Write the pair even if the meshing check finds overlapping "
                                 "teeth (the paper method's pair does, at the shoe handovers).")]
Force = Annotated[bool, opt("--force", help="Overwrite files at the paths it writes (in its "
                                            "output folder, if it has one, and the files named "
                                            "by its options) that wheelstep did not write or "
                                            "that were changed since (refused otherwise).")]
Tolerance = Annotated[bool, opt(
    "--tolerance", help="Also run the meshing check over the printer's dimensional band (SPEC "
                        "§11): grown and shrunk outlines at the band's centre distances.")]
FitChoice = Annotated[Optional[Fit], opt(
    "--fit", help="Draw both tooth outlines smaller along their normals (instead of the "
                  "printer's tooth clearance), just enough that the least backlash over its band "
                  "keeps the fit's margin (auto 0.01, tight 0.05, normal 0.1, loose 0.2 mm); "
                  "implies --tolerance. Drawn for --printer, else the default printer (its "
                  "compensation too).", shown="the printer band's fit, else its clearance")]
Format = Annotated[MeshFormat, opt("--format", help="Mesh files to write.")]
# --- conventions of every command
Json = Annotated[bool, opt("--json", help="Print the report as one JSON document on stdout "
                                          "(nothing else goes to stdout).")]
DryRun = Annotated[bool, opt("--dry-run", help="Compute and check, write nothing; say what "
                                               "would be written.")]
Quiet = Annotated[bool, opt("--quiet", "-q", help="Print nothing but errors (and the --json "
                                                  "document when asked for).")]
Verbose = Annotated[bool, opt("--verbose", "-v", help="Print more detail (on stderr): the "
                                                      "resolved parameters and every file.")]


def _suffix_check(suffixes: tuple[str, ...]):
    """A callback refusing a file path whose extension is none of ``suffixes`` (".png"): the
    file is written in that format whatever its name, so another name would mislabel it."""
    def check(ctx: typer.Context, param: typer.CallbackParam, value):
        if value is not None:
            require(value.suffix.lower() in suffixes, param.name, str(value),
                    f"must end in {' or '.join(suffixes)} (the extension sets the format)")
        return value
    return check


def output_file(flag: str, help: str, *suffixes: str):
    """An optional output-file option whose path must end in one of ``suffixes``."""
    return Annotated[Optional[Path], opt(flag, help=help, callback=_suffix_check(suffixes))]


def plot_option(what: str):
    """A ``--plot PNG`` option: ``what`` the picture shows."""
    return output_file("--plot", f"Write {what} (PNG).", ".png")


def csv_option(what: str):
    """A ``--csv FILE`` option: ``what`` the table holds."""
    return output_file("--csv", f"Write {what} (CSV).", ".csv")


def require_with(param: str, value, companion, flag: str) -> None:
    """Refuse option ``param`` given (``value`` not None) without the ``companion`` option's
    value it shapes (None: not given): it would do nothing. ``flag``: the companion's flag
    (e.g. "--dxf")."""
    if value is not None and companion is None:
        raise DesignError(param, value, f"shapes {flag}: give {flag} too")


def require_a_file(dry_run: bool, force: bool, **named) -> None:
    """Refuse --dry-run or --force where none of the file options ``named`` (option name ->
    path, None: not given) is given: the command then writes nothing, so either would do
    nothing."""
    if any(path is not None for path in named.values()):
        return
    flags = " or ".join(f"--{name.replace('_', '-')}" for name in named)
    for param, given in (("dry_run", dry_run), ("force", force)):
        if given:
            raise DesignError(param, "on", f"acts on the files the command writes, and without "
                                           f"{flags} it writes none")


def require_printed(param: str, value, unprinted: bool, what: str) -> None:
    """Refuse option ``param`` given (``value`` not None) that shapes the printed ``what``
    where none is printed (``unprinted``: -q without --json): it would do nothing."""
    if value is not None and unprinted:
        raise DesignError(param, value, f"shapes the printed {what}, which -q does not print (--json does)")


def _plain_float(text: str) -> float:
    """``float(text)``, refusing (ValueError) the underscores Python reads as digit groups."""
    if "_" in text:
        raise ValueError(text)
    return float(text)


def number_list(text: str, param: str) -> list[float]:
    """``"a,b,c"`` or ``"start:stop:step"`` (inclusive) to floats."""
    try:
        if ":" in text:
            start, stop, step = (_plain_float(v) for v in text.split(":"))
            for number in (start, stop, step):
                _check_number(number, param)
            require(step > 0, param, text, "step must be > 0")
            steps = (stop - start) / step      # inf for a step of 1e-320: too many to count
            require(math.isfinite(steps) and 0 <= steps < 10000, param, text, "must give 1 to 10000 values")
            n = int(np.floor(steps + 1e-9)) + 1
            return [start + i * step for i in range(n)]
        items = text.split(",")
        # an empty item is a typo (a value left out), and a list of none gives an empty table
        require(all(v.strip() for v in items), param, text,
                "has an empty value between commas: list numbers 'a,b,c' or give 'start:stop:step'")
        values = [_plain_float(v) for v in items]
        for number in values:
            _check_number(number, param)
        return values
    except DesignError:
        raise
    except ValueError:
        raise DesignError(param, text, "must be numbers 'a,b,c' or 'start:stop:step'"
                          + (", written without underscores" if "_" in text else "")) from None


def point(text: str, param: str) -> tuple[float, float]:
    """``"x,y"`` (mm) to a pair of floats."""
    try:
        x, y = (_plain_float(v) for v in text.split(","))
    except ValueError:
        raise DesignError(param, text, "must be 'x,y' in mm" + (", written without underscores"
                                                                 if "_" in text else "")) from None
    _check_number(x, param)
    _check_number(y, param)
    return x, y


def signs(items: list[str], param: str) -> dict[str, int]:
    """``["NAME=+1", "OTHER=-1"]`` to ``{"NAME": 1, "OTHER": -1}``; a name given twice is
    refused (one of its signs would be dropped unsaid)."""
    out, typed = {}, {}
    for item in items:
        name, _, sign = item.partition("=")
        require(sign in ("+1", "1", "-1"), param, item, "must be NAME=+1 or NAME=-1")
        require(name not in out, param, item, f"gives joint {name} again ({typed.get(name)} before "
                                              "it); give each joint once")
        out[name], typed[name] = int(sign), item
    return out


#: Most worker processes (``batch --jobs``, ``sweep --workers``) per CPU core: each is a
#: Python process with the gear libraries loaded (a few hundred MB), and more than this
#: only wait their turn.
WORKERS_PER_CORE = 4


def require_workers(param: str, count: int, zero: str) -> None:
    """Refuse ``count`` worker processes outside 0..WORKERS_PER_CORE per CPU core of this
    machine (DesignError naming ``param``); ``zero`` says what 0 means."""
    most = WORKERS_PER_CORE * (os.cpu_count() or 1)
    require(0 <= count <= most, param, count,
            f"must be 0..{most} ({WORKERS_PER_CORE} per CPU core of this machine; 0: {zero})")
