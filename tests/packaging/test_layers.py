"""The layer contract (pyproject.toml [tool.importlinter]) holds, and no module imports in a cycle."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_import_linter_contracts_are_kept():
    exe = shutil.which("lint-imports") or str(Path(sys.executable).parent / "lint-imports")
    result = subprocess.run([exe, "--no-cache"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert " 0 broken" in result.stdout.split("Contracts:")[-1], result.stdout[-2000:]


def test_no_import_cycle_between_any_modules():
    grimp = pytest.importorskip("grimp")
    networkx = pytest.importorskip("networkx")
    graph = grimp.build_graph("wheelstep_cli", cache_dir=None)
    edges = networkx.DiGraph()
    for module in graph.modules:
        for imported in graph.find_modules_directly_imported_by(module):
            # a package's __init__ re-exporting its own modules is not a cycle of ideas
            if not (imported.startswith(module + ".") or module.startswith(imported + ".")):
                edges.add_edge(module, imported)
    cycles = list(networkx.simple_cycles(edges, length_bound=6))
    assert not cycles, cycles[:5]
