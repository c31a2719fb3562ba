"""CLI conventions on every command: -h, --json (one JSON document on stdout), --dry-run
(nothing written, what would be said), -q (nothing printed on success), errors naming the
parameter by its flag."""

import json
from pathlib import Path

import pytest

from tests.helpers.clicheck import error_line, remedy_in

COMMANDS = ["pitch", "teeth", "gears", "mesh-check", "shoe", "kinematics", "stairs", "linkage",
            "trajectory", "batch", "sweep"]
WRITERS = ["gears", "mesh-check", "shoe", "kinematics", "stairs", "linkage", "trajectory", "batch",
           "sweep"]

SHOE_BATCH = "parts:\n  - name: sole\n    kind: shoe\n    printer: fdm-0.4-pla\n"
SHOE_SWEEP = "command: shoe\ndesign: desk-demo\ngrid:\n  width: [12]\n"


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    """A gear pair that meshes, written as STL (mesh-check's input)."""
    from wheelstep_cli.cli import run

    out = tmp_path_factory.mktemp("pair")
    assert run(["gears", "--profile", "desk-demo", "--format", "stl", "--out", str(out)]) == 0
    return out


def report_args(command: str, folder: Path, pair: Path) -> list[str]:
    """Quick arguments printing ``command``'s report; files (if any) go below ``folder``."""
    if command == "mesh-check":
        return [command, str(pair / "pinion.stl"), str(pair / "wheel.stl"), "--profile",
                "desk-demo", "--plot", str(folder / "mesh.png")]
    if command == "batch":
        batch = folder.parent / f"{folder.name}-shoe.yaml"
        batch.write_text(SHOE_BATCH)
        return [command, str(batch), "--out", str(folder / "batch"), "--jobs", "1"]
    if command == "sweep":
        sweep = folder.parent / f"{folder.name}-sweep.yaml"
        sweep.write_text(SHOE_SWEEP)
        return [command, str(sweep), "--out", str(folder / "sweep"), "--workers", "1"]
    files = {"gears": ["--profile", "desk-demo", "--format", "stl", "--out", str(folder / "gears")],
             "shoe": ["--out", str(folder / "shoe")],
             "kinematics": ["--plot", str(folder / "k.png")],
             "stairs": ["--plot", str(folder / "s.png")],
             "linkage": ["--preset", "jansen", "--samples", "360", "--csv", str(folder / "l.csv"),
                         "--plot", str(folder / "l.png"), "--gif", str(folder / "l.gif"),
                         "--gif-frames", "4"],
             "trajectory": ["--csv", str(folder / "t.csv"), "--dxf", str(folder / "t.dxf"),
                            "--plot", str(folder / "t.png")]}
    return [command, *files.get(command, [])]


def files_below(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file())


@pytest.mark.parametrize("command", COMMANDS)
def test_short_and_long_help(cli, command):
    short, long = cli(command, "-h"), cli(command, "--help")
    assert short.exit_code == 0 and short.stdout == long.stdout
    assert "Usage:" in short.stdout
    for flag in ("-q, --quiet", "-v, --verbose", "--json"):
        assert flag in short.stdout, flag
    assert ("--dry-run" in short.stdout) == (command in WRITERS)


def test_root_help_and_completion(cli):
    result = cli("-h")
    assert result.exit_code == 0
    assert "--install-completion" in result.stdout and "--show-completion" in result.stdout


def test_one_style_for_defaults_in_help(cli):
    text = " ".join(cli("gears", "-h").stdout.split())
    assert "[default: 48]" in text and "[default: both]" in text and "[48]" not in text
    text = " ".join(cli("kinematics", "-h").stdout.split())
    assert "[default: 60.0]" in text and "[default: 361]" in text


def _stated_defaults(command: str) -> dict[str, str]:
    """option -> the default its help states in words (``[default: ...]`` of an option whose
    value comes from a profile or the built-in design), for the states a run can confirm: a
    number or a word, or a formula ending in ``= number``."""
    import re

    import typer

    import wheelstep_cli.cli as cli_module

    cli_module._register_commands()
    stated = {}
    for param in typer.main.get_command(cli_module.app).commands[command].params:
        found = re.search(r"\[default: ([^\]]*)\]", getattr(param, "help", None) or "")
        if found and param.default is None:
            text = found.group(1).rsplit("= ", 1)[-1]
            if re.fullmatch(r"-?[\d.]+|[a-z]+", text):
                stated[param.name] = text
    return stated


@pytest.mark.parametrize("command", ["gears", "shoe", "kinematics"])
def test_the_defaults_the_help_states_are_the_ones_used(cli, command):
    """An option filled from the built-in design says its default in words (it has no
    concrete default for the help to show): each such word is the value a run resolves."""
    stated = _stated_defaults(command)
    args = [command, "-v"] + (["--dry-run"] if command in ("gears", "shoe") else [])
    resolved = dict(line.strip().split(" = ", 1) for line in cli(*args).stderr.splitlines()
                    if line.startswith("  ") and " = " in line)
    checked = {name: text for name, text in stated.items() if name in resolved}
    assert len(checked) >= (8 if command == "gears" else 4), (stated, resolved)
    for name, text in checked.items():
        try:
            assert float(resolved[name]) == float(text), name
        except ValueError:
            assert resolved[name] == text, name


@pytest.mark.parametrize("command", COMMANDS)
def test_json_is_one_document_on_stdout(cli, tmp_path, pair, command):
    result = cli(*report_args(command, tmp_path / "out", pair), "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert isinstance(data, dict) and data
    if command in WRITERS:
        # every file the run wrote is listed, as gears, shoe and batch listed theirs (the
        # commands writing files the user names listed none)
        listed = {Path(p).resolve() for p in data["written"]}
        assert {p.resolve() for p in files_below(tmp_path / "out")} <= listed, command


@pytest.mark.parametrize("command", WRITERS)
def test_dry_run_writes_nothing_and_says_what_it_would(cli, tmp_path, pair, command):
    folder = tmp_path / "out"
    result = cli(*report_args(command, folder, pair), "--dry-run")
    assert result.exit_code == 0, result.stderr
    assert not folder.exists() or not files_below(folder)
    assert "would write" in result.stdout
    written = cli(*report_args(command, folder, pair))
    assert written.exit_code == 0, written.stderr
    for path in files_below(folder):
        assert str(path) in result.stdout or path.name in result.stdout, path


@pytest.mark.parametrize("command", COMMANDS)
def test_quiet_prints_nothing_on_success(cli, tmp_path, pair, command):
    result = cli(*report_args(command, tmp_path / "out", pair), "-q")
    assert result.exit_code == 0, result.stderr
    assert result.stdout == "" and result.stderr == ""


def test_verbose_adds_detail_on_stderr_only(cli):
    plain, verbose = cli("stairs"), cli("stairs", "-v")
    assert verbose.stdout == plain.stdout
    assert "b = " in verbose.stderr and plain.stderr == ""


@pytest.mark.parametrize("args, resolved, left", [
    (["shoe", "--dry-run"], ["c = 360.0", "r_min = 20.0"], None),     # filled by the design's rule
    (["linkage", "--dry-run"], ["preset = four-bar"], "four_bar.l1"),  # the preset's leg
])
def test_verbose_never_prints_none(cli, tmp_path, args, resolved, left):
    result = cli(*args, "-v", "--out" if args[0] == "shoe" else "--csv",
                 str(tmp_path / ("o" if args[0] == "shoe" else "o.csv")))
    assert result.exit_code == 0, result.stderr
    assert "None" not in result.stderr
    for line in resolved:
        assert f"  {line}\n" in result.stderr
    if left:
        assert any(line.startswith("  not given") and left in line
                   for line in result.stderr.splitlines())


@pytest.mark.parametrize("args, shown", [
    (["gears", "--teeth", "paper", "--center-distance", "143.5", "--install-distance", "140"],
     "--install-distance = 140"),
    (["shoe", "--rmin", "-1"], "--rmin = -1"),
    (["kinematics", "--motor-rpm", "0"], "--motor-rpm = 0"),
    (["stairs", "--sweep", "--sweep-radii", "0"], "--sweep-radii = 0"),
    (["mesh-check", "missing.stl", "missing.stl"], "pinion = missing.stl"),   # an argument
    (["linkage", "--l3", "100"], "--l3 = 100"),          # the solver's crank angle: the link given
    # more local workers than the machine runs (they only queued, for minutes): refused
    (["sweep", "missing.yaml", "--workers", "1000"], "--workers = 1000: must be 0.."),
    (["batch", "missing.yaml", "--jobs", "1000"], "--jobs = 1000: must be 0.."),
    # a choice option's value not among its choices, as typed (the parser said "Invalid value")
    (["shoe", "--format", "obj"], "--format = obj: must be one of stl, 3mf, both"),
    (["gears", "--bore-shape=square"], "--bore-shape = square: must be one of round, d-flat, keyway, hex"),
])
def test_errors_name_the_parameter_as_written(cli, tmp_path, args, shown):
    assert error_line(cli(*args)).startswith(f"wheelstep: error: {shown}")


def test_a_mesh_that_fails_its_own_check_is_wheelsteps_defect_exit_1_nothing_written(
        tmp_path, monkeypatch, capsys):
    from types import SimpleNamespace

    from wheelstep_cli.cli import run
    from wheelstep_cli.errors import DesignError, MeshDefect
    from wheelstep_cli.geometry import mesh_checks

    assert not issubclass(MeshDefect, DesignError)     # no input is named or blamed for it
    broken = SimpleNamespace(ok=False, watertight=False, winding_consistent=True, volume=1.0,
                             expected_volume=1.0)
    monkeypatch.setattr(mesh_checks, "check_part", lambda part: broken)
    assert run(["shoe", "--width", "40", "--out", str(tmp_path / "out")]) == 1
    line = capsys.readouterr().err.strip()
    assert line.startswith("wheelstep: error: the ") and "failed the print check" in line
    assert "a defect of wheelstep" in line and "--width" not in line
    assert not (tmp_path / "out").exists()


def test_a_choice_typed_in_capitals_is_that_choice(cli, tmp_path):
    """`--format STL` (extensions are often written in capitals) is `--format stl`; a word
    that is no choice is still refused."""
    result = cli("gears", "--format", "STL", "--corner", "Space", "--dry-run", "--out", tmp_path / "o")
    assert result.exit_code == 0, result.stderr
    assert "pinion.stl" in result.stdout and "3mf" not in result.stdout
    assert cli("gears", "--format", "STP", "--dry-run", "--out", tmp_path / "o").exit_code == 2


def test_verbose_says_which_file_a_profile_name_was_read_from(cli, tmp_path, monkeypatch):
    """A profiles/ folder in the working folder comes before the shipped presets: -v says
    which file `--profile desk-demo` was read from, so a local copy never acts unseen."""
    from wheelstep_cli.config.profiles import shipped_profiles

    shipped = cli("shoe", "--profile", "desk-demo", "-v", "--dry-run", "--out", tmp_path / "a")
    assert f"  profile = desk-demo ({shipped_profiles() / 'desk-demo.yaml'})\n" in shipped.stderr
    (tmp_path / "profiles").mkdir()
    (tmp_path / "profiles" / "desk-demo.yaml").write_bytes((shipped_profiles() / "desk-demo.yaml").read_bytes())
    monkeypatch.chdir(tmp_path)
    local = cli("shoe", "--profile", "desk-demo", "-v", "--dry-run", "--out", tmp_path / "b")
    assert f"  profile = desk-demo ({Path.cwd() / 'profiles' / 'desk-demo.yaml'})\n" in local.stderr


@pytest.mark.parametrize("args, option, remedy", [
    (["kinematics", "--a", "-5"], "--a", {}),                          # a value's own limit
    (["stairs", "--rise", "abc"], None, {}),                             # not a number at all
    (["gears", "--z", "30", "--format", "stl", "--dry-run"], "--z", "said"),  # the bounds, the remedy said
])
def test_a_refusal_asked_for_json_is_json_on_stdout_too(cli, args, option, remedy):
    """A script reading a --json command's stdout gets the refusal there too: its exit code, the
    line said on stderr and, for bad input, the option, the value and the remedy (options: those
    the line says to use)."""
    result = cli(*args, "--json")
    line = error_line(result)
    error = json.loads(result.stdout)["error"]
    assert error["exit_code"] == 2 and error["message"] == line
    if remedy == "said":
        words = remedy_in(line)
        remedy = {flag: float(value) for flag, value in zip(words[::2], words[1::2])}
        assert remedy.get("--z", 30) > 30, line
    assert error["option"] == option and error["remedy"] == remedy
    assert error["remedies"] == ([remedy] if remedy else []) and error["problems"] == []
    if option is not None:
        assert error["value"] == float(args[args.index(option) + 1])
    plain = cli(*args)
    assert plain.stdout == "" and error_line(plain) == line            # without --json: stderr only


def test_an_argument_refused_asked_for_json_is_named_as_its_line_names_it(cli, tmp_path):
    """A refused argument (mesh-check's PINION) is no option: --json names it as the line does."""
    result = cli("mesh-check", tmp_path / "nope.stl", tmp_path / "nope2.stl", "--json")
    line = error_line(result)
    assert line.startswith("wheelstep: error: pinion = ")
    assert json.loads(result.stdout)["error"]["option"] == "pinion"


def test_a_refusal_said_at_a_profile_s_line_is_that_problem_in_json_too(cli, tmp_path):
    """A design profile's value refused by a rule (the cutter's tip land) is said at its line;
    --json says the same problem there (it named --fillet, the rule's own option, and no line)."""
    profile = tmp_path / "mine.yaml"
    profile.write_text("gears:\n  z: 48\n  dedendum: 1.9\n")
    result = cli("gears", "--profile", profile, "--dry-run", "--json", "--out", tmp_path / "out")
    line = error_line(result)
    assert line.startswith(f"wheelstep: error: {profile}:3: gears.dedendum = 1.9: leaves the cutter tip"), line
    error = json.loads(result.stdout)["error"]
    assert error["option"] is None and error["message"] == line
    assert error["problems"] == [{"where": f"{profile}:3", "key": "gears.dedendum",
                                  "message": line.split(f"{profile}:3: ", 1)[1]}]


JSON_ERROR_KEYS = {"exit_code", "message", "option", "value", "remedy", "remedies", "problems"}


@pytest.mark.parametrize("command", ["batch", "sweep"])
def test_a_file_s_problems_asked_for_json_are_json_too_each_at_its_line(cli, tmp_path, command):
    """An invalid batch or sweep file is refused with every problem at its file:line on stderr
    and, asked for --json, the same object as any refusal, each problem with its line and key
    (it printed nothing on stdout)."""
    text = ("parts:\n  - name: thin\n    kind: shoe\n    design: desk-demo\n    overrides:\n"
            "      width: 0.2\n      widht: 3\n" if command == "batch" else
            "command: gears\ndesign: desk-demo\ngrid:\n  pressure_angle: [20, 200]\n  backlsh: [0.1]\n")
    path = tmp_path / "in.yaml"
    path.write_text(text)
    result = cli(command, path, "--out", tmp_path / "out", "--json")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    error = json.loads(result.stdout)["error"]
    assert set(error) == JSON_ERROR_KEYS and error["message"] == result.stderr.strip()
    lines = result.stderr.strip().splitlines()
    assert len(error["problems"]) == len(lines) == 2
    for problem, line in zip(error["problems"], lines):
        assert line == f"wheelstep: error: {problem['where']}: {problem['message']}"
        assert problem["where"].startswith(f"{path}:") and problem["message"].startswith(problem["key"])


def test_an_interfering_pair_refused_asked_for_json_is_json_with_the_switch_that_writes_it(cli, tmp_path):
    """Paper teeth that interfere are a failed check (exit 1), not bad input: asked for --json
    the refusal is the same object, its remedy the switch that writes them anyway; applied,
    they are written."""
    args = ["gears", "--profile", "desk-demo", "--teeth", "paper", "--module", "1.48", "--format", "stl",
            "--out", tmp_path / "out"]
    result = cli(*args, "--json")
    line = error_line(result, code=1)
    assert line.startswith("wheelstep: refused: the teeth interfere at ") and not (tmp_path / "out").exists()
    error = json.loads(result.stdout)["error"]
    assert set(error) == JSON_ERROR_KEYS and error["exit_code"] == 1 and error["message"] == line
    assert error["remedy"] == {"--allow-interference": True} and error["option"] is None
    assert cli(*args, *error["remedy"]).exit_code == 0
