"""A refusal marks a value the user did not give as the default, and only then: the value
must be the number the option's help states as its default, with nothing else (a flag in
any spelling, a profile, a printer, other inputs it is worked out from) that gave it."""

from __future__ import annotations

import pytest

from tests.helpers.clicheck import error_line

SMALL_SHOE = ["--dry-run", "--a", "0.06", "--b", "0.1", "--rmin", "0.02"]


@pytest.mark.parametrize("args, expect", [
    # not given, the help's default: marked, in the line's own value and in the rule it ties to
    (["stairs", "--run", "0.5"], "--run = 0.5: with it, landing-angle = -90 (the default) fails: "),
    (["shoe", *SMALL_SHOE], "--a = 0.06: with it, strut-diameter = 12 (the default) fails: "),
    (["trajectory", "-H", "1e6", "--r1", "0.01", "--h-max", "1e6"], "-H = 1e6: with it, spacing = 1 (the default) fails: "),
    # a default while another option is not given (h-max: 100 if no --r3)
    (["trajectory", "--r1", "200"], "--r1 = 200: with it, h-max = 100 (the default) fails: "),
    # given in any of the parser's spellings: named as typed, never marked
    (["teeth", "-m10"], "-m = 10: too large for the tooth pitch"),
    (["teeth", "--module=10"], "--module = 10: too large for the tooth pitch"),
    (["shoe", *SMALL_SHOE, "--strut-diameter=12"], "--strut-diameter = 12: "),
    # a printer's compensation changed it: not the default any more
    (["shoe", *SMALL_SHOE, "--printer", "fdm-0.4-pla"], "--a = 0.06: with it, strut-diameter = 12.2 fails: "),
    # worked out from a value given (c = R_min - a + 4b, not the help's 360): said of that one
    (["pitch", "--b", "3000"], "--b = 3000: must be <= 2510 mm (the strut c = R_min - a + 4b = 11960 mm"),
    # the limit already says it is a default nobody gave
    (["teeth", "--backlash", "144"], "--backlash = 144: with it, module = 2 fails: the paper teeth's default module (none given)"),
])
def test_a_value_is_marked_as_the_default_only_when_it_is_one(cli, args, expect):
    line = error_line(cli(*args))
    assert line.startswith(f"wheelstep: error: {expect}"), line


def test_a_profile_may_give_what_the_command_line_does_not_so_nothing_is_marked(cli, tmp_path):
    profile = tmp_path / "p.yaml"
    profile.write_text("shoe:\n  width: 40\n")
    line = error_line(cli("shoe", "--profile", profile, *SMALL_SHOE))
    assert line.startswith("wheelstep: error: --a = 0.06: with it, strut-diameter = 12 fails: "), line


def test_only_options_documenting_one_number_have_a_default_to_mark():
    """A default that is a rule (0.25 x module) or an address read from the environment is
    no number a value can be compared with: such options are never marked."""
    import typer

    from wheelstep_cli.cli import app
    from wheelstep_cli.cli.naming import _documented_defaults

    group = typer.main.get_command(app)
    teeth = _documented_defaults(group, ["teeth"])
    assert teeth["module"] == 2 and "backlash" not in teeth
    assert "scheduler" not in _documented_defaults(group, ["sweep"])
    assert _documented_defaults(group, ["stairs"])["landing_angle"] == -90
    # "100 if no --r3": that number while --r3 is not given, none with it
    assert _documented_defaults(group, ["trajectory"])["h_max"] == 100
    assert "h_max" not in _documented_defaults(group, ["trajectory", "--r3=400"])
    # a default said with where it comes from is that number; a rule with numbers of its own
    # (paper teeth roll 0.5 mm inside the installed distance) and a list are none
    assert _documented_defaults(group, ["mesh-check"])["distance"] == 144
    gears = _documented_defaults(group, ["gears"])
    assert "center_distance" not in gears and "install_distance" not in gears


@pytest.mark.parametrize("command", ["pitch", "gears"])
def test_a_strut_too_long_for_the_crank_given_is_said_of_the_crank(cli, tmp_path, command):
    """--b 3000 sets the strut c = R_min - a + 4b = 11960 mm, past the longest length taken:
    the line named --c (not given) with the strut's limit; it names --b with the largest crank
    that keeps the strut within it, which applied is taken and 0.01 mm more is not."""
    out = ["--dry-run", "--out", tmp_path / "out"] if command == "gears" else []
    line = error_line(cli(command, "--b", "3000", *out))
    assert line.startswith("wheelstep: error: --b = 3000: must be <= 2510 mm (the strut c = R_min - a + 4b = "
                           "11960 mm they set must be <= 10000 mm)"), line
    assert cli(command, "--b", "2510", *out).exit_code == 0
    assert cli(command, "--b", "2510.01", *out).exit_code == 2
    assert error_line(cli(command, "--b", "3000", "--a", "1979", *out)).startswith(
        "wheelstep: error: --b = 3000: must be <= 2989.75 mm")
