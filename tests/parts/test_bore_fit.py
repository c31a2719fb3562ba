"""Hole shrink (SPEC §11): bores are drawn larger by the printer's hole compensation, and the
band report gives the shaft's clearance at the band's extremes."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from wheelstep_cli.config.profiles import load_printer_profile
from wheelstep_cli.config.specs import GearPairSpec
from wheelstep_cli.parts.kinds import KINDS, Printing, printed_spec
from wheelstep_cli.parts.tolerance_cli import bore_fit, bore_line


@pytest.mark.parametrize("name", ["fdm-0.4-pla", "fdm-0.4-petg", "resin-0.05-standard"])
def test_every_preset_states_hole_shrink_and_its_compensation_widens_the_bores(name):
    printer = load_printer_profile(name)
    assert printer.band is not None and printer.band.hole_shrink > 0
    design = GearPairSpec()
    printed = printed_spec(KINDS["gear-pair"], design, printer)
    assert printed.bore == pytest.approx(design.bore + printer.hole_compensation)
    assert printed.key_width is None or printed.key_width == pytest.approx(
        (design.key_width or 0) + printer.hole_compensation)


def test_the_bore_fit_runs_from_compensation_minus_shrink_to_the_compensation():
    printer = load_printer_profile("fdm-0.4-pla")
    design = GearPairSpec()
    printed = printed_spec(KINDS["gear-pair"], design, printer)
    pair = SimpleNamespace(spec=printed, printing=Printing(printer, design))
    fit = bore_fit(pair, printer.band)
    assert fit["shaft_mm"] == 8.0 and fit["drawn_mm"] == pytest.approx(8.2)
    assert fit["printed_mm"] == pytest.approx([8.2 - printer.band.hole_shrink, 8.2])
    assert fit["clearance_mm"] == pytest.approx([0.2 - printer.band.hole_shrink, 0.2])
    assert fit["shaft_fits"] is (0.2 - printer.band.hole_shrink >= 0)
    assert "bore: shaft 8 mm in a bore drawn 8.2 mm" in bore_line(fit)


def test_a_bore_drawn_at_the_shaft_size_is_tight_over_the_band():
    printer = load_printer_profile("fdm-0.4-pla")
    fit = bore_fit(SimpleNamespace(spec=GearPairSpec(), printing=None), printer.band)
    assert fit["clearance_mm"][0] == pytest.approx(-printer.band.hole_shrink)
    assert fit["shaft_fits"] is False and "TIGHT" in bore_line(fit)


def test_a_pair_without_bores_has_no_bore_fit():
    printer = load_printer_profile("fdm-0.4-pla")
    assert bore_fit(SimpleNamespace(spec=GearPairSpec(bore=0), printing=None), printer.band) is None
