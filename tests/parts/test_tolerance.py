"""The band cases, the refusal of a printer without a band and the fit's secant step (SPEC §11)."""

import numpy as np
import pytest

from wheelstep_cli.config.printers import FIT_MARGINS, Band, Fit
from wheelstep_cli.config.profiles import load_printer_profile
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.fit import _next_inset
from wheelstep_cli.parts.tolerance import band_cases, jams, require_band

PRESETS = ["fdm-0.4-pla", "fdm-0.4-petg", "resin-0.05-standard"]


@pytest.mark.parametrize("name", PRESETS)
def test_every_printer_preset_has_a_band(name):
    printer = load_printer_profile(name)
    band = require_band(printer)
    assert 0 < band.outline <= 0.2 and band.center_distance > 0 and band.hole_shrink > 0


def test_fdm_band_is_wider_than_resin():
    assert (load_printer_profile("fdm-0.4-pla").band.outline
            > load_printer_profile("resin-0.05-standard").band.outline)


def test_a_printer_without_a_band_is_told_to_add_one():
    from dataclasses import replace
    printer = replace(load_printer_profile("fdm-0.4-pla"), band=None)
    with pytest.raises(DesignError, match="band"):
        require_band(printer)


def test_cases_are_the_extremes_and_the_mixed_cases_at_the_smallest_distance():
    cases = band_cases(Band(outline=0.1, hole_shrink=0.2, center_distance=0.05))
    by_name = {c.name: (c.pinion_offset, c.wheel_offset, c.distance_shift) for c in cases}
    assert by_name["tight"] == (0.1, 0.1, -0.05)
    assert by_name["loose"] == (-0.1, -0.1, 0.05)
    assert by_name["pinion grown, wheel shrunk"] == (0.1, -0.1, -0.05)
    assert by_name["pinion shrunk, wheel grown"] == (-0.1, 0.1, -0.05)
    assert cases[0].name == "tight" and len(cases) == 4


def test_jam_is_overlap_or_no_backlash():
    assert jams({"interference": True, "backlash_min_mm": 0.2})
    assert jams({"interference": False, "backlash_min_mm": -0.01})
    assert not jams({"interference": False, "backlash_min_mm": 0.01})


def test_fit_margins_grow_from_auto_to_loose():
    margins = [FIT_MARGINS[f] for f in (Fit.auto, Fit.tight, Fit.normal, Fit.loose)]
    assert margins == sorted(margins) and margins[0] > 0


def _try(inset, least, jams=False, depth=0.0):
    return {"inset_mm": inset, "tight_least_backlash_mm": least, "jams": jams, "tight_depth_mm": depth}


def test_fit_step_by_the_normal_share_the_jam_depth_the_secant_or_the_bracket():
    cos_a = np.cos(np.radians(20))
    # an inset e on both gears opens the normal backlash by 4e: a quarter of the missing play x cos
    first = _next_inset([_try(0.05, -0.05)], 0.01, cos_a)
    assert first == pytest.approx(0.05 + 0.25 * (0.01 + 0.0025 + 0.05) * cos_a)
    # after a jam: half its depth (both gears) and the margin's share
    assert _next_inset([_try(0.0, None, True, 0.2)], 0.01, cos_a) == pytest.approx(
        0.1 + 0.25 * 0.0125 * cos_a)
    # a linear response of slope 2.4: the secant lands on the margin (+ half the tolerance)
    tried = [_try(0.05, -0.1), _try(0.1, 0.02)]
    assert _next_inset(tried, 0.05, cos_a) == pytest.approx(0.1 + (0.0525 - 0.02) / 2.4)
    # a step out of the bracket (0.08 jams, 0.1 keeps far more than the margin) bisects it
    tried = [_try(0.08, None, True, 0.001), _try(0.1, 0.5), _try(0.2, 0.6)]
    assert _next_inset(tried, 0.01, cos_a) == pytest.approx(0.09)


class _FakeReport:
    """Stands for a meshing report whose least backlash is linear in the outline inset;
    ``jammed``: the poses that jam (all four when the least backlash is not positive)."""

    def __init__(self, least, jammed=None):
        self.least = least
        self.phi_drive = self.phi_coast = self.phi_law = np.zeros(4)
        self.theta = np.arange(4.0)
        self.teeth = 4
        self.interference = np.full(4, least <= 0) if jammed is None else np.asarray(jammed)
        self.backlash = np.where(self.interference, -1.0, 1.0)

    def to_dict(self):
        flank = {"F_i_total_um": 1.0, "f_i_tooth_um": 1.0, "hub_speed_ripple_pct": 0.1}
        return {"distance_mm": 144.0, "interference": self.least <= 0, "interfering_poses": 0,
                "max_penetration_mm": getattr(self, "depth", 0.0), "backlash_min_mm": self.least,
                "backlash_max_mm": self.least + 0.1, "drive": flank, "coast": flank}


def _fake_search(monkeypatch, least_of_inset, law=None, jammed=None, depth=None):
    """fit_pair on fakes: a "pair" is the inset (mm) it was drawn with, its sections carry it
    and the tight corner's least backlash is ``least_of_inset`` less the band's growth."""
    import wheelstep_cli.parts.fit as fit
    import wheelstep_cli.parts.tolerance as tolerance

    def check(sections, case, settings=None):
        least = least_of_inset(sections.inset) - 0.1 * (case.pinion_offset + case.wheel_offset)
        report = _FakeReport(least, None if least > 0 else jammed)
        report.depth = 0.05 if depth is None else depth(sections.inset)
        return report

    from types import SimpleNamespace

    law = SimpleNamespace(corners=()) if law is None else law

    def sections_of(inset):
        return SimpleNamespace(inset=inset, shift=(np.zeros(1), np.zeros(1)), law=law)

    monkeypatch.setattr(fit, "sectioned_pair", sections_of)
    monkeypatch.setattr(fit, "inset_sections", lambda sections, mm: sections_of(sections.inset + mm))
    monkeypatch.setattr(fit, "check_case", check)
    monkeypatch.setattr(tolerance, "check_case", check)
    monkeypatch.setattr(fit, "mid_play", lambda sections, nominal: sections)
    monkeypatch.setattr(tolerance, "mid_play", lambda sections, nominal: sections)


def _fit(spec, fit="auto", printer=None):
    """fit_pair on the fakes: the design is drawn with no inset and the printer's tooth
    clearance set to 0 (the inset replaces it)."""
    from wheelstep_cli.parts.fit import fit_pair

    def build(s, p):
        assert p.tooth_clearance == 0.0
        return 0.0
    return fit_pair(spec, replace_printer() if printer is None else printer, fit, build,
                    inset=lambda pair, mm: pair + mm)


def test_fit_search_lands_on_the_margin_for_a_linear_response(monkeypatch):
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import FIT_TOLERANCE

    # least backlash = 4.3 x inset - 0.10 (4e / cos alpha), and 0.02 less at the tight corner
    _fake_search(monkeypatch, lambda inset: 4.3 * inset - 0.10)
    printer = load_printer_profile("fdm-0.4-pla")
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    result = _fit(spec, "normal", printer)
    tight = 4.3 * result.inset - 0.10 - 0.1 * 2 * printer.band.outline
    assert 0.1 - FIT_TOLERANCE <= tight <= 0.1 + FIT_TOLERANCE
    searched = [r for r in result.rounds if r["checked_on"] == "design sections"]
    assert len(searched) <= 3 and [r["inset_mm"] for r in result.rounds if r["checked_on"] == "fitted pair"] == [result.inset]
    assert result.pair == result.inset and result.design_pair == 0.0
    assert result.band["least_backlash_mm"] == pytest.approx(tight)


def test_fit_search_may_grow_the_teeth_but_not_past_the_design_play(monkeypatch):
    from types import SimpleNamespace

    # a band with room to spare: the teeth are drawn larger, but an inset e changes the
    # design's normal backlash (0.2 mm) by 4e, so never past -0.05 mm
    _fake_search(monkeypatch, lambda inset: 4.0 * inset + 0.5)
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.2)
    result = _fit(spec, "auto")
    assert result.inset == pytest.approx(-0.05)


def test_fit_search_stops_at_its_inset_cap_when_nothing_helps(monkeypatch):
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import FIT_MAX_INSET

    # every try jams 0.3 mm deep: the steps reach the cap and stop there
    _fake_search(monkeypatch, lambda inset: -1.0, depth=lambda inset: 0.3)
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    result = _fit(spec, "auto")
    assert result.stopped == "cap" and result.inset == pytest.approx(FIT_MAX_INSET)
    assert result.band["jams"]


def _fit_written_off_by(monkeypatch, off: float):
    """fit_pair on the fakes where the pair as written comes out ``off`` mm less inset than
    the search's offsets of the design's sections."""
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import fit_pair

    _fake_search(monkeypatch, lambda inset: 4.3 * inset - 0.10)
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    return fit_pair(spec, replace_printer(), "auto", lambda s, p: 0.0, inset=lambda pair, mm: pair + mm - off)


def test_the_written_pair_is_checked_again_and_the_inset_grown_while_it_jams(monkeypatch):
    from wheelstep_cli.parts.fit import INSET_TOLERANCE

    result = _fit_written_off_by(monkeypatch, 0.01)
    written = [r for r in result.rounds if r["checked_on"] == "fitted pair"]
    assert len(written) == 2 and written[0]["jams"] and not written[1]["jams"]
    assert written[1]["inset_mm"] == pytest.approx(written[0]["inset_mm"] + 0.5 * written[0]["tight_depth_mm"]
                                                   + INSET_TOLERANCE)
    assert result.inset == written[1]["inset_mm"] and not result.band["jams"]


def test_a_written_pair_that_keeps_jamming_reports_the_inset_it_was_built_with(monkeypatch):
    from wheelstep_cli.parts.fit import FIT_CONFIRM_ROUNDS

    result = _fit_written_off_by(monkeypatch, 1.0)
    written = [r for r in result.rounds if r["checked_on"] == "fitted pair"]
    assert len(written) == FIT_CONFIRM_ROUNDS and all(r["jams"] for r in written)
    assert result.inset == written[-1]["inset_mm"] and result.pair == pytest.approx(result.inset - 1.0)
    assert result.band["jams"]


def _law_with_a_corner(at_theta: float):
    """A law of period 4 rad (pinion) with one corner at pinion angle ``at_theta`` rad."""
    from types import SimpleNamespace

    return SimpleNamespace(corners=(at_theta / 2.0,), theta_period=4.0,
                           pinion_angle=lambda phi: 2.0 * np.asarray(phi))


def test_corner_poses_are_those_within_the_zone_of_a_corner_across_the_period_start():
    from types import SimpleNamespace

    from wheelstep_cli.parts.tolerance import corner_poses

    # 24 teeth: the zone is 1.5 pitches = 0.3927 rad either side of the corner
    theta = np.array([0.0, 0.45, 0.61, 1.0, 1.39, 1.40, 3.80, 3.95])
    report = SimpleNamespace(theta=theta, teeth=24)
    assert corner_poses(report, _law_with_a_corner(1.0)).tolist() == [
        False, False, True, True, True, False, False, False]
    # a corner at 0.1 rad: its zone wraps round the period's start (period 4 rad)
    assert corner_poses(report, _law_with_a_corner(0.1)).tolist() == [
        True, True, False, False, False, False, True, True]
    assert not corner_poses(report, SimpleNamespace(corners=())).any()


def test_fit_search_stops_when_more_inset_leaves_the_corner_jam_as_deep(monkeypatch):
    from types import SimpleNamespace

    import wheelstep_cli.parts.tolerance as tolerance
    from wheelstep_cli.parts.fit import fit_record, require_fit_met

    # the fake's 4 poses sit at pinion angles 0..3 rad with 4 teeth; a zone of 0.1 pitch
    # (0.16 rad) about the corner at 1 rad holds pose 1 only
    monkeypatch.setattr(tolerance, "CORNER_ZONE_PITCHES", 0.1)
    law = _law_with_a_corner(1.0)
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    _fake_search(monkeypatch, lambda inset: -1.0, law=law, jammed=np.array([False, True, False, False]))
    result = _fit(spec)
    searched = [r for r in result.rounds if r["checked_on"] == "design sections"]
    assert result.stopped == "corners" and len(searched) == 2
    assert searched[1]["inset_mm"] > searched[0]["inset_mm"]
    assert all(r["jammed_poses"] == r["jammed_at_corners"] == 1 for r in result.rounds)
    with pytest.raises(DesignError) as err:
        require_fit_met({**result.band, "fit": fit_record(result, "auto")})
    assert "all at the pitch-curve corners, and a larger inset did not make" in err.value.limit
    assert f"no outline inset up to {result.rounds[1]['inset_mm']:.3f} mm" in err.value.limit

    # a corner jam that the inset makes shallower: the search goes on
    _fake_search(monkeypatch, lambda inset: -1.0, law=law, jammed=np.array([False, True, False, False]),
                 depth=lambda inset: 0.3 - inset)
    assert _fit(spec).stopped != "corners"
    # jams elsewhere too: the search goes on growing the inset
    _fake_search(monkeypatch, lambda inset: -1.0, law=law, jammed=np.array([True, True, False, False]))
    result = _fit(spec)
    assert result.stopped != "corners" and len(result.rounds) > 2


def test_fit_cap_is_the_smaller_of_half_a_mm_and_0_15_module():
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import fit_cap

    assert fit_cap(SimpleNamespace(generated=SimpleNamespace(module=2.0))) == pytest.approx(0.3)
    assert fit_cap(SimpleNamespace(generated=SimpleNamespace(module=4.0))) == pytest.approx(0.5)
    assert fit_cap(SimpleNamespace(generated=None, spec=SimpleNamespace(module=1.5))) == pytest.approx(0.225)
    assert fit_cap(0.15) == pytest.approx(0.5)     # nothing known of its teeth


def replace_printer():
    from dataclasses import replace

    return replace(load_printer_profile("fdm-0.4-pla"), tooth_clearance=0.0)


def _fitted_band(least: float, jams: bool) -> dict:
    case = {"case": "tight", "jams": jams, "interfering_poses": 7 if jams else 0,
            "max_penetration_mm": 0.02 if jams else 0.0, "backlash_min_mm": least}
    return {"printer": "p", "jams": jams, "least_backlash_mm": least, "cases": [case],
            "fit": {"fit": "normal", "margin_mm": 0.1, "inset_mm": 0.12}}


def test_a_fit_short_of_its_margin_or_jamming_is_refused_naming_the_fit():
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.fit import require_fit_met

    require_fit_met(_fitted_band(0.1, False))
    for least, jammed, found in ((0.05, False, "keeps 0.050 mm"), (-0.2, True, "jams at 7 poses, 20 um deep")):
        with pytest.raises(DesignError) as err:
            require_fit_met(_fitted_band(least, jammed))
        assert err.value.param == "fit" and err.value.value == "normal"
        assert found in err.value.limit and "print without --fit" in err.value.limit


def test_a_case_that_jams_gives_no_backlash_or_te_in_its_line():
    from wheelstep_cli.parts.tolerance import band_lines

    flank = {"F_i_total_um": 3771.0, "f_i_tooth_um": 900.0, "hub_speed_ripple_pct": 573.1}
    cases = [{"case": "tight", "pinion_offset_mm": 0.1, "wheel_offset_mm": 0.1, "distance_mm": 143.95,
              "jams": True, "interfering_poses": 1536, "max_penetration_mm": 0.229,
              "backlash_min_mm": -4.248, "backlash_max_mm": -0.222, "drive": flank, "coast": flank},
             {"case": "loose", "pinion_offset_mm": -0.1, "wheel_offset_mm": -0.1, "distance_mm": 144.05,
              "jams": False, "interfering_poses": 0, "max_penetration_mm": 0.0,
              "backlash_min_mm": 0.5, "backlash_max_mm": 0.7, "drive": dict(flank, F_i_total_um=20.0),
              "coast": flank}]
    record = {"printer": "p", "band": {"outline_mm": 0.1, "center_distance_mm": 0.05}, "jams": True,
              "cases": cases}
    head, tight, loose = band_lines(record)
    assert "JAMS" in head and "JAMS (1536 poses, 229 um deep; no backlash or TE" in tight
    assert "-4.248" not in tight and "3771" not in tight
    assert "ok, backlash 0.500..0.700 mm, drive F'i 20.0 um" in loose


def test_a_jammed_case_line_says_how_much_of_its_jam_is_at_the_corners():
    from wheelstep_cli.parts.tolerance import band_lines

    flank = {"F_i_total_um": 1.0, "f_i_tooth_um": 1.0, "hub_speed_ripple_pct": 0.1}
    case = {"case": "tight", "pinion_offset_mm": 0.1, "wheel_offset_mm": 0.1, "distance_mm": 143.95,
            "jams": True, "interfering_poses": 68, "max_penetration_mm": 0.124,
            "backlash_min_mm": -1.0, "backlash_max_mm": 0.4, "drive": flank, "coast": flank,
            "poses": 1536, "jammed_poses": 68, "jammed_at_corners": 68}
    record = {"printer": "p", "band": {"outline_mm": 0.1, "center_distance_mm": 0.05}, "jams": True,
              "cases": [case]}
    assert "JAMS (68 poses, 124 um deep, all at the pitch-curve corners;" in band_lines(record)[1]
    case["jammed_at_corners"] = 20
    assert "JAMS (68 poses, 124 um deep, 20 at the pitch-curve corners;" in band_lines(record)[1]
    case["jammed_at_corners"] = 0
    assert "corner" not in band_lines(record)[1]
    # jammed at every pose: the corner share would only measure the corner zone
    case.update(jammed_poses=1536, interfering_poses=1536, jammed_at_corners=219)
    assert "JAMS (1536 poses" in band_lines(record)[1] and "corner" not in band_lines(record)[1]


def test_printed_outlines_are_checked_over_the_whole_cycle_as_densely_as_one_period():
    """A printed pair (``whole_cycle``) is checked over the law's whole cycle (one wheel turn:
    4 periods of the crank law) with the poses of one period in each, given (--samples, per
    period) or by default: a tooth is sampled as in the designed pair's check. A designed pair
    (its outlines repeat) keeps one period."""
    from wheelstep_cli.gears.cycle import WholeCycle
    from wheelstep_cli.gears.laws import CrankLaw
    from wheelstep_cli.gears.meshing import MeshingSettings
    from wheelstep_cli.gears.meshing.check import default_pose_count
    from wheelstep_cli.mechanism.crank import CrankMechanism
    from wheelstep_cli.parts.tolerance import SectionedPair, checked_law

    law = CrankLaw(CrankMechanism(30, 50, 180), 2)
    designed = SectionedPair(np.zeros((3, 2)), np.zeros((3, 2)), law, 72.125, 42)
    printed = SectionedPair(np.zeros((3, 2)), np.zeros((3, 2)), law, 72.125, 42, whole_cycle=True)
    given = MeshingSettings(samples=256)
    assert checked_law(designed, given) == (law, given)
    cycle, settings = checked_law(printed, given)
    assert cycle == WholeCycle(law) and settings.samples == 4 * 256
    assert checked_law(printed, MeshingSettings())[1].samples == 4 * default_pose_count(law, 42) == 4 * 1536
