"""The catalogue of PrusaSlicer's option names and value kinds, read off the installed slicer.

PrusaSlicer states its options twice: ``--save FILE.ini`` writes every key of a technology's
configuration with its default, and ``--help-fff`` / ``--help-sla`` describe each option
(its argument, its choices, its unit). Both together give, per key, the kind of value it
takes; the result is the package's ``config/prusa_options.json``, which checks a printer
profile's ``slicer:`` section without the slicer installed. Regenerate after moving to
another PrusaSlicer release (a test compares the file with the installed slicer)::

    python -m tests.helpers.prusa_options --update
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

CATALOGUE = Path(__file__).resolve().parents[2] / "wheelstep_cli" / "config" / "prusa_options.json"

#: An option's first help line: its flag, its argument (N, ABCD or none) and the text after it.
_OPTION = re.compile(r"^ --([a-z0-9-]+)(?:,[^ ]*)*(?: ([A-Z]+))?(?:\s+(.*))?$")
#: The closing parenthesis of a help text: what comes before "default:" (choices or a unit).
_CLOSING = re.compile(r"\(([^()]*?)(?:;|,)?\s*default: ?[^()]*\)\s*$")
_NUMBER = re.compile(r"^-?\d+(\.\d+)?$")


def _help(technology: str) -> dict[str, tuple[str | None, str]]:
    """flag (as a config key) -> (argument, whole help text) of ``prusa-slicer --help-<tech>``."""
    text = subprocess.run(["prusa-slicer", f"--help-{technology}"], capture_output=True, text=True,
                          check=True).stdout
    options: dict[str, tuple[str | None, str]] = {}
    key = None
    # the configuration's options follow the actions and the command line's own options
    text = text[text.index("Print options are processed"):]
    for line in text.splitlines():
        found = _OPTION.match(line)
        if found:
            key = found.group(1).replace("-", "_")
            options[key] = (found.group(2), found.group(3) or "")
        elif key is not None and line.startswith(" " * 21):
            arg, body = options[key]
            options[key] = (arg, f"{body} {line.strip()}")
        elif not line.strip() or not line.startswith(" "):
            key = None
    return options


def _defaults(technology: str) -> dict[str, str]:
    """key -> default value of every key ``prusa-slicer --save`` writes for the technology."""
    with tempfile.TemporaryDirectory() as folder:
        ini = Path(folder) / "defaults.ini"
        subprocess.run(["prusa-slicer", "--printer-technology", technology.upper(), "--save", str(ini)],
                       capture_output=True, check=True)
        lines = ini.read_text(encoding="utf-8").splitlines()
    return dict(line.split(" = ", 1) for line in lines if " = " in line and not line.startswith("#"))


def _kind(default: str, arg: str | None, body: str):
    """The kind of value a key takes as its help states it: ``["enum", choices...]``, "bool",
    "percent", "number" (told apart further by :func:`_refined`) or "text" (anything;
    PrusaSlicer reads it as it is)."""
    closing = _CLOSING.search(body)
    inside = closing.group(1).strip() if closing else ""
    words = [w.strip() for w in inside.split(",")]
    if arg is None and len(words) > 1 and all(re.fullmatch(r"[a-z0-9_-]+", w) for w in words):
        return ["enum", *words]
    if arg is None and default in ("0", "1"):
        return "bool"
    if arg == "ABCD":
        return "text"
    if default.endswith("%") or "%" in inside:
        return "percent"
    if arg == "N" and _NUMBER.match(default):
        return "number"
    return "text"


_OUT_OF_RANGE = re.compile(r"Value out of range: (\w+)|Invalid value for --([\w-]+)")


def _as_saved(technology: str, keys, value: str = "") -> dict[str, str | None]:
    """What ``prusa-slicer --load`` of ``keys`` all set to ``value`` (or a dict key -> its own
    value) saves for each, None for a
    key whose range refuses the value (the slicer names one such key a run; it is left out and
    the rest loaded again). It rounds a whole-number option's 2.5 to 2 and drops the % of an
    option that takes no percentage, without a word."""
    values = dict(keys) if isinstance(keys, dict) else dict.fromkeys(keys, value)
    keys, refused = list(values), {}
    with tempfile.TemporaryDirectory() as folder:
        given, saved = Path(folder) / "given.ini", Path(folder) / "saved.ini"
        while True:
            given.write_text("".join(f"{key} = {values[key]}\n" for key in keys), encoding="utf-8")
            done = subprocess.run(["prusa-slicer", "--printer-technology", technology.upper(), "--load",
                                   str(given), "--save", str(saved)], capture_output=True, text=True)
            if done.returncode == 0:
                break
            bad = _OUT_OF_RANGE.search(done.stdout + done.stderr)
            key = None if bad is None else (bad.group(1) or bad.group(2).replace("-", "_"))
            if key is None and len(keys) == 1:
                key = keys[0]       # a rule of the value with the defaults (100 % of a fill pattern)
            if key not in keys:
                raise RuntimeError(f"prusa-slicer refused the probe: {(done.stdout + done.stderr)[-500:]}")
            keys.remove(key)
            refused[key] = None
            if not keys:
                return refused
        lines = saved.read_text(encoding="utf-8").splitlines()
    found = dict(line.split(" = ", 1) for line in lines if " = " in line and not line.startswith("#"))
    return {**refused, **{key: found.get(key, "") for key in keys}}


def _refined(technology: str, kinds: dict) -> dict:
    """``kinds`` with each number told apart as the slicer reads it: "integer" (a whole
    number, 2.5 read as 2), "share" (a percentage, or a plain number read as a fraction:
    fill_density 0.3 is 30 %), "percent" (a number, or a percentage of another setting where
    the help says so) or "number"; each as ``[kind, least]`` when the slicer's range refuses -1
    (``least`` 0) and ``[kind, least, 100]`` when it refuses 101 (101 % for a share)."""
    numbers = [key for key, kind in kinds.items() if kind in ("number", "percent")]
    halves = _as_saved(technology, numbers, "2.5")
    small = _as_saved(technology, [k for k in numbers if halves[k] is None], "0.5")
    negative = _as_saved(technology, numbers, "-1")
    for key in numbers:
        half = halves[key] if halves[key] is not None else small.get(key)
        # a percentage only where the help says so: --save keeps '75%' of first_layer_height,
        # which slicing then reads as 75 mm
        if half in ("2", "0"):
            kind = "integer"
        elif kinds[key] == "percent":
            kind = "share" if (half or "").endswith("%") else "percent"
        else:
            kind = "number"
        kinds[key] = [kind] if negative[key] is not None else [kind, 0]
    for key, most in _greatest(technology, {k: kinds[k][0] for k in numbers}).items():
        kinds[key] = [kinds[key][0], kinds[key][1] if len(kinds[key]) > 1 else None, most]
    # (a least of None: the range refuses no negative value, only too large a one)
    return {key: kind[0] if isinstance(kind, list) and len(kind) == 1 else kind for key, kind in kinds.items()}


def _greatest(technology: str, kinds: dict[str, str]) -> dict[str, float]:
    """The greatest value the slicer's range takes of each number option that refuses 101
    (101 % for a share), found by bisection: a whole number for an integer option, to
    0.001 else; a share's as a percentage."""
    unit = {key: "%" if kind == "share" else "" for key, kind in kinds.items()}
    over = _as_saved(technology, {key: f"101{unit[key]}" for key in kinds})
    lo = {key: 0.0 for key, saved in over.items() if saved is None}
    hi = {key: 101.0 for key in lo}
    for _ in range(20):
        for key in lo:
            # one key a run: a refusal of a rule of several values names none of them
            mid = (lo[key] + hi[key]) / 2.0
            saved = _as_saved(technology, {key: f"{mid:.6f}{unit[key]}"})
            (lo if saved[key] is not None else hi)[key] = mid
    return {key: float(np.floor(lo[key] + 1e-6)) if kinds[key] == "integer" else round(lo[key], 3)
            for key in lo}


#: The bookkeeping keys of PrusaSlicer's presets (which preset, inherited from which, for
#: which printer), read and kept by --load but listed by neither --save nor the help.
PRESET_KEYS = ("inherits", "print_settings_id", "filament_settings_id", "printer_settings_id",
               "sla_print_settings_id", "sla_material_settings_id", "compatible_printers",
               "compatible_printers_condition", "compatible_prints", "compatible_prints_condition",
               "physical_printer_settings_id", "printer_vendor", "printer_variant")


def catalogue() -> dict:
    """The catalogue as the installed PrusaSlicer states it (see the module's docstring)."""
    version = subprocess.run(["prusa-slicer", "--help"], capture_output=True, text=True,
                             check=True).stdout.splitlines()
    release = next(line.split(" ")[0] for line in version if line.startswith("PrusaSlicer-"))
    out: dict = {"source": f"{release}: --save (every key, its default) and --help-fff/--help-sla"}
    for technology in ("fff", "sla"):
        described, defaults = _help(technology), _defaults(technology)
        # --save leaves out options without a value (a filament's retraction overrides), the
        # help the presets' bookkeeping keys: each is one PrusaSlicer reads
        keys = sorted(set(defaults) | set(described))
        kinds = _refined(technology, {key: _kind(defaults.get(key, ""), *described.get(key, (None, "")))
                                      for key in keys})
        out[technology] = {**kinds, **{key: "text" for key in PRESET_KEYS if key not in kinds}}
    return out


def main() -> None:
    if sys.argv[1:] != ["--update"]:
        sys.exit("usage: python -m tests.helpers.prusa_options --update")
    CATALOGUE.write_text(json.dumps(catalogue(), indent=1, sort_keys=True) + "\n", encoding="utf-8")
    print(f"wrote {CATALOGUE}")


if __name__ == "__main__":
    main()
