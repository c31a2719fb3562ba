"""The band cases, the refusal of a printer without a band and the fit's secant step (SPEC §11)."""

import numpy as np
import pytest

from wheelstep_cli.config.printers import FIT_MARGINS, Band, Fit
from wheelstep_cli.config.profiles import load_printer_profile
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.fit import _next_clearance
from wheelstep_cli.parts.tolerance import ShiftedLaw, band_cases, jams, require_band

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


def test_fit_step_first_by_the_normal_share_then_by_the_secant():
    cos_a = np.cos(np.radians(20))
    first = _next_clearance([{"clearance_mm": 0.15, "tight_least_backlash_mm": -0.05}], 0.01, cos_a)
    assert first == pytest.approx(0.15 + (0.01 + 0.0025 + 0.05) * cos_a)
    # a linear response of slope 1.2: the secant lands on the margin (+ half the tolerance)
    tried = [{"clearance_mm": 0.1, "tight_least_backlash_mm": -0.1},
             {"clearance_mm": 0.2, "tight_least_backlash_mm": 0.02}]
    assert _next_clearance(tried, 0.05, cos_a) == pytest.approx(0.2 + (0.0525 - 0.02) / 1.2)


def test_shifted_law_moves_the_wheel_angle_pose_by_pose():
    class Law:
        theta_period = 1.0

        def carrier_angle(self, theta):
            return 2.0 * np.asarray(theta)

        def hub_speed_factor(self, phi):
            return np.ones_like(np.asarray(phi, float))

    law = ShiftedLaw(Law(), np.array([0.0, 0.5]), np.array([0.01, 0.03]))
    assert law.carrier_angle(np.array([0.25]))[0] == pytest.approx(0.5 + 0.02)
    assert law.carrier_angle(np.array([1.25]))[0] == pytest.approx(2.5 + 0.02)


class _FakeReport:
    """Stands for a meshing report whose least backlash is linear in the tooth clearance;
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


def _fake_search(monkeypatch, least_of_clearance, law=None, jammed=None, depth=None):
    import wheelstep_cli.parts.fit as fit
    import wheelstep_cli.parts.tolerance as tolerance

    def check(sections, case, settings=None):
        least = least_of_clearance(sections.clearance) - 0.1 * (case.pinion_offset + case.wheel_offset)
        report = _FakeReport(least, None if least > 0 else jammed)
        report.depth = 0.05 if depth is None else depth(sections.clearance)
        return report

    from types import SimpleNamespace

    law = SimpleNamespace(corners=()) if law is None else law
    monkeypatch.setattr(fit, "sectioned_pair", lambda pair: SimpleNamespace(
        clearance=pair, shift=(np.zeros(1), np.zeros(1)), law=law))
    monkeypatch.setattr(fit, "check_case", check)
    monkeypatch.setattr(tolerance, "check_case", check)
    monkeypatch.setattr(fit, "mid_play", lambda sections, nominal: sections)
    monkeypatch.setattr(tolerance, "mid_play", lambda sections, nominal: sections)


def test_fit_search_lands_on_the_margin_for_a_linear_response(monkeypatch):
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import FIT_TOLERANCE, fit_pair

    # least backlash = 1.1 x clearance - 0.10, and 0.02 less at the tight corner (+0.1 mm each)
    _fake_search(monkeypatch, lambda clearance: 1.1 * clearance - 0.10)
    printer = replace_printer()
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    result = fit_pair(spec, printer, "normal", lambda s, p: p.tooth_clearance)
    tight = 1.1 * result.clearance - 0.10 - 0.1 * 2 * printer.band.outline
    assert 0.1 <= tight <= 0.1 + FIT_TOLERANCE
    assert len(result.rounds) <= 3
    assert result.band["least_backlash_mm"] == pytest.approx(tight)


def test_fit_search_stops_at_its_clearance_cap_when_nothing_helps(monkeypatch):
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import FIT_MAX_CLEARANCE, fit_pair

    _fake_search(monkeypatch, lambda clearance: -1.0)
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    result = fit_pair(spec, replace_printer(), "auto", lambda s, p: p.tooth_clearance)
    assert result.clearance <= FIT_MAX_CLEARANCE and result.band["jams"]


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


def test_fit_search_stops_when_more_clearance_leaves_the_corner_jam_as_deep(monkeypatch):
    from types import SimpleNamespace

    import wheelstep_cli.parts.tolerance as tolerance
    from wheelstep_cli.parts.fit import fit_pair, fit_record, require_fit_met

    # the fake's 4 poses sit at pinion angles 0..3 rad with 4 teeth; a zone of 0.1 pitch
    # (0.16 rad) about the corner at 1 rad holds pose 1 only
    monkeypatch.setattr(tolerance, "CORNER_ZONE_PITCHES", 0.1)
    law = _law_with_a_corner(1.0)
    spec = SimpleNamespace(pressure_angle=20.0, backlash_mm=0.5)
    _fake_search(monkeypatch, lambda clearance: -1.0, law=law, jammed=np.array([False, True, False, False]))
    result = fit_pair(spec, replace_printer(), "auto", lambda s, p: p.tooth_clearance)
    assert result.stopped == "corners" and len(result.rounds) == 2
    assert result.rounds[1]["clearance_mm"] > result.rounds[0]["clearance_mm"]
    assert all(r["jammed_poses"] == r["jammed_at_corners"] == 1 for r in result.rounds)
    with pytest.raises(DesignError) as err:
        require_fit_met({**result.band, "fit": fit_record(result, "auto", 0.5)})
    assert "all at the pitch-curve corners, and more tooth clearance did not make" in err.value.limit
    assert f"no tooth clearance up to {result.rounds[1]['clearance_mm']:.3f} mm" in err.value.limit

    # a corner jam that the clearance makes shallower: the search goes on
    _fake_search(monkeypatch, lambda clearance: -1.0, law=law, jammed=np.array([False, True, False, False]),
                 depth=lambda clearance: 0.3 - clearance)
    assert fit_pair(spec, replace_printer(), "auto", lambda s, p: p.tooth_clearance).stopped != "corners"
    # jams elsewhere too: the search goes on raising the clearance
    _fake_search(monkeypatch, lambda clearance: -1.0, law=law, jammed=np.array([True, True, False, False]))
    result = fit_pair(spec, replace_printer(), "auto", lambda s, p: p.tooth_clearance)
    assert result.stopped != "corners" and len(result.rounds) > 2


def test_fit_cap_is_the_smaller_of_1_mm_and_0_4_module():
    from types import SimpleNamespace

    from wheelstep_cli.parts.fit import fit_cap

    assert fit_cap(SimpleNamespace(generated=SimpleNamespace(module=2.0))) == pytest.approx(0.8)
    assert fit_cap(SimpleNamespace(generated=SimpleNamespace(module=4.0))) == pytest.approx(1.0)
    assert fit_cap(SimpleNamespace(generated=None, spec=SimpleNamespace(module=1.5))) == pytest.approx(0.6)
    assert fit_cap(0.15) == pytest.approx(1.0)     # nothing known of its teeth


def replace_printer():
    from dataclasses import replace

    return replace(load_printer_profile("fdm-0.4-pla"), tooth_clearance=0.0)


def _fitted_band(least: float, jams: bool) -> dict:
    case = {"case": "tight", "jams": jams, "interfering_poses": 7 if jams else 0,
            "max_penetration_mm": 0.02 if jams else 0.0, "backlash_min_mm": least}
    return {"printer": "p", "jams": jams, "least_backlash_mm": least, "cases": [case],
            "fit": {"fit": "normal", "margin_mm": 0.1, "tooth_clearance_mm": 0.3, "backlash_mm": 0.5}}


def test_a_fit_short_of_its_margin_or_jamming_is_refused_naming_the_fit():
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.fit import require_fit_met

    require_fit_met(_fitted_band(0.1, False))
    for least, jams, found in ((0.05, False, "keeps 0.050 mm"), (-0.2, True, "jams at 7 poses, 20 um deep")):
        with pytest.raises(DesignError) as err:
            require_fit_met(_fitted_band(least, jams))
        assert err.value.param == "fit" and err.value.value == "normal"
        assert found in err.value.limit and "print without --fit" in err.value.limit


def test_a_fitted_pair_outside_the_bounds_is_refused_naming_the_fit():
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.fit import require_fit_within_bounds

    flank = {"F_i_total_um": 6.0, "f_i_tooth_um": 5.0, "hub_speed_ripple_pct": 0.7}
    record = {"interference": False, "contact_lost": False, "law_hub_speed_ripple_pct": 0.0,
              "drive": dict(flank), "coast": dict(flank)}
    require_fit_within_bounds(record, _fitted_band(0.1, False))
    record["coast"]["hub_speed_ripple_pct"] = 1.2
    with pytest.raises(DesignError) as err:
        require_fit_within_bounds(record, _fitted_band(0.1, False))
    assert err.value.param == "fit"
    assert "needs (0.300 mm, backlash j_n 0.500 mm)" in err.value.limit
    assert "coast flank" in err.value.limit and "1.20 %" in err.value.limit


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
