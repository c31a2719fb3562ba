"""Checks of how the CLI answers, used by several test modules."""

from __future__ import annotations


def error_line(result, code: int = 2) -> str:
    """Assert the command exited with ``code`` and printed exactly one line on stderr; return it."""
    assert result.exit_code == code, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    return lines[0]


def with_remedy(args, remedy: list[str]) -> list[str]:
    """The command line ``args`` with a refusal's remedy (``["--z", "54", ...]``: flag, value
    pairs) applied as a user applies it: a flag already given takes the new value (given
    twice, an option is refused), the others are added."""
    line = [str(a) for a in args]
    for flag, value in zip(remedy[::2], remedy[1::2]):
        if flag in line:
            line[line.index(flag) + 1] = value
        else:
            line += [flag, value]
    return line


def remedy_in(line: str) -> list[str]:
    """A refusal's remedy: the options after its final ``use``, up to what it says of them
    in brackets (``["--z", "54", ...]``)."""
    return line.rsplit("; use ", 1)[1].split(" (", 1)[0].split()
