"""A printer profile's slicer: section: what PrusaSlicer would drop or refuse is refused at its line."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers.files import line_of, write
from wheelstep_cli.config.slicer_options import catalogue, slicer_problems

PLA = Path(__file__).resolve().parents[2] / "profiles" / "fdm-0.4-pla.yaml"


def _printer(tmp_path, replaced: str, by: str):
    """The PLA preset as a file of the user's, one line replaced."""
    text = PLA.read_text()
    assert replaced in text
    return write(tmp_path / "mine.yaml", text.replace(replaced, by))


@pytest.mark.parametrize("replaced, by, needle, expect", [
    ("  perimeters: 3\n", "  perimeters: many\n", "perimeters", "slicer.perimeters = 'many': must be a number"),
    ("  perimeters: 3\n", "  perimters: 3\n", "perimters",
     "slicer.perimters: not a PrusaSlicer option of FDM printers; did you mean perimeters?"),
    ("  fill_pattern: gyroid\n", "  fill_pattern: zigzag\n", "zigzag",
     "slicer.fill_pattern = 'zigzag': must be one of: rectilinear,"),
    ("  fill_density: 30%\n", "  fill_density: thirty\n", "thirty",
     "slicer.fill_density = 'thirty': must be a number or a percentage such as 15%"),
    ("  perimeters: 3\n", "  perimeters: 3\n  bed_shape: 0x0,100x0,100x100,0x100\n", "bed_shape",
     "slicer.bed_shape: is set by printer.bed of this profile; give it there"),
    ("  perimeters: 3\n", "  perimeters: 3\n  exposure_time: 2\n", "exposure_time",
     "slicer.exposure_time: not a PrusaSlicer option of FDM printers"),
])
def test_a_slicer_setting_prusaslicer_would_not_take_is_refused_at_its_line(cli, tmp_path, replaced, by,
                                                                            needle, expect):
    printer = _printer(tmp_path, replaced, by)
    result = cli("gears", "--printer", printer, "--out", tmp_path / "out")
    assert result.exit_code == 2
    line = result.stderr.strip().splitlines()[0]
    assert line.startswith(f"wheelstep: error: {printer}:{line_of(printer, needle)}: {expect}"), line
    assert not (tmp_path / "out").exists()


def test_every_preset_and_every_kind_of_value_the_catalogue_knows_passes():
    assert slicer_problems({"perimeters": 3, "fill_density": "15%", "infill_overlap": 0.2,
                            "fill_pattern": "gyroid", "wipe": True, "thin_walls": 0,
                            "nozzle_diameter": "0.4,0.6", "start_gcode": "G28"}, "fdm") == []
    assert slicer_problems({"exposure_time": 2.5, "supports_enable": 0, "display_orientation": "portrait"},
                           "resin") == []


def test_the_shipped_catalogue_is_what_the_installed_prusaslicer_says():
    """The catalogue was read off PrusaSlicer (tests/helpers/prusa_options.py); the slicer the
    tests run must agree, or the profiles are checked against another release's options."""
    from tests.helpers.prusa_options import catalogue as read_off_the_slicer
    from tests.helpers.slicer import require_slicer

    require_slicer()
    assert read_off_the_slicer() == catalogue()
