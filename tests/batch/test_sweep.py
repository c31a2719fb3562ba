"""`wheelstep sweep`: a sweep file's points computed on Dask (a local cluster, or a scheduler
and workers started here as subprocesses) give the same rows; refusals are rows; a worker
killed mid-sweep costs nothing; an unreachable scheduler and bad axes are refused at once.
`batch --scheduler` too. Interruptions and crashes: test_sweep_interrupts.py."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pyarrow.parquet as pq
import pytest

from tests.helpers.clicheck import error_line, remedy_in
from tests.helpers.files import SMALL_BATCH, write
from tests.helpers.sweeps import POINTS, SHOES, rows
from wheelstep_cli.cli.commands.sweep import _BEST_FILES

def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _start(*args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", *args], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGKILL)
    proc.wait(timeout=30)


@pytest.fixture(scope="module")
def cluster():
    """A `dask scheduler` and two single-process, single-thread `dask worker`s on localhost."""
    from distributed import Client

    address = f"tcp://127.0.0.1:{_free_port()}"
    port = address.rsplit(":", 1)[1]
    scheduler = _start("distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", port,
                       "--dashboard-address", ":0")
    workers = [_start("distributed.cli.dask_worker", address, "--nworkers", "1", "--nthreads", "1",
                      "--no-dashboard", "--name", f"w{i}") for i in range(2)]
    try:
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(2, timeout=60)
        yield address, workers
    finally:
        for proc in [*workers, scheduler]:
            _stop(proc)


def test_local_cluster_rows_and_refused_point(cli, tmp_path, monkeypatch):
    from wheelstep_cli.render import sweep_plot

    plotted = []
    drawn = sweep_plot.pareto_png
    monkeypatch.setattr(sweep_plot, "pareto_png", lambda *args: plotted.append(args) or drawn(*args))
    sweep = write(tmp_path / "shoes.yaml", SHOES)
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "2", "-q", "--json")
    assert result.exit_code == 1, result.stderr      # some points refused
    found = rows(tmp_path / "out")
    assert len(found) == POINTS
    refused = [r for r in found.values() if r["outcome"] == "refused"]
    assert {r["p_socket_depth"] for r in refused} == {60.0} and len(refused) == 3
    assert all("socket_depth = 60" in r["reason"] for r in refused)
    ok = [r for r in found.values() if r["outcome"] == "ok"]
    assert sorted(r["p_rim"] for r in ok) == [10.0, 12.0, 14.0]
    assert all(r["volume_mm3"] > 0 and r["mass_g"] > 0 for r in ok)
    assert all(json.loads(r["parameters"])["width"] == 12 for r in ok)
    csv_lines = (tmp_path / "out" / "results.csv").read_text().splitlines()
    assert len(csv_lines) == POINTS + 1 and csv_lines[0].startswith('"key"')
    assert (tmp_path / "out" / "pareto.png").read_bytes()[:4] == b"\x89PNG"
    # each design plotted is named by the values the sweep varied
    first, second, _, _, _, labels = plotted[0]
    assert sorted(labels) == sorted(f"socket_depth 10 rim {r['p_rim']:g}" for r in ok)
    assert sorted(zip(first, labels)) == sorted((r["volume_mm3"], f"socket_depth 10 rim {r['p_rim']:g}")
                                                for r in ok)
    assert json.loads(result.stdout)["computed"] == POINTS
    # a rerun computes nothing, but its table still holds the refused rows: exit 1, said so
    again = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1")
    assert again.exit_code == 1, again.stderr
    assert f"0 designs computed (0 refused or failed), {POINTS} already in " in again.stdout
    assert "(3 of them refused or failed)" in again.stdout, again.stdout


def without_seconds(csv: Path) -> list[str]:
    """The CSV's lines without their last column (seconds: the one that differs by design)."""
    lines = csv.read_text().splitlines()
    assert lines[0].endswith('"seconds"')
    return [line.rsplit(",", 1)[0] for line in lines]


def test_scheduler_gives_the_same_rows(cli, tmp_path, cluster):
    """Two runs on different clusters (other workers, other completion order) write the same
    files but for the seconds column: rows in point order."""
    address, _ = cluster
    sweep = write(tmp_path / "shoes.yaml", SHOES)
    assert cli("sweep", sweep, "--out", tmp_path / "local", "--workers", "2", "-q").exit_code == 1
    remote = cli("sweep", sweep, "--out", tmp_path / "remote", "--scheduler", address, "-q")
    assert remote.exit_code == 1, remote.stderr
    local, there = rows(tmp_path / "local"), rows(tmp_path / "remote")
    assert local == there
    assert without_seconds(tmp_path / "local" / "results.csv") == \
           without_seconds(tmp_path / "remote" / "results.csv")
    indices = pq.read_table(tmp_path / "remote" / "results.parquet").column("index").to_pylist()
    assert indices == list(range(POINTS))


def test_rows_are_written_in_point_order(tmp_path, monkeypatch):
    """Rows that come in any order (several part files, earlier results) are written in point
    order, each once: the same bytes as when they came in order."""
    from wheelstep_cli.batch import sweep_store
    from wheelstep_cli.batch.sweep_store import ResultStore, schema

    def row(i: int) -> dict:
        return {"key": f"k{i}", "index": i, "command": "shoe", "p_rim": float(i), "outcome": "ok",
                "volume_mm3": 10.0 * i, "versions": "v", "seconds": 0.0}

    columns = schema({"rim": "float"})
    ordered_store = ResultStore(tmp_path / "a", columns)
    for i in range(7):
        ordered_store.add(row(i))
    ordered_store.consolidate()
    monkeypatch.setattr(sweep_store, "FLUSH_ROWS", 2)     # several part files
    first = ResultStore(tmp_path / "b", columns)
    for i in (5, 1, 6):
        first.add(row(i))
    first.consolidate()                     # an interrupted run's rows
    second = ResultStore(tmp_path / "b", columns)
    for i in (4, 0, 3, 2, 6):               # 6 again: merged and still in a part after a crash
        second.add(row(i))
    second.consolidate()
    for name in ("results.csv", "results.parquet"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name


def test_outputs_are_owned(cli, tmp_path):
    """A user's file named like an output is refused before any work (nothing written, the
    file kept); --force overwrites it; a rerun into the sweep's own folder is not refused."""
    sweep = write(tmp_path / "one.yaml", "command: shoe\ndesign: desk-demo\ngrid:\n  width: [12]\n")
    out = tmp_path / "out"
    out.mkdir()
    (out / "results.csv").write_text("my own table\n")
    line = error_line(cli("sweep", sweep, "--out", out, "--workers", "1"))
    assert "--out" in line and "results.csv" in line and "not written by this command" in line
    assert sorted(p.name for p in out.iterdir()) == ["results.csv"]
    assert cli("sweep", sweep, "--out", out, "--workers", "1", "--dry-run").exit_code == 2
    forced = cli("sweep", sweep, "--out", out, "--workers", "1", "--force", "-q", "--json")
    assert forced.exit_code == 0, forced.stderr
    assert (out / "results.csv").read_text() != "my own table\n"
    record = json.loads((out / ".wheelstep-sweep.json").read_text())
    assert sorted(record["files"]) == ["pareto.png", "results.csv", "results.parquet"]
    again = cli("sweep", sweep, "--out", out, "--workers", "1", "-q", "--json")
    assert again.exit_code == 0, again.stderr
    assert (json.loads(again.stdout)["skipped"], json.loads(again.stdout)["computed"]) == (1, 0)
    (out / "pareto.png").write_bytes(b"changed by the user")
    line = error_line(cli("sweep", sweep, "--out", out, "--workers", "1"))
    assert "pareto.png" in line and "changed since this command wrote it" in line
    assert (out / "pareto.png").read_bytes() == b"changed by the user"


def test_tolerance_band_columns_are_the_gears_commands(cli, tmp_path):
    """``tolerance: true``: each pair's band check as ``gears --tolerance`` reports it; the best
    design kept has the report `gears` writes, the bounds' verdict included."""
    sweep = write(tmp_path / "band.yaml", "command: gears\ndesign: desk-demo\ntolerance: true\n"
                                          "printers: [fdm-0.4-pla]\n")      # one point
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1", "-q", "--keep", "best:1")
    assert result.exit_code == 0, result.stderr
    (row,) = rows(tmp_path / "out").values()
    assert row["outcome"] == "ok", row["reason"]
    gears = cli("gears", "--profile", "desk-demo", "--printer", "fdm-0.4-pla", "--tolerance",
                "--dry-run", "--json", "-q", "--out", tmp_path / "g")
    assert gears.exit_code == 0, (gears.stdout, gears.stderr)
    band = json.loads(gears.stdout)["meshing"]["tolerance"]
    assert row["band_jams"] is band["jams"]
    assert row["band_least_backlash_mm"] == pytest.approx(band["least_backlash_mm"], abs=1e-9)
    assert row["band_largest_backlash_mm"] == pytest.approx(band["largest_backlash_mm"], abs=1e-9)
    prefixes = {"tight": "band_tight", "pinion grown, wheel shrunk": "band_pinion_grown",
                "pinion shrunk, wheel grown": "band_wheel_grown", "loose": "band_loose"}
    for case in band["cases"]:
        prefix = prefixes[case["case"]]
        assert row[f"{prefix}_jams"] is case["jams"]
        assert row[f"{prefix}_backlash_min_mm"] == pytest.approx(case["backlash_min_mm"], abs=1e-9)
        assert row[f"{prefix}_drive_f_i_um"] == pytest.approx(case["drive"]["f_i_tooth_um"], abs=1e-9)
    assert row["band_least_backlash_mm"] < row["backlash_min_mm"]   # the band takes play away
    kept = json.loads((tmp_path / "out" / "best-1" / "gears.json").read_text())["meshing"]
    assert kept["bounds"] == json.loads(gears.stdout)["meshing"]["bounds"] and kept["bounds"]["within"]


def test_a_point_too_large_for_its_printers_bed_is_refused_as_gears_refuses_it(cli, tmp_path, monkeypatch):
    """The default pair's 208 mm wheel does not go on the resin bed: the point is refused with
    the line `gears --printer` gives, before its meshing check; the smaller pair `gears` builds
    and offers is the row's try (a sweep builds no remedy)."""
    import wheelstep_cli.parts.mesh_check as mesh_check
    from wheelstep_cli.batch.sweep_point import evaluate, resolve_point, versions
    from wheelstep_cli.config.profiles import load_printer_profile

    def no_check(*args, **kwargs):
        raise AssertionError("the pair was checked before its bed was")

    printer = "resin-0.05-standard"
    point = resolve_point(0, "gears", None, printer, load_printer_profile(printer), {}, False, versions())
    monkeypatch.setattr(mesh_check, "check_gear_pair", no_check)
    row = evaluate(point)           # a crash in it (the check reached) would be a failed row
    assert row["outcome"] == "refused", row
    monkeypatch.undo()      # gears checks the remedy it offers
    line = error_line(cli("gears", "--printer", printer, "--out", tmp_path / "g"))
    cause, remedy = row["reason"].split(": ", 1)[1].split("; nothing written; ")
    assert line.startswith(f"wheelstep: error: --printer = {printer}: {cause}; nothing written; use "), row["reason"]
    assert "does not fit the bed of printer 'resin-0.05-standard'" in line
    distance = remedy_in(line)
    assert distance[0] == "--install-distance" and remedy.startswith(f"try install_distance: {distance[1]} ("), remedy


def test_a_shoe_too_large_for_the_bed_is_a_refused_row_and_not_kept(cli, tmp_path):
    """A shoe sweep's point whose shoe no bed holds is refused as `shoe --printer` refuses it,
    named by the value the sweep varied (on the default printer when the sweep names none,
    whose plate a kept design goes on); --keep then writes only what a plate holds."""
    from wheelstep_cli.batch.sweep_point import evaluate, resolve_point, versions
    from wheelstep_cli.config.profiles import load_design_profile, load_printer

    design, printer = load_design_profile("bntu-2024"), load_printer("fdm-0.4-pla")
    # the command names the sizing input given when the printer is its default one
    line = error_line(cli("shoe", "--profile", "bntu-2024", "--rmin", "400", "--out", tmp_path / "shoe"))
    cause = line.split(" (the default printer", 1)[0].split(": ", 3)[3]
    assert cause.startswith("with it, part 'shoe' is 707.1 x 178.6 mm, larger than the bed of printer 'fdm-0.4-pla'")
    for name, given in ((printer.name, printer), (None, None)):
        row = evaluate(resolve_point(0, "shoe", design, name, given, {"r_min": 400}, False, versions()))
        assert row["outcome"] == "refused", row
        assert row["reason"].startswith(f"r_min = 400: {cause}"), row["reason"]
        assert row["reason"].endswith("(the default printer: the sweep names no printers)") == (name is None)
    # a rule two inputs share, said of the one varied (as `shoe --width 5` says it)
    row = evaluate(resolve_point(0, "shoe", load_design_profile("desk-demo"), printer.name, printer, {"width": 5},
                                 False, versions()))
    assert row["reason"].startswith("width = 5: must be >= 10.20 mm"), row["reason"]
    sweep = write(tmp_path / "s.yaml", "command: shoe\ndesign: bntu-2024\ngrid:\n  r_min: [20, 400]\n"
                  "printers: [fdm-0.4-pla]\n")
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1", "--keep", "best:2")
    assert result.exit_code == 1, result.stderr
    assert sorted(p.name for p in (tmp_path / "out").glob("best-*")) == ["best-1"]
    assert "wheelstep: warning: --keep best:2 keeps 1: the results hold 1 ok design to rank" in result.stderr


def test_tolerance_is_refused_for_shoes(cli, tmp_path):
    sweep = write(tmp_path / "s.yaml", "command: shoe\ntolerance: true\ngrid:\n  width: [12]\n")
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out"))
    assert "s.yaml:2: tolerance = true: the band check is of gear pairs" in line
    # so is keeping interfering teeth: a shoe has none
    sweep = write(tmp_path / "s.yaml", "command: shoe\nallow_interference: true\ngrid:\n  width: [12]\n")
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--dry-run"))
    assert "s.yaml:2: allow_interference = true: keeps gear pairs whose teeth interfere" in line, line
    assert not (tmp_path / "out").exists()


def test_rows_of_other_code_under_the_same_version_are_computed_again(tmp_path, monkeypatch):
    """A resumed sweep reuses a row only when wheelstep's own files are the same: a changed
    checkout (same version number) computes every point again."""
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch import sweep_point
    from wheelstep_cli.batch.sweep_run import run_sweep
    from wheelstep_cli.config.sweep_file import load_sweep

    plan = load_sweep(write(tmp_path / "shoes.yaml", SHOES))
    out = tmp_path / "out"
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as lc, Client(lc) as client:
        run_sweep(plan, out, client)
        assert run_sweep(plan, out, client).computed == 0           # the same code: every row kept
        monkeypatch.setattr(sweep_point, "package_digest", lambda: "another checkout")
        outcome = run_sweep(plan, out, client)
    assert (outcome.skipped, outcome.computed, outcome.dropped) == (0, POINTS, POINTS)
    assert all("another checkout" in row["versions"] for row in rows(out).values())


def test_a_rerun_with_another_grid_keeps_its_own_points_in_its_order(cli, tmp_path):
    """Points left out of the grid are dropped from the results (and counted); points kept
    take their place in the new grid's order."""
    from distributed import Client, LocalCluster

    from wheelstep_cli.batch.sweep_run import run_sweep
    from wheelstep_cli.config.sweep_file import load_sweep

    out = tmp_path / "out"
    first = load_sweep(write(tmp_path / "a.yaml", SHOES))
    # rim 12 and 14 stay, rim 10 goes, rim 8 comes first
    second = load_sweep(write(tmp_path / "b.yaml", SHOES.replace("{start: 10, stop: 14, step: 2}", "[8, 12, 14]")))
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as lc, Client(lc) as client:
        run_sweep(first, out, client)
        before = {row["parameters"]: row for row in rows(out).values()}
        said = cli("sweep", tmp_path / "b.yaml", "--out", out, "--dry-run")
        assert said.exit_code == 0 and ("2 of 6 designs would be computed; 2 earlier rows would be "
                                        "dropped (points no longer in the sweep") in said.stdout, said
        # --json says the files as the lines do: written none, would_write the tables
        planned = json.loads(cli("sweep", tmp_path / "b.yaml", "--out", out, "--dry-run", "--json").stdout)
        assert planned["written"] == [] and str(out / "results.parquet") in planned["would_write"], planned
        assert planned["would_remove"] == [] and planned["would_compute"] == 2
        outcome = run_sweep(second, out, client)
    assert (outcome.total, outcome.skipped, outcome.computed, outcome.dropped) == (6, 4, 2, 2)
    table = pq.read_table(out / "results.parquet").to_pylist()
    assert [row["index"] for row in table] == list(range(6))
    assert ([(row["p_socket_depth"], row["p_rim"]) for row in table]
            == [(values["socket_depth"], values["rim"]) for _, values in second.points])
    kept = {row["parameters"]: row for row in rows(out).values() if row["parameters"] in before}
    assert len(kept) == 4 and all(kept[k]["outcome"] == before[k]["outcome"] for k in kept)


def test_a_point_repeated_in_the_plan_is_one_row_at_its_first_place(tmp_path):
    """A value listed twice is refused in the file (tests/config); two points can still
    coincide where a range's values round alike: the run computes and keeps one row."""
    from dataclasses import replace

    from distributed import Client, LocalCluster

    from wheelstep_cli.batch.sweep_run import run_sweep
    from wheelstep_cli.config.sweep_file import load_sweep

    plan = load_sweep(write(tmp_path / "s.yaml", SHOES.replace("{start: 10, stop: 14, step: 2}", "[10]")))
    plan = replace(plan, points=(*plan.points, plan.points[0]))
    out = tmp_path / "out"
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as lc, Client(lc) as client:
        run_sweep(plan, out, client)
        run_sweep(plan, out, client)                 # the rerun rewrites the indices
    table = pq.read_table(out / "results.parquet").to_pylist()
    assert [(row["index"], row["p_socket_depth"]) for row in table] == [(0, 10), (1, 60)]


def test_unreachable_scheduler_is_one_line(cli, tmp_path):
    sweep = write(tmp_path / "shoes.yaml", SHOES)
    start = time.monotonic()
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--scheduler", "tcp://127.0.0.1:9")
    line = error_line(result)
    assert time.monotonic() - start < 15     # the bound on the refusal, not a benchmark
    assert "--scheduler" in line and "tcp://127.0.0.1:9" in line and "cannot be reached" in line
    assert "(nothing listens at that port); give the address `dask scheduler` prints" in line
    assert not (tmp_path / "out").exists()
    # a name that is no host is said to be one
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--scheduler", "no-such-host.invalid"))
    assert "(its host name does not resolve)" in line and not (tmp_path / "out").exists()


def test_bad_axes_refused_with_every_line(cli, tmp_path):
    sweep = write(tmp_path / "bad.yaml", """\
command: gears
fixed:
  zz: 3
grid:
  z: [18, 2000]
  module: {start: 3, stop: 1, step: 1}
  pressure_angle: {start: 15, stop: 25, step: -1}
random:
  seed: 1
  samples: 3
  bounds:
    backlash: {low: 0.5, high: 0.1}
printers: [no-such-printer]
""")
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    expected = {3: "fixed.zz: unknown parameter", 5: "grid.z[1] = 2000", 6: "grid.module: range 3..1",
                7: "grid.pressure_angle.step = -1", 12: "random.bounds.backlash: low 0.5 > high 0.1",
                13: "printers[0] = 'no-such-printer'"}
    assert len(lines) == len(expected)
    for line_no, text in expected.items():
        assert any(f"bad.yaml:{line_no}: {text}" in line for line in lines), (line_no, lines)
    assert not (tmp_path / "out").exists()


def test_no_printers_and_one_objective_twice_are_refused_in_words(cli, tmp_path):
    """`printers: []` and `objectives: [mass_g, mass_g]` each get a line a user can act on
    (not pydantic's "List should have at least 1 item"; not a one-point front)."""
    sweep = write(tmp_path / "s.yaml", "command: shoe\ngrid: {width: [20]}\nprinters: []\n")
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--dry-run"))
    assert line.endswith("s.yaml:3: printers = []: must name at least one printer profile (or leave "
                         "`printers:` out: no printer)"), line
    sweep = write(tmp_path / "s.yaml", "command: shoe\ngrid: {width: [20]}\nprinters: [fdm-0.4-pla]\n"
                  "objectives: [mass_g, mass_g]\n")
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--dry-run"))
    assert "s.yaml:4: objectives[1] = 'mass_g': names objectives[0] again" in line, line
    assert not (tmp_path / "out").exists()


def test_too_many_points_refused(cli, tmp_path):
    sweep = write(tmp_path / "big.yaml", "command: shoe\ngrid:\n  width: {start: 1, stop: 200, step: 1}\n"
                                         "  rim: {start: 2, stop: 101, step: 1}\n")
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out"))
    assert "the sweep has 20000 points; at most 10000" in line


@pytest.mark.parametrize("extra, line", [
    ("objectives: [drive_f_i_um, volume_mm3]\nprinters: [fdm-0.4-pla]\n",
     "objectives[0] = 'drive_f_i_um': is not a figure of command: shoe; its figures: volume_mm3, mass_g"),
    ("objectives: [volume_mm3, mass_g]\n",
     "objectives[1] = 'mass_g': needs `printers:` (the mass is the volume times the printer's "
     "material density)"),
])
def test_objectives_the_rows_cannot_hold_are_refused_at_their_line(cli, tmp_path, extra, line):
    sweep = write(tmp_path / "s.yaml", "command: shoe\ndesign: desk-demo\ngrid:\n  width: [12]\n" + extra)
    found = error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1"))
    assert found == f"wheelstep: error: {sweep}:5: {line}"
    assert not (tmp_path / "out").exists()


def test_profile_files_that_cannot_be_read_are_named_at_their_line_of_the_sweep_file(cli, tmp_path):
    """`design: bin.yaml` (not UTF-8) was said as `profile = bin.yaml`, with no line, after the
    plot warning; a printer file likewise as `printer = ...`; every one is now listed at once."""
    from wheelstep_cli.config.profiles import profile_names

    (tmp_path / "bin.yaml").write_bytes(b"a: 60\n\xff\n")
    (tmp_path / "pbin.yaml").write_bytes(b"name: x\n\xff\n")
    sweep = write(tmp_path / "s.yaml", f"command: gears\ndesign: {tmp_path / 'bin.yaml'}\n"
                  f"printers: [{tmp_path / 'pbin.yaml'}, fdm-0.4-pla, {tmp_path / 'none.yaml'}]\n"
                  "grid:\n  z: [48]\n")
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--dry-run")
    assert result.exit_code == 2
    assert result.stderr.splitlines() == [
        f"wheelstep: error: {sweep}:2: design = '{tmp_path / 'bin.yaml'}': is not UTF-8 text (byte 6)",
        f"wheelstep: error: {sweep}:3: printers[0] = '{tmp_path / 'pbin.yaml'}': is not UTF-8 text (byte 8)",
        f"wheelstep: error: {sweep}:3: printers[2] = '{tmp_path / 'none.yaml'}': not found; known printer "
        "profiles: " + ", ".join(profile_names(printer=True))]
    # a profile's own problem is said at its own line
    (tmp_path / "badz.yaml").write_text("gears:\n  z: 3\n")
    sweep = write(tmp_path / "s.yaml", f"command: gears\ndesign: {tmp_path / 'badz.yaml'}\ngrid:\n  z: [48]\n")
    assert error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--dry-run")) == (
        f"wheelstep: error: {tmp_path / 'badz.yaml'}:2: gears.z = 3: must be 6..240 (pinion teeth)")
    assert not (tmp_path / "out").exists()


def test_keep_is_refused_when_the_default_objectives_cannot_rank_the_rows(cli, tmp_path):
    """A shoe sweep without printers has no mass: --keep could keep nothing."""
    sweep = write(tmp_path / "s.yaml", "command: shoe\ndesign: desk-demo\ngrid:\n  width: [12]\n")
    line = error_line(cli("sweep", sweep, "--out", tmp_path / "out", "--keep", "best:2", "--dry-run"))
    assert line == ("wheelstep: error: --keep = best:2: ranks by the objectives volume_mm3 and mass_g; "
                    "mass_g needs `printers:` in the sweep file")
    assert not (tmp_path / "out").exists()


def test_a_shoe_sweep_without_printers_is_told_its_pareto_plot_will_be_empty(cli, tmp_path):
    sweep = write(tmp_path / "s.yaml", "command: shoe\ndesign: desk-demo\ngrid:\n  width: [12]\n")
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--dry-run")
    assert result.exit_code == 0, result.stderr
    assert ("wheelstep: warning: pareto.png plots volume_mm3 against mass_g, and mass_g needs `printers:` "
            "in the sweep file: it will show no design") in result.stderr
    with_printer = write(tmp_path / "p.yaml", sweep.read_text() + "printers: [fdm-0.4-pla]\n")
    assert "warning" not in cli("sweep", with_printer, "--out", tmp_path / "out", "--dry-run").stderr


def test_keep_best_writes_the_best_designs(cli, tmp_path):
    sweep = write(tmp_path / "shoes.yaml", SHOES + "objectives: [volume_mm3, mass_g]\n")
    result = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1", "--keep", "best:2", "-q")
    assert result.exit_code == 1, result.stderr
    ok = sorted((r for r in rows(tmp_path / "out").values() if r["outcome"] == "ok"),
                key=lambda r: r["volume_mm3"])
    for rank in (1, 2):
        folder = tmp_path / "out" / f"best-{rank}"
        record = json.loads((folder / ".wheelstep-shoe.json").read_text())
        stls = list(folder.glob("*.stl"))
        assert stls and all(p.name in json.dumps(record) for p in stls)   # the shoe command's files
        assert set(_BEST_FILES["shoe"]) <= set(record["files"])     # those checked before the run
    assert not (tmp_path / "out" / "best-3").exists()
    assert ok[0]["p_rim"] == 10.0        # the smallest body is the best of both objectives
    # a rerun keeping fewer removes the earlier run's files beyond them; a user's file stays
    (tmp_path / "out" / "best-2" / "notes.txt").write_text("mine")
    # a dry run says so (it listed nothing it would remove); the user's file is not among them
    dry = cli("sweep", sweep, "--out", tmp_path / "out", "--keep", "best:1", "--dry-run")
    assert dry.exit_code == 0, dry.stderr
    removes = sorted(line for line in dry.stdout.splitlines() if line.startswith("would remove"))
    best2 = sorted(p for p in (tmp_path / "out" / "best-2").iterdir() if p.name != "notes.txt")
    assert removes == sorted(f"would remove {p} (written by an earlier run)" for p in best2)
    assert f"would write {tmp_path / 'out' / 'best-1'}" in dry.stdout.splitlines()
    assert not any("best-2" in line for line in dry.stdout.splitlines() if "would write" in line)
    assert (tmp_path / "out" / "best-2" / ".wheelstep-shoe.json").exists()   # nothing removed
    again = cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1", "--keep", "best:1", "-q")
    assert again.exit_code == 1, again.stderr     # its table still holds the first run's refused rows
    assert (tmp_path / "out" / "best-1" / ".wheelstep-shoe.json").exists()
    assert [p.name for p in (tmp_path / "out" / "best-2").iterdir()] == ["notes.txt"]
    assert cli("sweep", sweep, "--out", tmp_path / "out", "--workers", "1", "-q").exit_code == 1
    assert not (tmp_path / "out" / "best-1").exists()


def test_a_users_file_where_a_best_design_goes_is_refused_before_the_run(cli, tmp_path):
    """--keep best:2 with a user's shoe.json in OUT/best-2: refused before any design is
    computed, dry run or not (not once the whole sweep is done); --force overwrites."""
    sweep = write(tmp_path / "shoes.yaml", SHOES + "objectives: [volume_mm3, mass_g]\n")
    mine = tmp_path / "out" / "best-2" / "shoe.json"
    mine.parent.mkdir(parents=True)
    mine.write_text("mine")
    for extra in ([], ["--dry-run"]):
        result = cli("sweep", sweep, "--out", tmp_path / "out", "--keep", "best:2", *extra)
        assert error_line(result) == (f"wheelstep: error: --out = {mine.parent}: shoe.json there exists and "
                                      "was not written by this command: it is kept; move it away or give "
                                      "--force to overwrite it")
        assert result.exit_code == 2 and not (tmp_path / "out" / "results.parquet").exists()
    assert mine.read_text() == "mine"
    dry = cli("sweep", sweep, "--out", tmp_path / "out", "--keep", "best:2", "--dry-run", "--force")
    assert dry.exit_code == 0, dry.stderr


def test_batch_on_the_scheduler(cli, tmp_path, cluster):
    address, _ = cluster
    batch = write(tmp_path / "batch.yaml", SMALL_BATCH)
    result = cli("batch", batch, "--out", tmp_path / "out", "--scheduler", address, "-q", "--json")
    assert result.exit_code == 0, result.stderr
    summary = json.loads(result.stdout)
    assert summary["built"] == ["pair", "shoes"] and summary["parts"] == 5
    line = error_line(cli("batch", batch, "--out", tmp_path / "x", "--scheduler", "tcp://127.0.0.1:9"))
    assert "--scheduler" in line


def test_killing_a_worker_mid_sweep_still_completes(tmp_path, cluster):
    """Last: it kills one of the module's workers."""
    from distributed import Client

    address, workers = cluster
    sweep = write(tmp_path / "shoes.yaml", SHOES.replace("stop: 14, step: 2", "stop: 22, step: 1"))
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    run = subprocess.Popen([sys.executable, "-m", "wheelstep_cli", "sweep", str(sweep), "--out",
                            str(tmp_path / "out"), "--scheduler", address, "-q"], env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    with Client(address, timeout="30s") as client:
        deadline = time.monotonic() + 120
        while not any(client.processing().values()) and time.monotonic() < deadline:
            time.sleep(0.05)
    _stop(workers[1])                     # a worker lost with its points in hand
    out, err = run.communicate(timeout=300)
    assert run.returncode == 1, err       # the refused points only
    found = rows(tmp_path / "out")
    assert len(found) == 2 * 13
    assert {r["outcome"] for r in found.values()} == {"ok", "refused"}
    assert all(r["p_socket_depth"] == 60.0 for r in found.values() if r["outcome"] == "refused")


def test_a_point_outside_the_bounds_says_its_remedy_as_a_try_in_the_files_keys():
    """A sweep builds no remedy per refused point: the row says what the figures point to as
    a try, in the sweep file's keys, not as a checked `use`."""
    from wheelstep_cli.batch import sweep_point

    point = sweep_point.resolve_point(0, "gears", None, None, None, {"z": 24, "thickness": 3}, False, "t")
    row = sweep_point.evaluate(point)
    assert row["outcome"] == "refused", row
    assert row["reason"].startswith("z = 24: the pair would mesh outside the bounds"), row["reason"]
    remedy = row["reason"].split("; try ", 1)[1]
    assert remedy.startswith("z: ") and remedy.endswith(" (from the figures; not built)"), remedy
    assert "use " not in row["reason"] and "--" not in row["reason"]
    # the row's figures were built and kept: only its remedy is not
    assert row["reason"].count("not built") == 1 and "); nothing written; try z: " in row["reason"], row["reason"]


def test_a_point_with_teeth_too_thin_for_its_printer_is_refused_as_gears_refuses_it():
    """desk-demo z 44 on the 0.4 mm FDM printer: `gears` and `batch` refuse its thin teeth
    (use z 42), so the sweep's row is refused too, not ranked among the designs it keeps."""
    from wheelstep_cli.batch import sweep_point
    from wheelstep_cli.config.profiles import load_design_profile, load_printer

    printer = load_printer("fdm-0.4-pla")
    rows = {z: sweep_point.evaluate(sweep_point.resolve_point(
        0, "gears", load_design_profile("desk-demo"), printer.name, printer, {"z": z}, False, "t"))
        for z in (42, 44)}
    assert rows[42]["outcome"] == "ok", rows[42]["reason"]
    assert rows[44]["outcome"] == "refused"
    assert rows[44]["reason"].startswith("z = 44: the teeth are too thin for printer 'fdm-0.4-pla'")
    assert "use z: 42 (fewer, larger teeth)" in rows[44]["reason"]


def test_a_row_without_a_printer_is_keyed_by_the_default_printers_bed(monkeypatch):
    """A row without printers is checked on the default printer's bed: another default printer
    (a profiles/ folder here that overrides it) makes it another row, not a stale one."""
    from dataclasses import replace

    import wheelstep_cli.config.profiles as profiles
    from wheelstep_cli.batch.sweep_point import resolve_point, versions

    from wheelstep_cli.batch import sweep_point

    first = resolve_point(0, "shoe", None, None, None, {"width": 20}, False, versions()).key
    default = profiles.load_printer()
    monkeypatch.setattr(profiles, "load_printer", lambda *a: replace(default, sha256="another"))
    sweep_point._default_printer.cache_clear()     # a new process reads the profile anew
    try:
        assert resolve_point(0, "shoe", None, None, None, {"width": 20}, False, versions()).key != first
    finally:
        sweep_point._default_printer.cache_clear()
