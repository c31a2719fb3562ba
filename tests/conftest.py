"""Shared test helpers: run the real CLI entry point in-process."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from wheelstep_cli.cli import run


@dataclass
class CliResult:
    exit_code: int
    stdout: str
    stderr: str


@pytest.fixture
def cli(capsys):
    """Call ``cli("gears", "--z", "48")``: runs wheelstep exactly as the console script does."""

    def invoke(*args: str) -> CliResult:
        capsys.readouterr()
        code = run([str(a) for a in args])
        out = capsys.readouterr()
        return CliResult(code, out.out, out.err)

    return invoke
