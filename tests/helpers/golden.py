"""Golden figures: the key outputs of every preset and a few designs, kept in tests/golden/.

Each case runs one command of the real CLI in a fresh folder (in a child process whose numpy
kernels are capped at one SIMD level, :data:`SIMD_CAP`, so that numpy's choice of kernels by
CPU does not move the hashes; the other libraries' own CPU paths are not capped) and records
its exit code,
the SHA-256 and size of every file it wrote, the SHA-256 of what it printed on stdout
(for the report commands) and the numeric figures of every JSON file it wrote (flattened
to ``file:key.path`` -> value). The golden test compares a new run with the stored one:
hashes exactly, figures to 1e-9 relative, so a refactor that changes an output shows
which figure moved and by how much. Each record notes the CPU kind it was made on
(:func:`cpu_kind`): on another kind some library's own CPU paths tessellate a mesh a little
differently (the shop-floor wheel 0.09 % more triangles, volumes 2e-8 apart on an AVX-512
machine against an AVX2 one), so there the bytes are not compared and the figures are, to
:data:`CROSS_CPU_REL` (counts to :data:`CROSS_CPU_COUNT_REL`).

Regenerate after an intended change (and list it in the change's note)::

    python -m tests.helpers.golden --update
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

GOLDEN_DIR = Path(__file__).resolve().parents[1] / "golden"
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

#: name -> command line (relative paths are resolved in the case's own folder).
CASES: dict[str, list[str]] = {
    "gears-default": ["gears", "--z", "48", "--out", "out"],
    "gears-desk-demo": ["gears", "--profile", "desk-demo", "--out", "out"],
    "gears-z24": ["gears", "--z", "24", "--out", "out"],
    "gears-turns4-z32": ["gears", "--turns", "4", "--z", "32", "--out", "out"],
    "gears-paper": ["gears", "--teeth", "paper", "--allow-interference", "--out", "out"],
    "shoe-default": ["shoe", "--out", "out"],
    "shoe-desk-demo": ["shoe", "--profile", "desk-demo", "--out", "out"],
    "batch-shop-floor": ["batch", "{examples}/shop-floor.yaml", "--out", "out", "--jobs", "1"],
    "batch-resin": ["batch", "{golden}/resin-batch.yaml", "--out", "out", "--jobs", "1"],
    "pitch-json": ["pitch", "--json"],
    "teeth-json": ["teeth", "--json"],
    "kinematics-json": ["kinematics", "--json"],
    "stairs-json": ["stairs", "--run", "300", "--rise", "150", "--sole-radius", "70",
                    "--landing-angle", "-90", "--json"],
    "linkage-jansen-json": ["linkage", "--preset", "jansen", "--json"],
    "trajectory-json": ["trajectory", "-H", "300", "--r1", "20", "--r2", "45", "--h-max", "120",
                        "--json"],
}

#: The libraries whose floating-point results reach the written bytes: a golden record notes
#: their versions, since another release may move a mesh vertex by one ulp (constraints.txt pins
#: them for the test command).
NUMERIC_LIBRARIES = ("numpy", "scipy", "shapely", "manifold3d", "trimesh")

#: Lists longer than this (sector tables, paths) are hashed with the file, not flattened.
LONG_LIST = 40


#: Figures compared across CPU kinds: floats to this relative difference (a mesh's volume moves
#: by 2e-8, a mass estimated from it by 3e-7), ...
CROSS_CPU_REL = 1e-5
#: ... and whole numbers above 100 (a mesh's triangles) to this.
CROSS_CPU_COUNT_REL = 0.01


def cpu_kind() -> str:
    """numpy's name of the widest SIMD level this CPU runs (``AVX512_SPR``, ``AVX2``, ...), the
    machine's architecture where numpy names none."""
    import platform

    try:
        from numpy._core._multiarray_umath import __cpu_features__
    except ImportError:
        return platform.machine()
    levels = ("AVX512_SPR", "AVX512_ICL", "AVX512_CNL", "AVX512_CLX", "AVX512_SKX", "AVX512_KNM",
              "AVX512_KNL", "AVX512F", "AVX2", "AVX", "SSE42", "ASIMD", "VSX")
    return next((level for level in levels if __cpu_features__.get(level)), platform.machine())


def _flatten(value, prefix: str, out: dict) -> None:
    if isinstance(value, dict):
        for key, item in value.items():
            _flatten(item, f"{prefix}.{key}" if prefix else str(key), out)
    elif isinstance(value, list):
        if len(value) <= LONG_LIST:
            for i, item in enumerate(value):
                _flatten(item, f"{prefix}[{i}]", out)
    elif isinstance(value, bool) or value is None:
        out[prefix] = value
    elif isinstance(value, (int, float)):
        out[prefix] = value


def library_versions() -> dict[str, str]:
    """name -> installed version of each of :data:`NUMERIC_LIBRARIES`."""
    from importlib.metadata import version

    return {name: version(name) for name in NUMERIC_LIBRARIES}


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


#: numpy's widest SIMD kernels the cases run with. numpy picks its kernels by the CPU at run time,
#: and its AVX-512 ones (sin, cos, arctan2, ...) round some results differently in the last
#: bit, which moves mesh vertices by an ulp: the records are made and checked capped at the
#: AVX2 level (x86-64-v3) so their hashes hold on every machine that has it.
SIMD_CAP = "X86_V3"


def _capped_env() -> dict[str, str]:
    """This process's environment with numpy's run-time kernels above :data:`SIMD_CAP` off
    (numpy 2.4 names its x86 levels so; another numpy runs uncapped, as constraints.txt does
    not install one)."""
    env = dict(os.environ)
    try:
        from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    except ImportError:
        return env
    if SIMD_CAP in __cpu_dispatch__:
        above = __cpu_dispatch__[__cpu_dispatch__.index(SIMD_CAP) + 1:]
        wider = [f for f in above if __cpu_features__.get(f)]
        if wider:
            env["NPY_DISABLE_CPU_FEATURES"] = " ".join(wider)
    return env


def run_case(name: str) -> dict:
    """Run one case in a fresh temporary folder, in a child process with numpy capped at
    :data:`SIMD_CAP`, and return its record."""
    root = str(Path(__file__).resolve().parents[2])
    env = {**_capped_env(), "PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))}
    with tempfile.TemporaryDirectory() as folder:
        record = Path(folder) / "record.json"
        done = subprocess.run([sys.executable, "-m", "tests.helpers.golden", "--record", name, str(record)],
                              env=env, cwd=root, capture_output=True, text=True, check=False, timeout=1800)
        if done.returncode != 0:
            raise RuntimeError(f"golden case {name} could not run: {done.stderr[-2000:]}")
        return json.loads(record.read_text())


def _record(name: str) -> dict:
    """Run one case in a fresh temporary folder (in this process) and return its record."""
    from wheelstep_cli.cli import run

    args = [a.replace("{examples}", str(EXAMPLES)).replace("{golden}", str(GOLDEN_DIR)) for a in CASES[name]]
    with tempfile.TemporaryDirectory() as tmp:
        cwd = os.getcwd()
        os.chdir(tmp)
        stdout, stderr = io.StringIO(), io.StringIO()
        try:
            with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
                code = run(args)
        finally:
            os.chdir(cwd)
        files, figures = {}, {}
        for path in sorted(Path(tmp).rglob("*")):
            if not path.is_file():
                continue
            rel = path.relative_to(tmp).as_posix()
            data = path.read_bytes()
            files[rel] = {"sha256": _sha(data), "bytes": len(data)}
            if rel.endswith(".json"):
                _flatten(json.loads(data), rel + ":", figures)
        text = stdout.getvalue()
        if args[-1] == "--json":
            _flatten(json.loads(text), "stdout:", figures)
        return {"args": CASES[name], "libraries": library_versions(), "cpu": cpu_kind(), "exit_code": code,
                "stdout_sha256": _sha(text.encode()) if args[-1] == "--json" else None, "files": files,
                "figures": figures}


def golden_path(name: str) -> Path:
    return GOLDEN_DIR / f"{name}.json"


def load(name: str) -> dict:
    return json.loads(golden_path(name).read_text())


def differences(stored: dict, new: dict, rel: float = 1e-9) -> list[str]:
    """What differs between two records, one line each (empty: identical): on the CPU kind
    the stored record was made on, bytes exactly and figures to ``rel``; on another, the files
    written and the figures to the cross-CPU tolerances."""
    same_cpu = stored.get("cpu") == new.get("cpu")
    lines = []
    if stored["exit_code"] != new["exit_code"]:
        lines.append(f"exit code {stored['exit_code']} -> {new['exit_code']}")
    if same_cpu and stored["stdout_sha256"] != new["stdout_sha256"]:
        lines.append("stdout changed")
    for name in sorted(set(stored["files"]) | set(new["files"])):
        old, now = stored["files"].get(name), new["files"].get(name)
        if (old != now) if same_cpu else (old is None or now is None):
            lines.append(f"file {name}: {old and old['sha256'][:12]} -> {now and now['sha256'][:12]}")
    for key in sorted(set(stored["figures"]) | set(new["figures"])):
        old, now = stored["figures"].get(key, "missing"), new["figures"].get(key, "missing")
        if not _same_figure(old, now, rel if same_cpu else None):
            lines.append(f"figure {key}: {old!r} -> {now!r}")
    if lines and not same_cpu:
        lines.insert(0, f"recorded on CPU kind {stored.get('cpu')}, run on {new.get('cpu')}: bytes not compared, "
                        f"figures to {CROSS_CPU_REL:g} (counts {CROSS_CPU_COUNT_REL:g})")
    if lines and stored.get("libraries") != new["libraries"]:
        lines.insert(0, f"recorded with {stored.get('libraries')}, run with {new['libraries']}: "
                        "install with `-c constraints.txt` as the README's test command does")
    return lines


def _same_figure(old, now, rel: float | None) -> bool:
    """Whether two figures agree: floats to ``rel`` (None: to the cross-CPU tolerances, whole
    numbers above 100 too), anything else exactly."""
    numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (old, now))
    if rel is None and numbers and all(isinstance(v, int) for v in (old, now)) and min(old, now) > 100:
        return math.isclose(old, now, rel_tol=CROSS_CPU_COUNT_REL)
    if numbers and isinstance(old, float) and isinstance(now, float):
        return math.isclose(old, now, rel_tol=CROSS_CPU_REL if rel is None else rel, abs_tol=1e-12)
    return old == now


def main(argv: list[str]) -> int:
    if argv[:1] == ["--record"]:
        Path(argv[2]).write_text(json.dumps(_record(argv[1])))
        return 0
    names = [a for a in argv if not a.startswith("--")] or list(CASES)
    if "--update" not in argv:
        print("usage: python -m tests.helpers.golden --update [CASE ...]")
        return 2
    GOLDEN_DIR.mkdir(exist_ok=True)
    for name in names:
        record = run_case(name)
        golden_path(name).write_text(json.dumps(record, indent=1, sort_keys=True) + "\n")
        print(f"{name}: exit {record['exit_code']}, {len(record['files'])} files, "
              f"{len(record['figures'])} figures")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
