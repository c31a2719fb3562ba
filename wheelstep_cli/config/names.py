"""One snake_case name per parameter; the command-line flag is derived from it.

Errors (:class:`~wheelstep_cli.errors.DesignError`) carry the snake_case name, which is
also the YAML key. A file names it as the key; the command line as the flag.
"""

from __future__ import annotations

import re


def flag_name(param: str) -> str:
    """The command-line flag of a parameter: ``install_distance`` -> ``--install-distance``."""
    return "--" + param.replace("_", "-")


def as_flags(options: dict) -> str:
    """Options (name -> value) as a command line gives them: ``--z 74 --backlash 0.239``."""
    from wheelstep_cli.errors import format_value

    return " ".join(f"{flag_name(name)} {format_value(value)}" for name, value in options.items())


def as_keys(options: dict) -> str:
    """Options (name -> value) as a file gives them: ``z: 74, backlash: 0.239``."""
    from wheelstep_cli.errors import format_value

    return ", ".join(f"{name}: {format_value(value)}" for name, value in options.items())


def yaml_message(err) -> str:
    """A DesignError as a file names it: ``install_distance = 140: must be ...`` (a switch as
    YAML writes it, true or false)."""
    from wheelstep_cli.errors import format_value

    value = str(err.value).lower() if isinstance(err.value, bool) else format_value(err.value)
    return f"{err.param} = {value}: {in_file_words(err.limit)}"


def in_file_words(text: str, batch: bool = True) -> str:
    """``text`` with the flags of a part's parameters named as a file's keys (``needs
    --bore-shape d-flat`` -> ``needs bore_shape d-flat``): a rule's words serve both the
    command line and a file. Other flags (a command's own, such as ``--force``) stay, and
    for a design profile (``batch`` False) also those only a batch entry has as keys
    (``--printer``, ``--allow-interference``: a profile gives the parts, the command the rest)."""
    keys = _file_keys() if batch else _file_keys() - _BATCH_ONLY

    def key(match: re.Match) -> str:
        name = match.group(1).replace("-", "_")
        return name if name in keys else match.group(0)

    # a command line quoted in backticks (`wheelstep gears --printer NAME`) keeps its flags:
    # the even pieces lie outside backticks
    pieces = text.split("`")
    return "`".join(_FLAG.sub(key, piece) if i % 2 == 0 else piece for i, piece in enumerate(pieces))


_FLAG = re.compile(r"(?<![\w-])--([a-z][a-z0-9-]*)")


def _file_keys() -> frozenset[str]:
    """The keys a batch entry gives a part's parameters by (its overrides, its printer)."""
    from wheelstep_cli.config.specs import GearPairSpec, ShoeSpec

    return frozenset({*GearPairSpec.model_fields, *ShoeSpec.model_fields, *_BATCH_ONLY})


#: Keys of a batch entry that a design profile does not have.
_BATCH_ONLY = frozenset({"printer", "allow_interference"})


def remedy_in_yaml(err, keys=lambda options: f"overrides {{{as_keys(options)}}}", entry: bool = True) -> str:
    """A refusal with remedies (``require_within_bounds`` and ``verified_undercut`` of
    parts.mesh_bounds) as a file states it: each remedy (``use`` or, unbuilt, ``try``) and
    each failed try as ``keys(options)`` (default a batch entry's ``overrides {z: 90,
    backlash: 0.239}``), not as flags; any other refusal as :func:`yaml_message` words it.
    ``entry``: of a batch entry, whose "nothing written" is said "not built" (the file's other
    entries are written; a sweep's row keeps the words)."""
    message = yaml_message(err)   # its flags already said as keys (in_file_words)
    if entry:
        message = re.sub(r"; nothing written(?=;|$)", "; not built", message)
    return remedies_as_keys(message, err, keys)


def remedies_as_keys(message: str, err, keys=as_keys) -> str:
    """``message`` (``err``'s words, its flags already said as keys by :func:`in_file_words`)
    with each remedy ``err`` offers and each try it made said as ``keys(options)``."""
    from wheelstep_cli.errors import offered_remedies

    # the longest first: a try that holds a shorter one (z 44 module 2.9 holds z 44) stays whole
    for tried in sorted(getattr(err, "tried", None) or [], key=lambda t: -len(as_flags(t))):
        message = _whole_words(message, in_file_words(as_flags(tried)), keys(tried))
    # every remedy offered (an undercut may offer more than one), else the one
    for remedy in offered_remedies(err):
        for verb in ("use", "try"):
            message = _whole_words(message, in_file_words(f"{verb} {as_flags(remedy)}"), f"{verb} {keys(remedy)}")
    return message


def _whole_words(text: str, old: str, new: str) -> str:
    """``text`` with ``old`` replaced by ``new`` where it is not part of a longer number or word
    (a try of z 24 leaves z 240 alone)."""
    return re.sub(rf"(?<![\w.]){re.escape(old)}(?![\w.])", lambda _: new, text)
