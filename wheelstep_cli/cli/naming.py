"""How a refusal names a parameter: as the user wrote it on the command line (the flag's
spelling, the value's text), and, for a value the user did not give, as the default it is."""

from __future__ import annotations

from wheelstep_cli.config.names import flag_name
from wheelstep_cli.errors import DesignError, tie_context


def command_options(group, argv: list[str]) -> dict[str, list[str]]:
    """Parameter name -> option strings of the subcommand named in ``argv`` (empty if none is)."""
    name = next((arg for arg in argv if arg in group.commands), None)
    if name is None:
        return {}
    return {param.name: [*param.opts, *param.secondary_opts] for param in group.commands[name].params
            if param.param_type_name == "option"}


def _as_typed(param: str, options: dict[str, list[str]], argv: list[str]) -> str:
    """The parameter as the user wrote it: the spelling of its flag found in ``argv``, else
    its first long flag; a name the command has no option for (an argument, a derived
    quantity such as a crank angle, a profile key) stays as it is."""
    opts = options.get(param) or options.get(param.replace("-", "_"))
    if not opts:
        return param
    typed = {arg.split("=", 1)[0] for arg in argv if arg.startswith("-")}
    used = [o for o in opts if o in typed]
    return (used or [o for o in opts if o == flag_name(param)] or opts)[0]


def given_names(options: dict[str, list[str]], argv: list[str]) -> list[str]:
    """Names of the parameters whose flags appear in ``argv``."""
    typed = {arg.split("=", 1)[0] for arg in argv if arg.startswith("-")}
    return [name for name, opts in options.items() if typed.intersection(opts)]


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


def _typed_value(flag: str, err: DesignError, argv: list[str]) -> str:
    """The value as the user typed it after ``flag`` (``1e9``, not ``1e+09``) when it is the
    number the error is about; else as the messages print it."""
    number = err.value if isinstance(err.value, (int, float)) and not isinstance(err.value, bool) else None
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
    option the command line did not give is said as the default it is, when nothing else
    could have given it (no ``--profile``, no plate or G-code read for its design): the
    parameter the line names (``--distance = 144 (the default): ...``), and the one the rule
    is about when the line names another (``--z = 100: with it, backlash = 0.239 (the
    default) fails: ...``)."""
    options = command_options(group, argv)
    given = {name.replace("-", "_") for name in given_names(options, argv)}
    name = typed_name(err, options, argv)
    if not _from_defaults(given, argv):
        return error_text(err, name, argv), name

    def untyped(param: str) -> bool:
        return param.replace("-", "_") in options and param.replace("-", "_") not in given

    if err is not original and untyped(original.param):
        context = tie_context(original.param, original.shown_value)
        err = err.restated(err.limit.replace(context, tie_context(original.param,
                                                                  f"{original.shown_value} {DEFAULT_MARK}")))
    if untyped(err.param):
        return f"{name} = {err.shown_value} {DEFAULT_MARK}: {err.limit}", name
    return error_text(err, name, argv), name


#: How a line marks the value of an option the user did not give.
DEFAULT_MARK = "(the default)"


def _from_defaults(given: set[str], argv: list[str]) -> bool:
    """Whether a value no option gave is a default: no design profile was given, and no
    plate or G-code whose metadata holds the design (mesh-check) was read."""
    return not {"profile", "gcode"} & given and not any(arg.lower().endswith(".3mf") for arg in argv)
