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
    """The kind of value a key takes: ``["enum", choices...]``, "bool", "percent", "number"
    or "text" (anything; PrusaSlicer reads it as it is)."""
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


def catalogue() -> dict:
    """The catalogue as the installed PrusaSlicer states it (see the module's docstring)."""
    version = subprocess.run(["prusa-slicer", "--help"], capture_output=True, text=True,
                             check=True).stdout.splitlines()
    release = next(line.split(" ")[0] for line in version if line.startswith("PrusaSlicer-"))
    out: dict = {"source": f"{release}: --save (every key, its default) and --help-fff/--help-sla"}
    for technology in ("fff", "sla"):
        described = _help(technology)
        out[technology] = {key: _kind(default, *described.get(key, (None, "")))
                           for key, default in sorted(_defaults(technology).items())}
    return out


def main() -> None:
    if sys.argv[1:] != ["--update"]:
        sys.exit("usage: python -m tests.helpers.prusa_options --update")
    CATALOGUE.write_text(json.dumps(catalogue(), indent=1, sort_keys=True) + "\n", encoding="utf-8")
    print(f"wrote {CATALOGUE}")


if __name__ == "__main__":
    main()
