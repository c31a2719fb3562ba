"""The #16 defect replays (tests/fuzz/test_issue16_defects.py) run against another source tree,
e.g. a commit before the fixes checked out with ``git worktree add --detach /tmp/old COMMIT``
(link ``/tmp/old/wheelstep_cli/profiles -> ../profiles`` so the old code reads its own
presets, not the editable install's). Each case runs in a subprocess with a 3 GiB address
space and a 90 s timeout; one JSON line per case says whether the replay's checks fail there
and why. Results: benchmarks/results.md (#16 defect replays on the code before the fixes).

    python benchmarks/issue16_replay_old.py /tmp/old [INDEX ...]
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MEMORY = 3 << 30
TIMEOUT = 90


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))


def replay(code: str, args: list[str], files: dict[str, bytes], named: str) -> list[str]:
    """What the replay's checks find wrong with ``args`` run on the tree ``code`` (empty: none)."""
    with tempfile.TemporaryDirectory() as tmp:
        for name, data in files.items():
            Path(tmp, name).write_bytes(data)
        env = dict(os.environ, PYTHONPATH=code, COLUMNS="200")
        try:
            run = subprocess.run([sys.executable, "-m", "wheelstep_cli", *args], cwd=tmp, env=env,
                                 capture_output=True, text=True, timeout=TIMEOUT,
                                 preexec_fn=_limit_memory, stdin=subprocess.DEVNULL)
            code_, err = run.returncode, run.stderr
        except subprocess.TimeoutExpired:
            code_, err = "timeout", ""
        left = sorted(p.name for p in Path(tmp).iterdir())
    lines = err.strip().splitlines()
    why = [] if code_ == 2 else [f"exit {code_}"]
    if len(lines) != 1:
        why.append(f"{len(lines)} stderr lines")
    elif named not in lines[0]:
        why.append(f"line lacks {named!r}")
    if "Traceback" in err:
        why.append("traceback")
    if left != sorted(files):
        why.append("wrote " + ",".join(sorted(set(left) - set(files))))
    return why


def main() -> None:
    sys.path.insert(0, str(ROOT))
    from tests.fuzz.test_issue16_defects import CASES

    code, only = sys.argv[1], {int(i) for i in sys.argv[2:]}
    for i, (args, files, named) in enumerate(CASES):
        if not only or i in only:
            why = replay(code, args, files, named)
            print(json.dumps({"i": i, "case": " ".join(args)[:70], "fails": bool(why), "why": why}),
                  flush=True)


if __name__ == "__main__":
    main()
