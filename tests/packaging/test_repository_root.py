"""The repository's top level holds the project's layout only: scratch files a run leaves in
the working folder (13 STL files once landed there) are not committed."""

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: What the top level holds: the brief's layout and the project's own folders.
LAYOUT = {".ci", ".gitignore", "README.md", "benchmarks", "constraints.txt", "docs", "examples",
          "profiles", "pyproject.toml", "setup.py", "tests", "wheelstep_cli"}


@pytest.mark.skipif(shutil.which("git") is None or not (ROOT / ".git").exists(),
                    reason="needs the git checkout")
def test_only_the_layout_is_committed_at_the_top_level():
    listed = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True)
    top = {line.split("/", 1)[0] for line in listed.stdout.splitlines()}
    assert top - LAYOUT == set()
