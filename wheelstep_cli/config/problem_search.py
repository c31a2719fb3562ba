"""Every problem of a run's input at once: a rule stops at the first value it finds at fault,
so the spec is resolved again without the command line's options and the design profile's
keys found at fault so far, the defaults standing in, while that finds another given value
at fault."""

from __future__ import annotations

from typing import Any

from wheelstep_cli.config.schema import InvalidInput
from wheelstep_cli.errors import DesignError


class WithoutKeys:
    """A design profile seen without some of its keys (``"section.key"``): the defaults
    stand in for them."""

    def __init__(self, profile, keys: set[str]):
        self.profile, self.keys = profile, keys

    @property
    def shipped(self) -> bool:
        return self.profile.shipped

    def where(self, section: str, key: str) -> str | None:
        return self.profile.where(section, key)

    def values(self, section: str) -> dict[str, Any]:
        return {k: v for k, v in self.profile.values(section).items() if f"{section}.{k}" not in self.keys}


def blamed(err: DesignError, cli: dict[str, Any]) -> tuple[set[str], set[str]]:
    """(the command line's options, the profile's ``"section.key"``) that the problem ``err``
    (as config.resolve says it: for an option given, else at the profile's line) names: the
    one it is said for (empty sets: neither, it is the defaults' own)."""
    if isinstance(err, InvalidInput):
        return set(), {issue.what for issue in err.issues}
    named = err.param.replace("-", "_")
    return ({named} if cli.get(named) is not None else set()), set()


def tied_keys(err: DesignError) -> set[str]:
    """Every parameter a rule is stated for (its own and those tied on), snake_case."""
    if hasattr(err, "tied"):
        return err.tied
    if isinstance(err, InvalidInput):
        return {issue.what.rpartition(".")[2] for issue in err.issues}
    return {name.replace("-", "_") for name in (err.param, *err.alternatives)}


def every_problem(resolved, loaded, cli: dict[str, Any], first: DesignError) -> DesignError:
    """``first`` (a rule the command line ``cli`` or the design profile ``loaded`` breaks, said
    for an option or at the profile's line) carrying in ``also`` every other rule their values
    break, so the user mends them in one go: a rule stops at the first value it finds at fault,
    so the spec is resolved again (``resolved(profile seen, options)``, raising the rule it
    finds broken, said by :func:`~wheelstep_cli.config.resolve._named_for`) without the options and keys found so far (the defaults
    standing in) while that finds another given value at fault. A problem that the defaults
    standing in take part in is not said (it may stem from them): its value is left out unsaid
    and the search goes on. The profile's problems are said as one file's lines."""
    options, keys = blamed(first, cli)
    if not options and not keys:
        return first
    found = [first]
    while True:
        top = {k: (None if k in options else v) for k, v in cli.items()}
        seen = loaded if loaded is None or not keys else WithoutKeys(loaded, keys)
        try:
            resolved(seen, top)
            break
        except DesignError as err:
            more_options, more_keys = blamed(err, top)
            if not (more_options - options or more_keys - keys):
                break               # the defaults' own, or nothing left to leave out: the search ends
            left_out = options | {key.rpartition(".")[2] for key in keys}
            if not tied_keys(err) & left_out:
                found.append(err)
            options, keys = options | more_options, keys | more_keys
    return gathered(found)


def gathered(found: list[DesignError]) -> DesignError:
    """The problems ``found`` in one run as one error: the first, carrying the others in
    ``also``; a file's problems (InvalidInput) said as one file's lines (in its order, the
    first one's remedies), where its first problem was found."""
    problems: list[DesignError] = []
    for err in found:
        at = next((k for k, said in enumerate(problems) if isinstance(said, InvalidInput)), None)
        if isinstance(err, InvalidInput) and at is not None:
            every = InvalidInput([*problems[at].issues, *err.issues])
            every.remedy = getattr(problems[at], "remedy", {})
            every.remedies = list(getattr(problems[at], "remedies", []))
            problems[at] = every
        else:
            problems.append(err)
    if len(problems) > 1:
        problems[0].also = problems[1:]
    return problems[0]
