"""In CI the slicer tests run or fail: a missing prusa-slicer skips them only outside CI."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run_slicer_tests(tmp_path: Path, ci: bool) -> subprocess.CompletedProcess:
    """The slicer test module with no prusa-slicer on PATH, with or without CI set."""
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    env["PATH"] = str(tmp_path)  # an empty folder: no prusa-slicer
    if ci:
        env["CI"] = "true"
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs",
                           str(ROOT / "tests" / "batch" / "test_batch_slicer.py")],
                          capture_output=True, text=True, env=env, cwd=ROOT, timeout=300)


@pytest.mark.parametrize("ci", [False, True])
def test_missing_slicer_skips_outside_ci_and_fails_in_ci(tmp_path, ci):
    result = run_slicer_tests(tmp_path, ci)
    if ci:
        assert result.returncode == 1, result.stdout
        assert "prusa-slicer is not installed (CI=true: the slicer tests must run)" in result.stdout
        assert "passed" not in result.stdout.lower() and "skipped" not in result.stdout.lower()
    else:
        assert result.returncode == 0, result.stdout
        assert "SKIPPED" in result.stdout and "failed" not in result.stdout.lower()
        assert "prusa-slicer is not installed" in result.stdout
