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


AFTER_THE_COMMAND = """\
import atexit, signal, sys, threading, time
import wheelstep_cli.cli as cli

def run():
    if sys.argv[1] == "done":
        def waiting_exit_handler():           # a library's, registered while the command ran
            signal.raise_signal(signal.SIGINT)
            time.sleep(60)
        atexit.register(waiting_exit_handler)
        return 1
    threading.Thread(target=time.sleep, args=(60,)).start()   # left waiting by the Ctrl-C
    print("wheelstep: aborted", file=sys.stderr)
    return 130

cli.run = run
cli.main()
"""


@pytest.mark.parametrize("case", ["done", "interrupted"])
def test_nothing_waits_once_the_command_has_returned(tmp_path, case):
    """Done, a Ctrl-C while a library's exit handler waits ends the wait with the command's
    own exit code (and none is left to kill the process as Python shuts down); interrupted,
    the process ends at once, not waiting for threads the Ctrl-C cut off."""
    import subprocess
    import time

    script = tmp_path / "entry.py"
    script.write_text(AFTER_THE_COMMAND)
    start = time.monotonic()
    run = subprocess.run([sys.executable, str(script), case], capture_output=True, text=True, timeout=120)
    assert run.returncode == (1 if case == "done" else 130), run.stderr
    assert time.monotonic() - start < 45        # not the minute the waits would take


def test_loading_the_cli_leaves_the_batch_pipeline_unloaded():
    """Every command imports the console script's Ctrl-C handling (batch.interrupts); the
    batch pipeline it sits beside (plan, run, build: YAML, pools, printers) is loaded by the
    batch command alone, so `gears` does not pay for it at start-up."""
    import subprocess

    probe = ("import sys, wheelstep_cli.cli as cli; cli._register_commands(); "
             "import wheelstep_cli.batch as batch; "
             "print(sorted(m for m in sys.modules if m.startswith('wheelstep_cli.batch.'))); "
             "batch.load_batch; print('wheelstep_cli.batch.plan' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    loaded, after = out.stdout.splitlines()
    assert loaded == "['wheelstep_cli.batch.interrupts']"
    assert after == "True"     # the package's names still load on first use


def test_output_cut_short_by_its_reader_ends_quietly_with_sigpipes_code(tmp_path):
    """`wheelstep teeth | head -1`: click exits 1 when stdout's reader goes away, which is the
    code of a failed check here (a `set -o pipefail` script took a good pair for a bad one).
    The run ends with 141 (128 + SIGPIPE, as a shell says of such a writer), nothing on stderr."""
    import subprocess

    proc = subprocess.Popen([sys.executable, "-m", "wheelstep_cli", "teeth"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, cwd=tmp_path)
    proc.stdout.close()              # the reader is gone before the table is printed
    stderr = proc.stderr.read()
    assert proc.wait(timeout=120) == 141, stderr
    assert stderr == b""


def test_a_refusals_json_cut_short_by_its_reader_ends_quietly_too(tmp_path):
    """The refusal's --json is printed after the command returned (outside click, which
    handled the pipe inside it): it ended in a BrokenPipeError traceback and exit 1."""
    import subprocess

    proc = subprocess.Popen([sys.executable, "-m", "wheelstep_cli", "gears", "--thickness", "-1", "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=tmp_path)
    proc.stdout.close()
    stderr = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141, stderr
    assert stderr.startswith("wheelstep: error: --thickness = -1: ") and "Traceback" not in stderr, stderr
