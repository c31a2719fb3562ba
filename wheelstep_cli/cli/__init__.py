"""The ``wheelstep`` command line: a Typer app whose commands live in ``commands/``.

Errors a user can fix (bad values, impossible designs) are reported as one line
on stderr with exit code 2 and nothing written, naming the parameter by its flag; see
:func:`run`. Every command takes ``-h``/``--help``, ``-q``, ``-v`` and, where it prints
a report, ``--json``; where it writes files, ``--dry-run``.
"""

from __future__ import annotations

import atexit
import errno
import os
import re
import signal
import sys
import warnings

import typer

try:  # typer >= 0.2x ships its own copy of click
    from typer._click import exceptions as click_errors
except ImportError:  # pragma: no cover - older typer uses click itself
    from click import exceptions as click_errors

from wheelstep_cli.batch.interrupts import (caused_by_interrupt, exit_now, exit_unless_threads_end,
                                            interrupts_not_lost)
from wheelstep_cli.cli.naming import (aliases_as_typed, command_options, command_params, flag_values, given_names,
                                      option_values, os_error_text, refusal_line, strut_as_given, subcommand)
from wheelstep_cli.cli.refusal import said
from wheelstep_cli.config.schema import InvalidInput
from wheelstep_cli.errors import CheckRefused, DesignError, Interrupted, MeshDefect

app = typer.Typer(
    name="wheelstep",
    help="Design parts of wheel-step movers: non-circular gear pairs, support shoes, "
         "linkages; written as printable meshes.",
    add_completion=True,
    no_args_is_help=True,
    context_settings={"help_option_names": ["-h", "--help"]},
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)


def _version(value: bool) -> None:
    if value:
        from wheelstep_cli import __version__

        typer.echo(f"wheelstep {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="Print the version and exit.")) -> None:
    """Design parts of wheel-step movers: non-circular gear pairs, support shoes, linkages."""


def _register_commands() -> None:
    from wheelstep_cli.cli.commands import register_all

    register_all(app)


_register_commands()


#: What a number option's value must be, by the parser's complaint about it.
_NUMBER_KINDS = (("valid integer", "must be a whole number"), ("valid number", "must be a number"))


def bad_number_text(err: click_errors.UsageError, argv: list[str]) -> str | None:
    """One line for a number option whose value is not a number of its kind, or a choice
    option's value not among its choices: the flag as typed, the value and what it must be,
    with a number's limit when the models state one (``--z = 1e9: must be a whole number,
    6..240 (pinion teeth)``); None for other errors."""
    param = getattr(err, "param", None)
    message = err.format_message()
    kind = next((words for said, words in _NUMBER_KINDS if said in message), None)
    choices = re.search(r"is not (?:one of )?('.+?)\.?$", message)      # a choice option's words
    if kind is None and choices:
        kind = "must be one of " + choices.group(1).replace("'", "")
    if param is None or kind is None or not getattr(param, "opts", None):
        return None
    given = flag_values(set(param.opts) | set(getattr(param, "secondary_opts", [])), argv)
    if not given:
        return None
    typed = given[-1]
    return f"{typed[0]} = {typed[1] or repr('')}: {kind if choices else _with_limit(kind, param.name or '')}"


def _number_kind(param) -> str | None:
    """What a number option's value must be ("must be a whole number"), None for others."""
    annotation = getattr(getattr(param, "type_descriptor", None), "annotation", None)
    if annotation is None:   # click's own parameters carry their type
        annotation = {"integer": int, "float": float}.get(getattr(getattr(param, "type", None), "name", None))
    return {int: "must be a whole number", float: "must be a number"}.get(annotation)


def _with_limit(kind: str, name: str) -> str:
    """``kind`` ("must be a whole number") with the option's limit when the models state one
    (", 6..240 (pinion teeth)")."""
    from wheelstep_cli.config.design import MechanismSection
    from wheelstep_cli.config.schema import field_limit
    from wheelstep_cli.config.specs import GearPairSpec, ShoeSpec

    limit = field_limit((GearPairSpec, ShoeSpec, MechanismSection), name)
    return kind + (", " + limit[len("must be "):] if limit is not None and limit.startswith("must be ") else "")


def misread_value_text(group, argv: list[str]) -> str | None:
    """One line for an option value of the named subcommand that the parser would read as
    something the person did not mean; None when there is none (or help is asked for):

    * a number with an underscore (``--z 4_8``): Python's parsers read it as 48;
    * an empty text or path (``--out ''``): a path reads it as the current folder;
    * an option given twice that takes one value (``--z 40 --z 48``): the parser keeps the
      last and drops the other unsaid.
    """
    name = subcommand(group, argv)
    if name is None or "-h" in argv or "--help" in argv:
        return None
    options, words = command_params(group, argv), argv[argv.index(name) + 1:]
    both = _both_ways(options, words)
    if both is not None:
        return both
    seen: dict[str, tuple[str, str]] = {}
    for param, flag, value in option_values(options, words):
        if not getattr(param, "multiple", False) and param.name in seen:
            first = seen[param.name]
            return f"{flag} = {value}: given twice ({first[0]} = {first[1]} before it); give it once"
        seen[param.name] = (flag, value)
        kind = _number_kind(param)
        if kind is not None and "_" in value:
            return f"{flag} = {value}: {_with_limit(kind, param.name or '')}, written without underscores"
        if kind is None and not value.strip():
            # a number's empty value gets the parser's own line ("must be a number")
            return f"{flag} = {value!r}: must not be {'empty' if not value else 'only spaces'}"
    return None


def _both_ways(params, argv: list[str]) -> str | None:
    """One line for a switch given both on and off (``--tolerance --no-tolerance``: the parser
    keeps the last), None when there is none."""
    words = argv[:argv.index("--")] if "--" in argv else argv
    for param in params:
        on = [w for w in words if w in param.opts]
        off = [w for w in words if w in getattr(param, "secondary_opts", ())]
        if on and off:
            return f"{off[0]} = on: contradicts {on[0]}, given too; give one of them"
    return None


def _refusal(err: DesignError, command, args: list[str]) -> tuple[list[str], DesignError, str | None]:
    """(its lines, the error as they state it, the parameter as the line names it; None: a
    file's problems, each at its ``file:line``) of the bad input ``err``."""
    if isinstance(err, InvalidInput):
        return err.lines(), err, None
    given = given_names(command, args)
    stated = strut_as_given(err, command, args, given).for_given(given)
    located = None if stated.param.replace("-", "_") in given else _in_design_profile(stated, command, args)
    if located is not None:     # said at the profile's line: its problem, the remedies the line's
        return located.lines(), located, None
    line, name = refusal_line(err, stated, command, args)
    return [aliases_as_typed(line, command, args)], stated, name


def _in_design_profile(err: DesignError, group, argv: list[str]):
    """``err`` (of a value the command line did not give) said at the line of the ``--profile``
    that gives it (InvalidInput), None when no profile was given or it does not give it."""
    from wheelstep_cli.config.profiles import load_design_profile
    from wheelstep_cli.config.resolve import in_profile

    name = subcommand(group, argv)
    if name is None:
        return None
    # the command's own options, as the parser reads them (nothing after "--")
    given = [value for param, _, value in option_values(command_params(group, argv), argv[argv.index(name) + 1:])
             if param.name == "profile"]
    if not given:
        return None
    try:
        loaded = load_design_profile(given[-1])
    except DesignError:
        return None
    return in_profile(err, loaded, "shoe" if name == "shoe" else "gears")


def run(argv: list[str] | None = None) -> int:
    """Run the CLI on ``argv`` and return the exit code (0 ok, 1 failed check, 2 bad input)."""
    args = sys.argv[1:] if argv is None else list(argv)
    try:
        command = typer.main.get_command(app)
    except KeyboardInterrupt:
        return _aborted()
    misread = misread_value_text(command, args)
    if misread is not None:
        return said([f"wheelstep: error: {misread}"], 2, args)
    try:
        result = _invoke(command, args)
    except (MeshDefect, CheckRefused) as err:  # a failed check (wheelstep's own, or of the result)
        return said([f"wheelstep: {'refused' if isinstance(err, CheckRefused) else 'error'}: {err}"], 1, args, err)
    except DesignError as err:                # bad input: each problem found (``also``) on its lines
        refusals = [_refusal(problem, command, args) for problem in (err, *getattr(err, "also", ()))]
        lines = [f"wheelstep: error: {line}" for problem_lines, _, _ in refusals for line in problem_lines]
        _, stated, name = refusals[0]
        return said(lines, 2, args, stated, name, every=[(problem, name, problem_lines) for problem_lines, problem,
                                                         name in refusals] if len(refusals) > 1 else None)
    except click_errors.NoArgsIsHelpError as err:
        typer.echo(err.format_message(), err=True)
        return 2
    except click_errors.UsageError as err:
        number = bad_number_text(err, args)
        if number is not None:
            return said([f"wheelstep: error: {number}"], 2, args)
        where = f" ({err.ctx.command_path})" if err.ctx is not None else ""
        # a choice option's check is pydantic's: its "Value error, " tag is no news to a user
        message = err.format_message().replace("Value error, ", "")
        return said([f"wheelstep: error{where}: {message}"], 2, args)
    except click_errors.ClickException as err:
        return said([f"wheelstep: error: {err.format_message()}"], err.exit_code, args)
    except OSError as err:
        return said([f"wheelstep: error: {os_error_text(err, command_options(command, args), args)}"], 2, args)
    return result if isinstance(result, int) else 0


def _invoke(command, args: list[str]):
    """The command's result; a Ctrl-C in any of its forms said in one line (the command's own
    :class:`Interrupted` line, else 'aborted') with the exit code :data:`INTERRUPTED`."""
    try:
        with warnings.catch_warnings(), interrupts_not_lost():
            # library warnings (numpy floating point, matplotlib layout) are not for the person
            # at the terminal: every figure that matters is checked before it is written
            warnings.simplefilter("ignore")
            result = command.main(args=args, prog_name="wheelstep", standalone_mode=False)
    except Interrupted as err:
        typer.echo(f"wheelstep: {err}", err=True)
        return INTERRUPTED
    except (typer.Abort, KeyboardInterrupt):
        return _aborted()
    except SystemExit as err:
        if isinstance(err.__context__, OSError) and err.__context__.errno == errno.EPIPE:
            # click exits 1 (a failed check, here) when the reader of stdout went away (`| head`):
            # said as a shell says a writer stopped by SIGPIPE, and quietly, as such a writer is
            return OUTPUT_CLOSED
        raise
    except Exception as err:
        if caused_by_interrupt(err):          # a Ctrl-C a library wrapped in an error of its own
            return _aborted()
        raise
    if result == INTERRUPTED:
        # typer turns Ctrl-C in a command into this exit code, silently
        return _aborted()
    return result


#: The exit code of a run stopped by Ctrl-C (128 + SIGINT), as shells report it.
INTERRUPTED = 130
#: The exit code of a run whose output's reader closed it (128 + SIGPIPE), as shells report it.
OUTPUT_CLOSED = 141


def _aborted() -> int:
    """Say that the run was stopped (Ctrl-C): files are written atomically, so none is half
    written."""
    typer.echo("wheelstep: aborted", err=True)
    return INTERRUPTED


def main() -> None:
    """Console-script entry point."""
    # registered before any library's, so run after them: past the exit handlers Python drops
    # its signal handlers, and a Ctrl-C would kill the process with SIGINT's exit code
    atexit.register(signal.signal, signal.SIGINT, signal.SIG_IGN)
    try:
        code = run()
    except KeyboardInterrupt:                 # in the instant after the command returned
        code = _aborted()
    except BrokenPipeError:
        # stdout's reader went away while a refusal's --json was printed (after the command):
        # quiet, as in the command, and nothing left for Python to flush into the closed pipe
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        code = OUTPUT_CLOSED
    # a Ctrl-C while threads are joined or exit handlers wait ends the wait, with the
    # command's exit code (its files are written, or left alone)
    signal.signal(signal.SIGINT, lambda signum, frame: exit_now(code))
    if code == INTERRUPTED:
        # workers cut off by the Ctrl-C may have left a thread that waits on them for ever (a
        # pool's reader of a result half sent), which Python's shutdown would join
        exit_unless_threads_end(code)
    sys.exit(code)
