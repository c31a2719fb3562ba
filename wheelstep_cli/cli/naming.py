"""How a refusal names a parameter: as the user wrote it on the command line (the flag's
spelling, the value's text), and, for a value the user did not give, as the default it is."""

from __future__ import annotations

import re

from wheelstep_cli.config.names import flag_name
from wheelstep_cli.errors import NONE_GIVEN, DesignError, tie_context


def subcommand(group, argv: list[str]) -> str | None:
    """The name of the subcommand ``argv`` runs (None: it names none)."""
    return next((arg for arg in argv if arg in group.commands), None)


def command_params(group, argv: list[str]) -> list:
    """The options of the subcommand ``argv`` runs (none if it names no subcommand)."""
    name = subcommand(group, argv)
    return [] if name is None else [p for p in group.commands[name].params if p.param_type_name == "option"]


def command_options(group, argv: list[str]) -> dict[str, list[str]]:
    """Parameter name -> option strings of the subcommand ``argv`` runs (empty if none)."""
    return {param.name: [*param.opts, *param.secondary_opts] for param in command_params(group, argv)}


def _as_typed(param: str, options: dict[str, list[str]], argv: list[str]) -> str:
    """The parameter as the user wrote it: the spelling of its flag found in ``argv``, else
    its first long flag; a name the command has no option for (an argument, a derived
    quantity such as a crank angle, a profile key) stays as it is."""
    opts = options.get(param) or options.get(param.replace("-", "_"))
    if not opts:
        return param
    typed = {arg.split("=", 1)[0] for arg in argv if arg.startswith("-")}
    typed |= {arg[:2] for arg in argv if arg.startswith("-") and not arg.startswith("--")}   # -m10
    used = [o for o in opts if o in typed]
    return (used or [o for o in opts if o == flag_name(param)] or opts)[0]


def given_names(group, argv: list[str]) -> list[str]:
    """Names of the options of the subcommand named in ``argv`` that the command line gives,
    read as the parser reads them (``--z 48``, ``--z=48``, ``-m10``, ``-qm10``; a switch by
    any of its spellings)."""
    params = command_params(group, argv)
    if not params:
        return []
    words = argv[argv.index(subcommand(group, argv)) + 1:]
    words = words[:words.index("--")] if "--" in words else words
    named = {param.name for param, _, _ in option_values(params, words)}
    switches = {flag: p.name for p in params if getattr(p, "is_flag", False) or getattr(p, "count", False)
                for flag in (*p.opts, *p.secondary_opts)}
    for word in words:
        if word in switches:
            named.add(switches[word])
        elif word.startswith("-") and not word.startswith("--"):
            # a bundle of short switches (-qv) names each
            named.update(switches[f"-{letter}"] for letter in word[1:] if f"-{letter}" in switches)
    return [p.name for p in params if p.name in named]


def option_values(params, argv: list[str]) -> list[tuple[object, str, str]]:
    """(parameter, flag as typed, value) of every value-taking option of ``params`` in
    ``argv`` as the parser reads them: ``--flag value``, ``--flag=value``, ``-f value``,
    ``-fvalue`` and bundled ``-qfvalue``; a value is not read as an option, and nothing
    after ``--`` is an option."""
    by_flag = {flag: p for p in params for flag in (*p.opts, *p.secondary_opts)}
    takes_value = {flag: not (getattr(p, "is_flag", False) or getattr(p, "count", False))
                   for flag, p in by_flag.items()}
    found, i = [], 0
    while i < len(argv) and argv[i] != "--":
        arg, i = argv[i], i + 1
        if arg.startswith("--"):
            flag, eq, value = arg.partition("=")
            if takes_value.get(flag) and (eq or i < len(argv)):
                found.append((by_flag[flag], flag, value if eq else argv[i]))
                i += 0 if eq else 1
            continue
        for k in range(1, len(arg) if arg.startswith("-") else 1):
            flag = "-" + arg[k]
            if flag not in by_flag:
                break
            if takes_value[flag]:
                if k + 1 < len(arg) or i < len(argv):
                    found.append((by_flag[flag], flag, arg[k + 1:] if k + 1 < len(arg) else argv[i]))
                    i += 0 if k + 1 < len(arg) else 1
                break
    return found


def strut_as_given(err: DesignError, group, argv: list[str], given: list[str]) -> DesignError:
    """``err``, where it is also stated for the strut length c, stated as well for --rmin when
    the command line gives the strut as R_min and not as c (c is sized from it): the line then
    names the option typed, not a default that shares the blame."""
    if "r_min" not in given or "c" in given or "c" not in err.alternatives:
        return err
    typed = [value for param, _, value in option_values(command_params(group, argv), argv) if param.name == "r_min"]
    try:
        r_min = float(typed[-1])
    except (IndexError, ValueError):
        return err
    alternatives = {}
    for name, stated in err.alternatives.items():    # in c's place: the same precedence
        alternatives.update({name: stated, **({"r_min": (r_min, stated[1])} if name == "c" else {})})
    return err._with_extras(DesignError(err.param, err.value, err.limit, alternatives))


def aliases_as_typed(line: str, group, argv: list[str]) -> str:
    """``line`` with each option the command line gives by one of its spellings (``--rmin`` or
    ``--r-min``) written that way wherever the line names it by another: a remedy applied as
    it reads then replaces the option given instead of giving it twice."""
    import re

    name = subcommand(group, argv)
    if name is None:
        return line
    words = [word.partition("=")[0] for word in argv[argv.index(name) + 1:]]
    for param in command_params(group, argv):
        spellings = [flag for flag in param.opts if flag.startswith("--")]
        typed = [word for word in words if word in spellings]
        for other in spellings if typed and len(spellings) > 1 else ():
            if other != typed[-1]:
                line = re.sub(rf"(?<![\w-]){re.escape(other)}(?![\w-])", typed[-1], line)
    return line


def error_text(err: DesignError, name: str, argv: list[str]) -> str:
    """One line: the parameter as the user wrote it (``name``), the value and the limit."""
    return f"{name} = {_typed_value(name, err, argv)}: {err.limit}"


def typed_name(err: DesignError, options: dict[str, list[str]], argv: list[str]) -> str:
    """``err``'s parameter as the user wrote it (its flag as typed, an argument by its name)."""
    name = _as_typed(err.param, options, argv)
    if name == err.param and isinstance(err.value, str):
        # a file's problem named by the reader ("file"): the option that gave that file
        found = _path_option(err.value, options, argv)
        if found is not None and found[1] == err.value:
            name = found[0]
    return name


def _number(value: object) -> int | float | None:
    """``value`` when it is a number (not a switch's True / False), else None."""
    return value if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def _typed_value(flag: str, err: DesignError, argv: list[str]) -> str:
    """The value as the user typed it after ``flag`` (``1e9``, not ``1e+09``) when it is the
    number the error is about; else as the messages print it."""
    number = _number(err.value)
    for _, text in flag_values({flag}, argv):
        try:
            same = number is not None and float(text) == float(number)
        except ValueError:
            same = False
        if same:
            return text
    return err.shown_value


def flag_values(flags: set[str], argv: list[str]) -> list[tuple[str, str]]:
    """(flag as typed, its value) of every one of ``flags`` given in ``argv``, as
    ``--flag value`` or ``--flag=value``, in order."""
    pairs = []
    for i, arg in enumerate(argv):
        flag, eq, value = arg.partition("=")
        if flag in flags and (eq or i + 1 < len(argv)):
            pairs.append((flag, value if eq else argv[i + 1]))
    return pairs


def _path_option(filename: str, options: dict[str, list[str]], argv: list[str]) -> tuple[str, str] | None:
    """(flag as typed, its value) of the option in ``argv`` whose path is ``filename``, a
    folder holding it or inside it, else None."""
    from pathlib import Path

    pairs = flag_values({o for opts in options.values() for o in opts}, argv)
    file = Path(filename)
    # the option given that very path first, whatever the order (--out . --profile p.yaml)
    for flag, value in pairs:
        if value and file == Path(value):
            return flag, value
    for flag, value in pairs:
        given = Path(value)
        if value and (given in file.parents or file in given.parents):
            return flag, value
    return None


def os_error_text(err: OSError, options: dict[str, list[str]], argv: list[str]) -> str:
    """One line for a file that cannot be written: naming the option whose path it is (as the
    user typed it), the value and why (with the name-length limit when that is why)."""
    import errno
    import os
    from pathlib import Path

    why = err.strerror or str(err)
    if err.errno == errno.ENAMETOOLONG:
        why += f"; a file or folder name holds at most {os.pathconf('/', 'PC_NAME_MAX')} bytes"
    filename = getattr(err, "filename", None)
    found = _path_option(str(filename), options, argv) if filename else None
    if found is not None:
        where = "" if Path(filename) == Path(found[1]) else f"{filename}: "
        return f"{found[0]} = {found[1]}: cannot be written ({where}{why})"
    return f"cannot write{f' {filename}' if filename else ''}: {why}"


def refusal_line(original: DesignError, err: DesignError, group, argv: list[str]) -> tuple[str, str]:
    """(the line, the parameter as it names it) for ``err``, the design error ``original``
    restated for a parameter the user gave (:meth:`DesignError.for_given`). A value of an
    option the command line did not give is marked as the default when it is the number
    the option's help states as its default and nothing else could have given it (no
    ``--profile``, no plate or G-code read for its design): the parameter the line names
    (``--z = 48 (the default): ...``) and the one the rule is about when the line names
    another (``--run = 0.5: with it, landing-angle = -90 (the default) fails: ...``). A value
    worked out from other inputs (c from a and b, a printer's compensation) is not marked."""
    options = command_options(group, argv)
    name = typed_name(err, options, argv)
    given = {n.replace("-", "_") for n in given_names(group, argv)}
    if {"profile", "gcode"} & given or any(arg.lower().endswith(".3mf") for arg in argv):
        return error_text(err, name, argv), name
    defaults = _documented_defaults(group, argv)

    def is_default(param: str, value: object) -> bool:
        param = param.replace("-", "_")
        return param not in given and _number(value) is not None and defaults.get(param) == value

    if err is not original and is_default(original.param, original.value) and NONE_GIVEN not in original.limit:
        context = tie_context(original.param, original.shown_value)
        err = err.restated(err.limit.replace(context, tie_context(original.param,
                                                                  f"{original.shown_value} {DEFAULT_MARK}")))
    if is_default(err.param, err.value) and NONE_GIVEN not in err.limit:
        return f"{name} = {err.shown_value} {DEFAULT_MARK}: {err.limit}", name
    return error_text(err, name, argv), name


#: How a line marks the value of an option the user did not give.
DEFAULT_MARK = "(the default)"


def _documented_defaults(group, argv: list[str]) -> dict[str, float]:
    """Parameter name -> the default number each option of the subcommand named in ``argv``
    documents: its own default, else the ``[default: N]`` its help shows (options whose
    default is None print the value the design takes); options whose default is not one
    number (a rule such as ``0.25 x module``) are left out."""
    found, params = {}, command_params(group, argv)
    # the options given, read as the parser reads them (for a default that holds without one)
    given = set(given_names(group, argv))
    flags = {flag: p.name for p in params for flag in p.opts}
    for param in params:
        default = param.default
        if default is None:
            shown = re.search(r"\[default: ([^\]]+)\]\s*$", param.help or "")
            default = shown.group(1) if shown else None
            # a default said with where it comes from ("the design's, 144"); not a list of
            # numbers, nor a rule with numbers of its own ("paper 0.5 less, 143.5")
            number = re.fullmatch(r"[^\d;,]+,\s*(-?\d+(?:\.\d+)?)", default or "")
            default = number.group(1) if number else default
            # a default that holds while another option is not given ("100 if no --r3")
            unless = re.fullmatch(r"(-?\d+(?:\.\d+)?) if no (--[a-z0-9-]+)", default or "")
            if unless:
                default = None if flags.get(unless.group(2)) in given else unless.group(1)
        try:
            found[param.name] = float(default)
        except (TypeError, ValueError):
            continue
    return found
