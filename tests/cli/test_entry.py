"""The console script's entry: Ctrl-C while the CLI's libraries load ends in one line."""

import sys
import types

import pytest


class _Loading(types.ModuleType):
    """Stands for wheelstep_cli.cli while Ctrl-C arrives during its import."""

    def __getattr__(self, name):
        raise KeyboardInterrupt


def test_ctrl_c_while_the_cli_loads_is_one_line_and_exit_130(monkeypatch, capsys):
    from wheelstep_cli.__main__ import main

    monkeypatch.setitem(sys.modules, "wheelstep_cli.cli", _Loading("wheelstep_cli.cli"))
    with pytest.raises(SystemExit) as stop:
        main()
    assert stop.value.code == 130
    assert capsys.readouterr().err == "wheelstep: aborted\n"


def test_the_console_script_is_the_guarded_entry():
    import tomllib
    from pathlib import Path

    project = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())
    assert project["project"]["scripts"]["wheelstep"] == "wheelstep_cli.__main__:main"


def test_a_refusal_after_the_work_started_is_the_only_line_on_stderr(cli, tmp_path):
    """The progress bars are for a terminal: on a redirected stderr they leave nothing, not
    even the blank line rich ends them with, so the refusal is stderr's one line."""
    result = cli("gears", "--thickness", "1e5", "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert result.stderr.startswith("wheelstep: error: --thickness = ") and result.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("where", ["command", "building the commands", "wrapped by a library"])
def test_ctrl_c_in_a_run_is_one_line_and_exit_130(cli, monkeypatch, where):
    """Ctrl-C while a command works (typer turns it into a silent exit code), while the
    commands are being built, or caught and wrapped by a library (Python wraps one that lands
    in a class body's __set_name__ while a module loads): one line, exit 130, no traceback."""
    import typer

    import wheelstep_cli.parts.gear_tables as tables

    def interrupt(*args, **kwargs):
        if where != "wrapped by a library":
            raise KeyboardInterrupt
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as err:
            raise RuntimeError("Error calling __set_name__") from err

    if where != "building the commands":
        monkeypatch.setattr(tables, "pitch_report", interrupt)
    else:
        monkeypatch.setattr(typer.main, "get_command", interrupt)
    result = cli("pitch")
    assert result.exit_code == 130
    assert result.stderr == "wheelstep: aborted\n" and result.stdout == ""


@pytest.mark.parametrize("args, shown", [
    (["--module", "1e9"], "--module = 1e9: "),          # not 1e+09
    (["--thickness=1e5"], "--thickness = 1e5: "),       # not 100000
    (["--z", "47"], "--z = 47: "),
])
def test_a_refused_number_is_shown_as_typed(cli, tmp_path, args, shown):
    result = cli("gears", *args, "--out", tmp_path / "out")
    assert result.exit_code == 2 and result.stderr.startswith(f"wheelstep: error: {shown}")


def test_a_ctrl_c_once_the_command_is_done_does_not_change_its_exit_code(monkeypatch):
    """While Python shuts down after the command (its signal handlers gone), a Ctrl-C would
    kill the process: the command's own exit code stands."""
    import signal

    import wheelstep_cli.cli as cli_module

    monkeypatch.setattr(cli_module, "run", lambda: 1)
    try:
        with pytest.raises(SystemExit) as stop:
            cli_module.main()
        signal.raise_signal(signal.SIGINT)     # ignored: nothing raised, the process lives
        assert stop.value.code == 1
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
