"""Run one fuzz invocation in a subprocess and check what it did."""

from __future__ import annotations

import hashlib
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

from tests.fuzz.cases import Invocation

ROOT = Path(__file__).resolve().parents[2]
TIMEOUT = 120.0
MEMORY = 6 << 30            # bytes of address space: a run that needs more is a finding
USER_TEXT = b"a file of the user's: never to be touched\n"


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))


def _setup(folder: Path, inv: Invocation) -> None:
    for name, data in inv.files.items():
        (folder / name).write_bytes(data)
    (folder / "notes.txt").write_bytes(USER_TEXT)
    out = folder / "out"
    if inv.out_setup == "user-file":
        out.mkdir()
        (out / "notes.txt").write_bytes(USER_TEXT)
    elif inv.out_setup == "file-as-folder":
        out.mkdir()
        for name in ("gears.json", "shoe.json", "manifest.json", "k.png", "k.csv"):
            (out / name).mkdir()
    elif inv.out_setup == "read-only":
        out.mkdir()
        (out / "notes.txt").write_bytes(USER_TEXT)
        out.chmod(0o555)
    elif inv.out_setup == "manifest-claim":
        out.mkdir()
        (out / "notes.txt").write_bytes(USER_TEXT)
        (out / "manifest.json").write_text(json.dumps({"outputs": {"notes.txt": "x"}}))


def _snapshot(folder: Path) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in folder.rglob("*") if p.is_file()}


def check(inv: Invocation) -> list[str]:
    """Run ``inv`` in a fresh folder; return what went wrong (empty: nothing)."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        _setup(folder, inv)
        before = _snapshot(folder)
        env = dict(os.environ, PYTHONPATH=str(ROOT), COLUMNS="200")
        try:
            run = subprocess.run([sys.executable, "-m", "wheelstep_cli", *inv.args], cwd=folder,
                                 capture_output=True, text=True, timeout=TIMEOUT, env=env,
                                 preexec_fn=_limit_memory, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            return [f"timeout after {TIMEOUT:g} s"]
        finally:
            if (folder / "out").is_dir():
                (folder / "out").chmod(0o755)
        return _findings(inv, run, folder, before)


def _findings(inv: Invocation, run, folder: Path, before: dict[str, str]) -> list[str]:
    found = []
    after = _snapshot(folder)
    if "Traceback" in run.stderr or "MemoryError" in run.stderr:
        found.append("traceback: " + run.stderr.strip().splitlines()[-1][:200])
    if run.returncode not in (0, 1, 2):
        found.append(f"exit code {run.returncode}")
    for name, digest in before.items():
        if after.get(name) != digest:
            found.append(f"touched a file it did not write: {name}")
    if any(name.endswith(".part") for name in after):
        found.append("left a temporary .part file")
    if run.returncode == 2:
        lines = run.stderr.strip().splitlines()
        if not lines or not all(line.startswith("wheelstep: error") for line in lines):
            found.append("refusal is not 'wheelstep: error' lines: " + run.stderr.strip()[:200])
        if set(after) != set(before):
            found.append("refused but wrote: " + ", ".join(sorted(set(after) - set(before))))
        for line in lines:
            if line.startswith("wheelstep: error") and not names_a_given_parameter(line, inv.args):
                found.append("refusal names no parameter the user gave: " + line[:200])
    if run.returncode == 0 and "--json" in inv.args:
        try:
            json.loads(run.stdout, parse_constant=_no_constant)
        except ValueError as err:
            found.append(f"--json output is not valid JSON ({err})")
    for name in sorted(set(after) - set(before)):
        if name.endswith(".stl") and run.returncode == 0:
            found.extend(_mesh_findings(folder / name))
    return found


_PREFIX = re.compile(r"^wheelstep: error(?: \([^)]*\))?: ")
_FLAG = re.compile(r"(?<![\w-])(--?[A-Za-z][\w-]*)")
_FILE_PLACE = re.compile(r"^([^\s:=]+)(?::\d+)?:")
#: Click's own words for a parameter that is missing (naming it is right: the user did not give it)
_MISSING = ("Missing argument", "Missing option", "Got unexpected extra argument")
#: The commands' arguments by name, in order (the words after the command, before any flag)
ARGUMENTS = {"mesh-check": ["pinion", "wheel"], "batch": ["file"]}
#: Options whose value is a file read (its errors may name it with ``file:line``)
FILE_OPTIONS = ("--profile", "--law-csv")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _typed(args: list[str]) -> dict[str, list[str]]:
    """flag -> the values typed after it (``--x v`` or ``--x=v``; a flag alone: no value);
    a negative number is a value, not a flag."""
    flags: dict[str, list[str]] = {}
    for i, arg in enumerate(args):
        if not arg.startswith("-") or _is_number(arg):
            continue
        flag, eq, value = arg.partition("=")
        follows = args[i + 1] if i + 1 < len(args) else None
        given = value if eq else follows if follows is not None and (
            not follows.startswith("-") or _is_number(follows)) else None
        flags.setdefault(flag, []).extend([] if given is None else [given])
    return flags


def _same_value(shown: str, typed: list[str]) -> bool:
    """Whether the value a refusal shows is one the user typed (numbers compared as numbers,
    as %g prints them; a printer-compensated value shows the typed one first)."""
    shown = shown.split(" (", 1)[0].strip("'\"")
    if not typed or shown in typed:
        return True
    try:
        number = float(shown)
    except ValueError:
        return False
    for value in typed:
        try:
            other = float(value)
        except ValueError:
            continue
        # %g's rounding; and a value that is zero to a billionth (5e-324 deg, as radians and
        # back) shown as 0
        if number == other or (number != number and other != other) or (
                abs(number - other) <= max(1e-5 * max(abs(number), abs(other)), 1e-9)):
            return True
    return False


def names_a_given_parameter(line: str, args: list[str]) -> bool:
    """Whether the refusal ``line`` names what the user gave: a flag they typed with the
    value they typed (``--x = v``, Click's ``'--x'``), a file they gave with its place
    (``p.yaml:3: key = ...``), or an argument by its name with the value typed in its place
    (``pinion = x.stl``)."""
    text = _PREFIX.sub("", line, count=1)
    typed = _typed(args)
    if text.startswith(_MISSING):
        return True
    arguments = dict(zip(ARGUMENTS.get(args[0], []) if args else [],
                         [a for a in args[1:3] if not a.startswith("-")]))
    name, eq, rest = text.partition(" = ")
    if eq and " " not in name:
        shown = rest.partition(": ")[0]
        if name in typed:
            return _same_value(shown, typed[name])
        if name in arguments:
            return shown == arguments[name]                # an argument: pinion = x.stl
    files = set(arguments.values()) | {v for flag in FILE_OPTIONS for v in typed.get(flag, [])}
    place = _FILE_PLACE.match(text)
    if place and place.group(1) in files:
        return True                                       # p.yaml:1: gears.z = '48': ...
    head = name if eq and " " not in name else text
    return any(flag in typed for flag in _FLAG.findall(head))


def _no_constant(name: str):
    raise ValueError(f"{name} is not JSON")


def _mesh_findings(path: Path) -> list[str]:
    import trimesh

    mesh = trimesh.load(path, force="mesh", process=True)
    ok = (mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
          and len(mesh.split(only_watertight=False)) == 1)
    return [] if ok else [f"invalid mesh written: {path.name}"]
