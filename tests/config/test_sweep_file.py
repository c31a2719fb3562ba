"""Sweep files: the points a grid, random samples and printers expand to, and their limits."""

from __future__ import annotations

import pytest

from tests.helpers.files import write
from wheelstep_cli.config.schema import InvalidInput
from wheelstep_cli.config.sweep_file import MAX_POINTS, load_sweep


def test_grid_ranges_include_the_stop_without_float_drift(tmp_path):
    plan = load_sweep(write(tmp_path / "s.yaml", """\
command: gears
grid:
  backlash: {start: 0.1, stop: 0.5, step: 0.1}
  z: [18, 24]
fixed: {thickness: 4}
printers: [fdm-0.4-pla, fdm-0.4-petg]
"""))
    assert plan.axes == ("backlash", "z") and len(plan.points) == 2 * 5 * 2
    backlashes = sorted({values["backlash"] for _, values in plan.points})
    assert backlashes == [0.1, 0.2, 0.3, 0.4, 0.5]
    assert {printer for printer, _ in plan.points} == {"fdm-0.4-pla", "fdm-0.4-petg"}
    assert all(values["thickness"] == 4 for _, values in plan.points)
    assert plan.objectives == ("drive_f_i_um", "backlash_max_mm")


def test_random_samples_are_seeded_and_within_bounds(tmp_path):
    text = """\
command: shoe
random:
  seed: 7
  samples: 20
  bounds:
    width: {low: 10, high: 14}
    rim: {low: 5.5, high: 9.0}
"""
    first = load_sweep(write(tmp_path / "a.yaml", text)).points
    again = load_sweep(write(tmp_path / "b.yaml", text)).points
    assert first == again and len(first) == 20
    widths = [values["width"] for _, values in first]
    assert all(isinstance(w, int) and 10 <= w <= 14 for w in widths) and len(set(widths)) > 1
    assert all(5.5 <= values["rim"] <= 9.0 for _, values in first)
    other = load_sweep(write(tmp_path / "c.yaml", text.replace("seed: 7", "seed: 8"))).points
    assert other != first


def test_structure_problems_each_at_its_line(tmp_path):
    with pytest.raises(InvalidInput) as err:
        load_sweep(write(tmp_path / "s.yaml", """\
command: drill
grid:
  z: 5
extra: 1
"""))
    lines = err.value.lines()
    assert any("s.yaml:1: command" in line for line in lines)
    assert any("s.yaml:4: extra: unknown key" in line for line in lines)
    assert any("s.yaml:3: grid.z = 5: must be a list of values" in line for line in lines)
    assert MAX_POINTS == 10_000


@pytest.mark.parametrize("grid, expect", [
    # a tiny step: refused at its line before its values are listed (1e10 of them filled the memory)
    ("  width: {start: 20, stop: 30, step: 1.0e-9}\n",
     "s.yaml:3: grid.width: range 20..30 step 1e-09 holds 10000000001 values; a sweep has at most 10000 points"),
    # two axes within the limit whose product is not: counted, not listed
    ("  width: {start: 20, stop: 30, step: 0.01}\n  a: {start: 100, stop: 200, step: 0.02}\n",
     "s.yaml:1: the sweep has 5006001 points; at most 10000"),
    # too many to count: a float overflow, not a traceback
    ("  width: {start: 0, stop: 20, step: 1.0e-320}\n", "holds too many values; a sweep has at most 10000 points"),
    ("  width: {start: -1.0e+308, stop: 1.0e+308, step: 1}\n", "holds too many values; a sweep has at most"
                                                               " 10000 points"),
])
def test_a_sweep_too_large_is_refused_before_its_points_are_listed(tmp_path, monkeypatch, grid, expect):
    import wheelstep_cli.config.sweep_file as sweep_file

    def listed(*args):
        raise AssertionError("the points were listed")

    monkeypatch.setattr(sweep_file, "_points", listed)
    with pytest.raises(InvalidInput) as info:
        load_sweep(write(tmp_path / "s.yaml", "command: shoe\ngrid:\n" + grid))
    assert [line.endswith(expect) for line in info.value.lines()] == [True], info.value.lines()


def test_tolerance_needs_printers_with_a_band(tmp_path):
    """``tolerance: true`` on a printer profile without a ``band:`` is refused at its line
    (never taken as a perfect printer); with the presets (all have one) it is planned."""
    from pathlib import Path

    preset = (Path(__file__).resolve().parents[2] / "profiles" / "fdm-0.4-pla.yaml").read_text()
    write(tmp_path / "noband.yaml", preset.split("band:")[0] + "material:" + preset.split("material:")[1])
    sweep = write(tmp_path / "s.yaml", f"command: gears\ntolerance: true\nprinters:\n  - fdm-0.4-pla\n"
                                       f"  - {tmp_path / 'noband.yaml'}\n")
    with pytest.raises(InvalidInput) as err:
        load_sweep(sweep)
    (line,) = err.value.lines()
    assert line.startswith(f"{sweep}:5: printers[1] = ") and "has no dimensional band" in line
    ok = write(tmp_path / "ok.yaml", "command: gears\ntolerance: true\nprinters: [fdm-0.4-pla]\n")
    assert load_sweep(ok).tolerance is True


def test_a_gear_sweep_refuses_a_printer_whose_band_names_a_fit(tmp_path):
    """A sweep does not search each design's fit, so a printer whose band names one (and
    whose pairs `gears` would fit) is refused at its line with what to do instead."""
    from pathlib import Path

    preset = (Path(__file__).resolve().parents[2] / "profiles" / "fdm-0.4-pla.yaml").read_text()
    fitted = preset.replace("  center_distance: 0.05\n", "  center_distance: 0.05\n  fit: normal\n")
    assert fitted != preset
    write(tmp_path / "fitted.yaml", fitted)
    for tolerance in ("", "tolerance: true\n"):
        sweep = write(tmp_path / "s.yaml", f"command: gears\n{tolerance}printers:\n  - fdm-0.4-pla\n"
                                           f"  - {tmp_path / 'fitted.yaml'}\n")
        with pytest.raises(InvalidInput) as err:
            load_sweep(sweep)
        (line,) = err.value.lines()
        row = 4 + bool(tolerance)
        assert line.startswith(f"{sweep}:{row}: printers[1] = ") and "its band names fit: normal" in line
        assert f"wheelstep gears --printer {tmp_path / 'fitted.yaml'}" in line


def test_a_value_listed_twice_on_an_axis_is_refused_at_its_line(tmp_path):
    """`rim: [8, 9, 8.0]` made one point of 8 and 8.0: '3 designs computed', 2 rows."""
    sweep = write(tmp_path / "s.yaml", "command: shoe\ngrid:\n  width: [12]\n  rim: [8, 9, 8.0]\n")
    with pytest.raises(InvalidInput) as err:
        load_sweep(sweep)
    assert err.value.lines() == [f"{sweep}:4: grid.rim[2] = 8: repeats grid.rim[0] = 8; list each "
                                 "value once"]
    plan = load_sweep(write(tmp_path / "t.yaml", "command: shoe\ngrid:\n  rim: [8, 9, 8.5]\n"))
    assert [values["rim"] for _, values in plan.points] == [8, 9, 8.5]
    # a printer listed twice doubled the points likewise
    sweep = write(tmp_path / "p.yaml", "command: shoe\nprinters: [fdm-0.4-pla, fdm-0.4-petg, fdm-0.4-pla]\n"
                  "grid:\n  rim: [8, 9]\n")
    with pytest.raises(InvalidInput) as err:
        load_sweep(sweep)
    assert err.value.lines() == [f"{sweep}:2: printers[2] = 'fdm-0.4-pla': repeats printers[0]; list "
                                 "each printer once"]


def test_a_range_whose_values_are_kept_alike_is_refused(tmp_path):
    """A step finer than the 12 decimals a range's values are kept to would make five points
    of one value (five designs said computed, one row)."""
    sweep = write(tmp_path / "s.yaml", "command: shoe\ngrid:\n  rim: {start: 10, stop: 10.0000000000005, "
                                       "step: 0.0000000000001}\n")
    with pytest.raises(InvalidInput) as err:
        load_sweep(sweep)
    assert err.value.lines() == [f"{sweep}:3: grid.rim: step 1e-13 is too fine: its values round alike to 12 "
                                 "decimals (one point where several are asked for); give a coarser step"]
    plan = load_sweep(write(tmp_path / "t.yaml", "command: shoe\ngrid:\n  rim: {start: 10, stop: 10.000000000005, "
                                                 "step: 0.000000000001}\n"))
    assert len({values["rim"] for _, values in plan.points}) == len(plan.points) == 6


def test_random_draws_are_different_points(tmp_path):
    """Whole-number bounds repeat values: each draw is a new point (three rows for three
    samples), and more samples than the bounds hold points are refused at their line."""
    text = "command: shoe\nrandom:\n  seed: 1\n  samples: {n}\n  bounds: {{rim: {{low: 6, high: 10}}}}\n"
    for n in (3, 5):
        plan = load_sweep(write(tmp_path / f"s{n}.yaml", text.format(n=n)))
        rims = [values["rim"] for _, values in plan.points]
        assert len(set(rims)) == len(rims) == n and set(rims) <= set(range(6, 11)), rims
    sweep = write(tmp_path / "s.yaml", text.format(n=6))
    with pytest.raises(InvalidInput) as err:
        load_sweep(sweep)
    assert err.value.lines() == [f"{sweep}:4: random.samples = 6: more than the 5 different points "
                                 "the bounds hold (whole numbers, or decimals to 9 places); at most 5"]
    # decimal bounds that hold one value (they drew it again and again, for ever)
    for low, high in (("8.5", "8.5"), ("8", "8.0")):
        one = write(tmp_path / "one.yaml", text.format(n=2).replace("low: 6, high: 10", f"low: {low}, high: {high}"))
        with pytest.raises(InvalidInput) as err:
            load_sweep(one)
        assert "random.samples = 2: more than the 1 different point the bounds hold" in err.value.lines()[0]


def test_profiles_a_sweep_file_names_by_path_are_found_beside_it(tmp_path, monkeypatch):
    """printers: [mine.yaml] and design: demo.yaml beside the sweep file, run from another
    folder: found there (as a batch file's are), recorded as paths from the working folder."""
    from pathlib import Path

    profiles = Path(__file__).resolve().parents[2] / "profiles"
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    (jobs / "mine.yaml").write_text((profiles / "fdm-0.4-pla.yaml").read_text())
    (jobs / "demo.yaml").write_text((profiles / "desk-demo.yaml").read_text())
    sweep = write(jobs / "s.yaml", "command: shoe\ndesign: demo.yaml\nprinters: [mine.yaml]\ngrid:\n  rim: [8, 9]\n")
    monkeypatch.chdir(tmp_path)             # no mine.yaml here: only the sweep file's folder has one
    plan = load_sweep(sweep)
    assert plan.design == "jobs/demo.yaml"
    assert {printer for printer, _ in plan.points} == {"jobs/mine.yaml"}
