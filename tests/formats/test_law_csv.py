"""A law CSV is read row by row: a line that is not a row of two plain numbers (after the
header lines) is refused naming its line, never skipped — a skipped typo changes the law."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.helpers.clicheck import error_line
from wheelstep_cli.errors import DesignError
from wheelstep_cli.formats.law_csv import read_law_csv

DRIVING = np.arange(0.0, 180.01, 2.5)
ROWS = [f"{a:.6f},{a / 2 + 3 * np.sin(np.radians(2 * a)):.6f}" for a in DRIVING]


def _write(tmp_path, rows, header=("driving_deg,driven_deg",)):
    path = tmp_path / "law.csv"
    path.write_text("\n".join([*header, *rows]) + "\n")
    return path


@pytest.mark.parametrize("line, text, why", [
    (31, "72O500000,37.970729", "line 32: '72O500000,37.970729' is not a row of two plain numbers "
                                "(headers and notes go before the rows)"),
    (31, "7_5.000000,39.000000", "line 32: '7_5.000000,39.000000' is not a row of two plain numbers"),
    (31, "75,nan", "line 32: 'nan' is not a plain number"),
    (31, "75,3_9", "line 32: '3_9' is not a plain number"),
    (5, "12.5,6.25,3", "line 6: has 3 values; a row is 'driving_deg, driven_deg'"),
    (5, "driving,driven", "line 6: 'driving,driven' is not a row of two plain numbers"),
])
def test_a_bad_row_is_refused_naming_its_line(cli, tmp_path, line, text, why):
    rows = list(ROWS)
    rows[line - 1] = text
    path = _write(tmp_path, rows)
    found = error_line(cli("gears", "--law-csv", path, "--dry-run", "--out", tmp_path / "out"))
    assert found.startswith(f"wheelstep: error: --law-csv = {path}: {why}"), found


def test_headers_blank_lines_semicolons_and_trailing_separators_are_read(tmp_path):
    plain = read_law_csv(_write(tmp_path, ROWS))
    other = read_law_csv(_write(tmp_path, ["", *(r.replace(",", ";") + ";" for r in ROWS), "", "# end",
                                           "\x1a"], header=("\ufeff# a law from a spreadsheet", "period;360",
                                                             "in;out")))
    theta = np.linspace(0.0, 3.0, 7)
    assert np.array_equal(plain.carrier_angle(theta), other.carrier_angle(theta))
    # a comment after a row, as after a header (README: `#` comments anywhere)
    noted = read_law_csv(_write(tmp_path, [f"{r}  # note {k}" for k, r in enumerate(ROWS)],
                                header=("driving_deg,driven_deg # degrees",)))
    assert np.array_equal(plain.carrier_angle(theta), noted.carrier_angle(theta))


def test_too_few_rows_is_one_line(tmp_path):
    with pytest.raises(DesignError, match="needs at least 8 numeric rows"):
        read_law_csv(_write(tmp_path, ROWS[:5]))


@pytest.mark.parametrize("change, why", [
    # a row repeated: the driving angle stands still
    (lambda rows: rows[:20] + [rows[19]] + rows[20:],
     "line 22: the driving angle 47.5 deg does not increase past 47.5 deg (line 21); both angles "
     "increase strictly over one period"),
    # a kink half-way: the rows are a period but no smooth law (said of the file, not of a residual)
    (lambda rows: [f"{a:.6f},{(0.7 * a if a <= 90 else 63 + 0.3 * (a - 90)):.6f}" for a in DRIVING],
     "the samples do not fit a smooth periodic law: they stray up to "),
    # the last row left out: 177.5 deg is no 360/k
    (lambda rows: rows[:-1], "the driving angle spans 177.5 deg from line 2 to line 73; it must span "
                             "360/k deg (k whole: closed gears)"),
])
def test_rows_that_are_no_period_are_refused_naming_the_lines(cli, tmp_path, change, why):
    path = _write(tmp_path, change(list(ROWS)))
    found = error_line(cli("gears", "--law-csv", path, "--dry-run", "--out", tmp_path / "out"))
    assert found.startswith(f"wheelstep: error: --law-csv = {path}: {why}"), found


def _seventh(decimals: int, last_driving: float | None = None) -> list[str]:
    """A law over 360/7 deg of the driving angle (k = 7) written to ``decimals`` decimals."""
    period = 360.0 / 7.0
    driving = np.linspace(0.0, period, 37)
    driven = 3.5 * driving + 2.0 * np.sin(2.0 * np.pi * driving / period)
    if last_driving is not None:
        driving[-1] = last_driving
    return [f"{a:.{decimals}f},{b:.{decimals}f}" for a, b in zip(driving, driven)]


def test_a_period_rounded_to_the_decimals_written_is_one_period(tmp_path):
    """360/7 deg written to 2 decimals spans 51.43 deg: within the decimals written it is one
    period, so the law is read with the exact period and matches the finely written one."""
    coarse = read_law_csv(_write(tmp_path, _seventh(2)))
    fine = read_law_csv(_write(tmp_path, _seventh(9)))
    assert coarse.theta_period == pytest.approx(2.0 * np.pi / 7.0, abs=1e-15)
    assert coarse.phi_period == pytest.approx(np.pi, abs=1e-15)
    theta = np.linspace(0.0, 2.0 * np.pi / 7.0, 11)
    # within the rounding: 0.005 deg of driven angle, and 0.005 deg of driving at a ratio of 3.5
    rounding = np.radians(0.005 + 3.5 * 0.005)
    assert np.max(np.abs(coarse.carrier_angle(theta) - fine.carrier_angle(theta))) < rounding


@pytest.mark.parametrize("first", [None, "0,0"])
def test_a_span_off_by_more_than_its_decimals_is_still_refused(tmp_path, first):
    """51.45 for 360/7 in rows of 2 decimals; also with the first row written as whole
    numbers (exact, not +- 0.5 deg of slack)."""
    rows = _seventh(2, last_driving=51.45)
    rows[0] = first or rows[0]
    with pytest.raises(DesignError, match="the driving angle spans 51.45 deg from line 2 to line 38"):
        read_law_csv(_write(tmp_path, rows))


def test_a_tooth_count_the_laws_periods_do_not_divide_is_said_of_the_csv_with_counts_that_do(cli, tmp_path):
    """A law of 7 periods per pinion turn and the default 48 teeth: the line names the CSV
    the user gave (not a --z they did not) and the nearest counts; one applied is built."""
    path = _write(tmp_path, _seventh(6))
    line = error_line(cli("gears", "--law-csv", path, "--dry-run", "--out", tmp_path / "out"))
    assert line == (f"wheelstep: error: --law-csv = {path}: with it, z = 48 (the default) fails: must be a multiple of 7 "
                    "(law periods per pinion turn) and >= 6; use --z 42 or use --z 49")
    # near the tooth limit (240) only the counts a design may have
    top = error_line(cli("gears", "--law-csv", path, "--z", "240", "--dry-run", "--out", tmp_path / "out"))
    assert top.endswith("; use --z 238"), top
    result = cli("gears", "--law-csv", path, "--z", "49", "--dry-run", "--out", tmp_path / "out")
    assert result.exit_code == 0, result.stderr


def test_a_batch_entrys_law_csv_whose_periods_do_not_divide_its_teeth_is_refused_at_its_line(cli, tmp_path):
    """The same rule for a batch entry: refused before any build (exit 2, nothing written), at
    the entry's law_csv line, with the counts that fit."""
    path = _write(tmp_path, _seventh(6))
    batch = tmp_path / "b.yaml"
    batch.write_text(f"parts:\n  - name: pair\n    kind: gear-pair\n    printer: fdm-0.4-pla\n"
                     f"    overrides:\n      law_csv: {path}\n")
    result = cli("batch", batch, "--out", tmp_path / "out")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert error_line(result) == (f"wheelstep: error: {batch}:6: parts[0].overrides.law_csv = '{path}': with "
                                  "it, z = 48 fails: must be a multiple of 7 (law periods per pinion turn) "
                                  "and >= 6; use z: 42 or use z: 49")


def test_a_plate_keeps_its_law_csvs_digest_and_is_checked_only_with_that_file(cli, tmp_path, monkeypatch):
    """A plate's design names its law CSV by the path given where it was made: checked from
    another folder the plate is named with what it lacks (not a --law-csv never given), and
    a CSV changed since is refused (it would check another law)."""
    monkeypatch.chdir(tmp_path)
    _write(tmp_path, ROWS)
    result = cli("gears", "--law-csv", "law.csv", "--format", "3mf", "--out", "out")
    assert result.exit_code == 0, result.stderr
    plates = sorted(str(p.relative_to(tmp_path)) for p in (tmp_path / "out").glob("gears*.3mf"))
    assert cli("mesh-check", *plates, "--samples", "384").exit_code == 0
    monkeypatch.chdir(tmp_path / "out")
    line = error_line(cli("mesh-check", *(Path(p).name for p in plates), "--samples", "384"))
    assert line.startswith("wheelstep: error: pinion = gears-") and "its design's law CSV 'law.csv'" in line
    assert line.endswith("cannot be read from here: run where the plate was made, or put the CSV at that path")
    monkeypatch.chdir(tmp_path)
    _write(tmp_path, ROWS[:-1] + ["180.000000,90.000001"])
    line = error_line(cli("mesh-check", *plates, "--samples", "384"))
    assert "is not the file the plate was made with" in line and "the law changed since" in line, line
