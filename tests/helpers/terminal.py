"""The CLI run as from a terminal, for tests of a real Ctrl-C: its own process group, SIGINT
at its default (pytest's runner may ignore it), stopped as a terminal stops it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

#: The checkout the tests run (its package, not another installed copy, in the child).
ROOT = Path(__file__).resolve().parents[2]


def start_cli(*args) -> subprocess.Popen:
    """``python -m wheelstep_cli *args`` in a process group of its own (text pipes for stdout
    and stderr), as a shell starts a command in the foreground."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.Popen([sys.executable, "-m", "wheelstep_cli", *map(str, args)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: (signal.signal(signal.SIGINT, signal.SIG_DFL), os.setsid()))


def ctrl_c(run: subprocess.Popen) -> None:
    """SIGINT to ``run``'s whole process group, as a terminal's Ctrl-C sends it."""
    os.killpg(run.pid, signal.SIGINT)
