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
    ("  perimeters: 3\n", "  perimeters: many\n", "perimeters", "slicer.perimeters = 'many': must be a whole number"),
    # ranges and kinds as PrusaSlicer reads them (it would drop the fraction, refuse the rest)
    ("  perimeters: 3\n", "  perimeters: 2.5\n", "perimeters", "slicer.perimeters = 2.5: must be a whole number"),
    ("  perimeters: 3\n", "  perimeters: 1e999\n", "1e999", "slicer.perimeters = '1e999': must be a whole number"),
    # a fan speed is a whole percentage up to 100 (as PrusaSlicer saves it), not a fraction
    ("  perimeters: 3\n", "  perimeters: 3\n  max_fan_speed: 101\n", "max_fan_speed",
     "slicer.max_fan_speed = 101: must be at most 100"),
    ("  perimeters: 3\n", "  perimeters: -1\n", "perimeters", "slicer.perimeters = -1: must be >= 0"),
    ("  fill_density: 30%\n", "  fill_density: 150%\n", "150%",
     "slicer.fill_density = '150%': must be at most 100%"),
    ("  fill_density: 30%\n", "  fill_density: 30\n", "fill_density: 30",
     "slicer.fill_density = 30: must be at most 100% (a number without % is a fraction: 0.3 is 30 %)"),
    ("  layer_height: 0.2\n", "  layer_height: 5\n", "layer_height: 5",
     "slicer.layer_height = 5: must be at most the nozzle diameter (0.4 mm, nozzle_diameter)"),
    # a nozzle of 0 lays down nothing: named itself, not the layers it is thinner than
    ("  nozzle_diameter: 0.4\n", "  nozzle_diameter: 0\n", "nozzle_diameter",
     "slicer.nozzle_diameter = 0: must be > 0 mm"),
    ("  first_layer_height: 0.2\n", "  first_layer_height: 75%\n", "75%",
     "slicer.first_layer_height = '75%': must be a number"),
    ("  perimeters: 3\n", "  perimters: 3\n", "perimters",
     "slicer.perimters: not a PrusaSlicer option of FDM printers; did you mean perimeters?"),
    ("  fill_pattern: gyroid\n", "  fill_pattern: zigzag\n", "zigzag",
     "slicer.fill_pattern = 'zigzag': must be one of: rectilinear,"),
    ("  fill_density: 30%\n", "  fill_density: thirty\n", "thirty",
     "slicer.fill_density = 'thirty': must be a percentage such as 15% (or a fraction such as 0.15)"),
    ("  perimeters: 3\n", "  perimeters: 3\n  bed_shape: 0x0,100x0,100x100,0x100\n", "bed_shape",
     "slicer.bed_shape: is set by printer.bed of this profile; give it there"),
    # the meshes are drawn compensated: the slicer's own compensation would do it twice
    ("  perimeters: 3\n", "  perimeters: 3\n  elefant_foot_compensation: 0.2\n", "elefant_foot",
     "slicer.elefant_foot_compensation: would compensate again what the meshes are drawn compensated "
     "for (printer.elephant_foot_inset of this profile); give it there"),
    ("  perimeters: 3\n", "  perimeters: 3\n  xy_size_compensation: -0.1\n", "xy_size",
     "slicer.xy_size_compensation: would compensate again what the meshes are drawn compensated "
     "for (printer.hole_compensation and printer.tooth_clearance of this profile); give it there"),
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


def test_every_kind_of_value_prusaslicer_reads_passes():
    assert slicer_problems({"perimeters": 3, "fill_density": "15%", "infill_overlap": 0.2,
                            "fill_pattern": "gyroid", "wipe": True, "thin_walls": 0,
                            "nozzle_diameter": "0.4, 0.6", "temperature": "215,220", "wipe_tower": "1,0",
                            "z_offset": "-1e-3", "start_gcode": "G28", "filament_retract_length": "1",
                            "inherits": "Original Prusa i3 MK3", "extrusion_width": "105%"}, "fdm") == []
    assert slicer_problems({"fill_density": 0.3}, "fdm") == []          # a fraction: 30 %
    assert slicer_problems({"max_fan_speed": 100, "min_fan_speed": 35, "raft_first_layer_density": 90,
                            "wipe": 1.0, "bridge_flow_ratio": 1.5}, "fdm") == []
    assert slicer_problems({"exposure_time": 2.5, "supports_enable": 0, "display_orientation": "portrait",
                            "material_colour": "#29B2B2"}, "resin") == []
    # what a resin printer has no use for is no PrusaSlicer option of it, not the printer section's
    assert slicer_problems({"skirts": 1}, "resin") == [("skirts", "not a PrusaSlicer option of resin (SLA) "
                                                                  "printers")]


def test_a_slicer_problem_is_named_with_the_files_other_problems(cli, tmp_path):
    printer = _printer(tmp_path, "  perimeters: 3\n", "  perimeters: many\n")
    printer.write_text(printer.read_text().replace("max_height: 250", "max_height: -1", 1))
    lines = cli("gears", "--printer", printer, "--out", tmp_path / "out").stderr.strip().splitlines()
    assert any("printer.max_height = -1" in line for line in lines), lines
    assert any("slicer.perimeters = 'many'" in line for line in lines), lines


def test_a_nozzle_per_extruder_is_read_as_the_first_extruders(cli, tmp_path):
    printer = _printer(tmp_path, "  nozzle_diameter: 0.4\n", "  nozzle_diameter: 0.4, 0.6\n")
    result = cli("gears", "--printer", printer, "--format", "3mf", "--out", tmp_path / "out")
    assert result.exit_code == 0, result.stderr
    assert list((tmp_path / "out").glob("*.3mf"))


def test_the_shipped_catalogue_is_what_the_installed_prusaslicer_says():
    """The catalogue was read off PrusaSlicer (tests/helpers/prusa_options.py); the slicer the
    tests run must agree, or the profiles are checked against another release's options."""
    from tests.helpers.prusa_options import catalogue as read_off_the_slicer
    from tests.helpers.slicer import require_slicer

    require_slicer()
    assert read_off_the_slicer() == catalogue()
