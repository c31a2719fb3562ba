"""Checks of how the CLI answers, used by several test modules."""

from __future__ import annotations


def error_line(result, code: int = 2) -> str:
    """Assert the command exited with ``code`` and printed exactly one line on stderr; return it."""
    assert result.exit_code == code, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    return lines[0]
