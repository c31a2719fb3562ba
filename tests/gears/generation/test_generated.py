"""Generated teeth (SPEC §9): involute limit, undercut/pointed refusal, law-agnostic pitch curves."""

import json
import re

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.generation import RackCutter, generate_pair
from wheelstep_cli.gears.laws import CrankLaw, blended_law, law_from_samples
from wheelstep_cli.gears.pitch_curves import center_distance_for_module, pinion_radius, pitch_curves, wheel_radius
from wheelstep_cli.mechanism.crank import CrankMechanism
from wheelstep_cli.geometry.planar import check_outline

from tests.helpers.clicheck import error_line


def involute_error(outline, pitch_radius, teeth, module, alpha, thickness, first_centre, band):
    """Normal distance (mm) of outline points in a radius band from the exact involute flanks.

    Teeth are centred at first_centre + k 2pi/teeth with arc thickness ``thickness`` at the
    pitch circle; the flank at radius rho sits at half-angle s/2r + inv(alpha) - inv(alpha_rho).
    """
    inv = lambda a: np.tan(a) - a
    rho = np.hypot(outline[:, 0], outline[:, 1])
    keep = (rho > band[0]) & (rho < band[1])
    rho, beta = rho[keep], np.arctan2(outline[keep, 1], outline[keep, 0])
    step = 2 * np.pi / teeth
    d = np.mod(beta - first_centre + step / 2, step) - step / 2
    a_rho = np.arccos(pitch_radius * np.cos(alpha) / rho)
    half = thickness / (2 * pitch_radius) + inv(alpha) - inv(a_rho)
    return np.abs(np.abs(d) - half) * rho * np.cos(a_rho), len(rho)


@pytest.mark.parametrize("backlash", [0.0, 0.5])
def test_constant_ratio_gives_involute_spur_gears(backlash):
    # b = 0: U = n = 2, circles r = L/3 = 48 (z 48, m 2) and r_H = 96 (z 96)
    law, L = CrankLaw(CrankMechanism(60.0, 0.0, 360.0), 2), 144.0
    alpha = np.radians(20.0)
    pair = generate_pair(law, 48, RackCutter(alpha, 1.0, 1.25, 0.25, backlash), center_distance=L)
    assert pair.module == pytest.approx(2.0, abs=1e-6) and pair.wheel_teeth == 96
    m, p = 2.0, 2.0 * np.pi
    # pinion: a tooth centred half a pitch after the period start (a space at theta = -90 deg)
    s_pinion = p / 2 - backlash / (2 * np.cos(alpha))
    err, n = involute_error(pair.pinion_outline, 48.0, 48, m, alpha, s_pinion,
                            -np.pi / 2 + np.pi / 48, (48 - 0.8 * m, 48 + 0.9 * m))
    assert n > 2000 and err.max() < 0.005, err.max()
    # wheel: carved by the pinion dilated by j_n/2 -> its teeth lose j_n/2 of thickness too
    s_wheel = p / 2 - backlash / (2 * np.cos(alpha))
    err, n = involute_error(pair.wheel_outline, 96.0, 96, m, alpha, s_wheel,
                            np.pi / 4, (96 - 0.8 * m, 96 + 0.9 * m))
    assert n > 4000 and err.max() < 0.005, err.max()


def test_reference_design_generates_valid_outlines_with_the_spec_pitch():
    law, L = CrankLaw(CrankMechanism(60, 100, 360), 2), 143.5
    curves = pitch_curves(law, L)
    assert curves.period_arc / 24 == pytest.approx(6.600, abs=5e-4)     # SPEC §9: 6.600 mm
    pair = generate_pair(law, 48, RackCutter(), center_distance=L)
    assert pair.module == pytest.approx(2.1008, abs=1e-4)
    for outline, name in ((pair.pinion_outline, "pinion"), (pair.wheel_outline, "wheel")):
        check_outline(outline, name)
    assert pair.min_curvature_radius > pair.undercut_limit
    assert pair.pinion_tip_land >= 0.1 and pair.wheel_tip_land >= 0.1


def test_undercut_is_refused_with_the_remedy():
    law, L = CrankLaw(CrankMechanism(60, 100, 360), 2), 144
    with pytest.raises(DesignError) as info:
        generate_pair(law, 48, RackCutter(pressure_angle=np.radians(10.0)), center_distance=L)
    text = str(info.value)
    assert "undercut" in text and "pressure angle >=" in text and "use pinion z >= " in text
    assert "module <=" not in text       # a module is no remedy: a given module scales the curves
    # following the remedy's pressure angle makes the same law generate, and so does its count
    needed = float(text.split("pressure angle >= ")[1].split(" deg")[0])     # rounded up: it clears
    generate_pair(law, 48, RackCutter(pressure_angle=np.radians(needed)), center_distance=L)
    teeth = int(text.split("use pinion z >= ")[1].split(" ")[0])
    generate_pair(law, teeth, RackCutter(pressure_angle=np.radians(10.0)), center_distance=L)


def test_undercut_on_a_small_spur_pinion():
    law, L = CrankLaw(CrankMechanism(60.0, 0.0, 360.0), 2), 144.0
    with pytest.raises(DesignError, match="undercut"):
        generate_pair(law, 12, RackCutter(), center_distance=L)       # z = 12 < 17 at 20 deg


def test_pointed_teeth_are_refused():
    law, L = CrankLaw(CrankMechanism(60, 100, 360), 2), 144
    with pytest.raises(DesignError, match="come to a point"):
        generate_pair(law, 48, RackCutter(pressure_angle=np.radians(30.0), addendum=1.25,
                                          dedendum=1.5, fillet=0.1), center_distance=L)


def test_pointed_teeth_remedy_follows_the_cause():
    """Teeth topped by more than max_topping x module to keep the tip land floor are those
    beside the pitch-curve corners (an ordinary tooth under the floor loses at most
    floor / (2 tan a)): the refusal names the topping and tells them to take more teeth, a
    smaller addendum or pressure angle. The default design tops two pinion teeth by 14 um,
    so a limit below that refuses it; the floor is 0.1 mm at module 2 and more, a fraction
    of a smaller module (a 0.15 mm module is a larger pair scaled down: not pointed)."""
    from dataclasses import replace

    from wheelstep_cli.gears.generation import GenerationSettings

    law = CrankLaw(CrankMechanism(60, 100, 360), 2)
    strict = replace(GenerationSettings(), max_topping=0.004)
    with pytest.raises(DesignError) as err:
        generate_pair(law, 48, RackCutter(backlash=0.24), center_distance=144, settings=strict)
    assert re.match(r"the pinion teeth come to a point \(a 0\.1 mm tip land needs 0\.01\d mm off the tip, "
                    r"more than 0\.004 x the module = 0\.008 mm\)", err.value.limit), err.value.limit
    assert err.value.limit.endswith("use a smaller addendum, a smaller pressure angle or more teeth (--z)")
    generate_pair(law, 48, RackCutter(backlash=0.24), center_distance=144)     # within 0.35 x module
    generate_pair(law, 48, RackCutter(backlash=0.02), center_distance=10)


def test_the_generators_lengths_follow_a_module_below_theirs():
    """Below GenerationSettings.length_module (2 mm) every length setting takes the module's
    proportion; at or above it they stay as given (the F'i and f'i bounds are micrometres)."""
    from wheelstep_cli.gears.generation import GenerationSettings

    given = GenerationSettings()
    assert given.at_module(2.0) == given and given.at_module(4.2) == given
    half = given.at_module(1.0)
    for name in GenerationSettings.LENGTHS:
        assert getattr(half, name) == pytest.approx(getattr(given, name) / 2.0, rel=1e-12), name
    assert half.tilt == given.tilt and half.poses_per_tooth == given.poses_per_tooth
    assert half.mount_tolerance == given.mount_tolerance        # the frame's, not the teeth's
    with pytest.raises(DesignError, match="length_module = 0: must be > 0 mm"):
        GenerationSettings(length_module=0)


def test_below_its_length_module_a_scaled_design_is_generated_as_the_scaled_pair():
    """A pair of module 1.05 mm and the same design at a quarter of the size (rolling at a
    quarter of the distance, a quarter of the backlash) have the same teeth: both outlines
    scaled by 1/4 (a quarter scales every float exactly), so the same transmission error and
    hub speed ripple however small the module."""
    law = CrankLaw(CrankMechanism(60, 100, 360), 2)
    base = generate_pair(law, 48, RackCutter(backlash=0.12), center_distance=72.0)
    quarter = generate_pair(law, 48, RackCutter(backlash=0.03), center_distance=18.0)
    assert base.module < 2.0 and quarter.module == pytest.approx(base.module / 4.0, rel=1e-12)
    for name in ("pinion_outline", "wheel_outline"):
        ours, theirs = getattr(base, name), 4.0 * getattr(quarter, name)
        assert ours.shape == theirs.shape, name
        np.testing.assert_allclose(theirs, ours, rtol=0, atol=1e-9 * base.module)


def test_cli_reports_undercut_and_pointed_in_one_line(cli, tmp_path):
    for args, words in ((["--pressure-angle", "10"], "undercut"),
                        (["--pressure-angle", "30", "--addendum", "1.25", "--dedendum", "1.5",
                          "--fillet", "0.1", "--backlash", "0.5"], "come to a point")):
        out = tmp_path / "x"
        result = cli("gears", *args, "--out", out)
        assert words in error_line(result), result.stderr
        assert not out.exists()


def basel_law(rows=721):
    """Bäsel (arXiv:1905.02642) §8, Fig. 8.3: driven angle psi = phi - (2 - sqrt 2) sin phi."""
    phi = np.linspace(0.0, 360.0, rows)
    psi = np.degrees(np.radians(phi) - (2 - np.sqrt(2)) * np.sin(np.radians(phi)))
    return law_from_samples(phi, psi)


def test_basel_example_reproduces_its_centre_distance():
    # published: z = 14, m = 2 -> a = 28.4385 (perimeter integral I(0, 2pi) = 3.09315)
    law = basel_law()
    unit = pitch_curves(law, 1.0, 65536).period_arc
    assert unit == pytest.approx(3.09315, abs=5e-5)
    assert center_distance_for_module(law, 14, 2.0) == pytest.approx(28.4385, abs=5e-4)


def test_law_csv_generates_a_smooth_published_style_case(cli, tmp_path):
    csv = tmp_path / "law.csv"
    phi = np.linspace(0.0, 360.0, 361)
    psi = np.degrees(np.radians(phi) - 0.3 * np.sin(np.radians(phi)))
    distance = center_distance_for_module(law_from_samples(phi, psi), 28, 1.5)   # z 28, m 1.5
    csv.write_text("driving_deg,driven_deg\n" + "\n".join(f"{a:.9f},{b:.9f}" for a, b in zip(phi, psi)))
    out = tmp_path / "out"
    result = cli("gears", "--law-csv", csv, "--z", "28", "--center-distance", f"{distance:.6f}",
                 "--install-distance", f"{distance:.6f}", "--bore", "4", "--format", "stl", "--out", out)
    assert result.exit_code == 0, result.stderr
    report = json.loads((out / "gears.json").read_text())
    assert report["generated"]["wheel_teeth"] == 28
    assert report["generated"]["pinion_teeth"] == 28
    # mesh-check takes the same law from the CSV and reproduces what gears measured
    check = cli("mesh-check", out / "pinion.stl", out / "wheel.stl", "--law-csv", csv,
                "--distance", f"{distance:.6f}", "--json")
    assert check.exit_code == 0, check.stderr
    summary, written = json.loads(check.stdout), report["meshing"]
    assert summary["law"]["csv"] == str(csv) and summary["law"]["driving_period_deg"] == pytest.approx(360.0)
    assert summary["interference"] is written["interference"] is False
    for key in ("backlash_min_mm", "backlash_max_mm", "pinion_teeth", "tooth_pitch_mm"):
        assert summary[key] == pytest.approx(written[key], rel=1e-6), key
    for side in ("drive", "coast"):
        for key in ("F_i_total_um", "f_i_tooth_um", "hub_speed_ripple_pct"):
            assert summary[side][key] == pytest.approx(written[side][key], rel=1e-6), (side, key)
    # a law CSV's gears drive no hub: both reports word their ripple as the output speed's
    text = cli("mesh-check", out / "pinion.stl", out / "wheel.stl", "--law-csv", csv,
               "--distance", f"{distance:.6f}").stdout
    assert "drive flank: F'i" in text and "output speed ripple" in text and "hub speed" not in text
    assert "output speed ripple" in result.stdout and "hub speed" not in result.stdout


@settings(max_examples=12, deadline=None)
@given(amp=st.floats(0.0, 0.25), shift=st.floats(-30.0, 30.0))
def test_law_from_samples_recovers_ratio_and_rolling_arcs(amp, shift):
    # phi(theta) = theta + amp sin(theta) over one turn: U = 1/(1 + amp cos theta)
    theta = np.linspace(shift, shift + 360.0, 181)
    phi = theta + np.degrees(amp * np.sin(np.radians(theta)))
    law = law_from_samples(theta, phi)
    t = np.radians(np.linspace(shift, shift + 360.0, 50))
    ph = law.carrier_angle(t)
    assert np.allclose(law.ratio(ph), 1.0 / (1.0 + amp * np.cos(t)), atol=1e-6)
    assert np.allclose(pinion_radius(law, ph, 100.0) + wheel_radius(law, ph, 100.0), 100.0)
    curves = pitch_curves(law, 100.0)
    wheel_arc = np.sum(np.hypot(*np.diff(curves.wheel, axis=0).T))
    assert wheel_arc == pytest.approx(curves.period_arc, rel=1e-6)   # they roll without slip


def test_default_pair_meshes_without_interference_within_its_backlash_band(cli, tmp_path):
    # the written pair, checked by the meshing check on its mid-thickness sections (SPEC §10)
    result = cli("gears", "--format", "stl", "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    report = json.loads((tmp_path / "gears.json").read_text())
    meshing, generated = report["meshing"], report["generated"]
    assert meshing["interference"] is False and not meshing["contact_lost"]
    # constant angular play worth j_n (the default, 0.239 mm) at the mean wheel pitch radius: the
    # normal backlash scales with the wheel pitch radius (79.8..102 mm over 92.6), plus 2 x 0.006 mm
    j = report["parameters"]["backlash"]
    assert j * 79.0 / 92.6 < meshing["backlash_min_mm"] and meshing["backlash_max_mm"] < j * 103.0 / 92.6 + 0.03
    # SPEC §10 figures, both flanks within the bounds of issue 13
    for side in ("drive", "coast"):
        assert meshing[side]["F_i_total_um"] <= 15.0 and meshing[side]["f_i_tooth_um"] <= 10.0
    assert meshing["drive"]["hub_speed_ripple_pct"] <= 1.0
    assert generated["module_mm"] == pytest.approx(2.1082, abs=1e-4)
    assert "hub speed ripple" in result.stdout


def test_blend_keeps_closure_and_is_not_refused_as_undercut():
    law, L = CrankLaw(CrankMechanism(60, 100, 360), 2), 144
    blended = blended_law(law, np.radians(1.0))
    assert blended.theta_period == pytest.approx(law.theta_period, abs=1e-12)   # closes exactly
    phi = np.linspace(-np.pi / 4, np.pi / 4, 2001)[:-1]
    assert np.mean(blended.ratio(phi)) == pytest.approx(np.mean(law.ratio(phi)), rel=1e-4)
    far = np.abs(phi) < np.radians(40.0)
    assert np.allclose(blended.ratio(phi[far]), law.ratio(phi[far]), rtol=1e-4)   # ~only near corners
    pair = generate_pair(blended, 48, RackCutter(), center_distance=L)       # the blended corner is cut like a pivot
    assert pair.corner == "space"


def test_round_tips_rounds_convex_corners_only():
    from wheelstep_cli.gears.generation import round_tips

    # an L-shaped plate: five convex corners and one concave corner
    ell = np.array([[0, 0], [10, 0], [10, 4], [4, 4], [4, 10], [0, 10]], dtype=float)
    r = 0.5
    rounded = round_tips(ell, r, 1e-4)
    area = 0.5 * np.sum(rounded[:, 0] * np.roll(rounded[:, 1], -1) - np.roll(rounded[:, 0], -1) * rounded[:, 1])
    # each convex corner loses (1 - pi/4) r^2; the arcs are chords of 8 per quarter turn
    # inscribed in the circle, so a little more
    lost = 5 * (1 - np.pi / 4) * r * r
    assert 64.0 - 1.05 * lost < area <= 64.0 - lost
    assert area > 0                                            # counter-clockwise
    # the concave corner stays sharp (to the chord error of the polygonal buffers)
    assert np.min(np.hypot(rounded[:, 0] - 4.0, rounded[:, 1] - 4.0)) < 0.01
    assert not np.any(np.all(np.isclose(rounded, [10.0, 0.0], atol=1e-3), axis=1))  # convex ones cut


def test_settings_are_values_changed_with_replace():
    from dataclasses import FrozenInstanceError, replace

    from wheelstep_cli.gears.generation import GenerationSettings

    base = GenerationSettings()
    changed = replace(base, tilt=0.3)
    assert changed.tilt == 0.3 and base.tilt == 0.6 and changed.pivot == base.pivot
    with pytest.raises(FrozenInstanceError):
        base.tilt = 0.1
    with pytest.raises(DesignError, match="backlash_mode"):
        GenerationSettings(backlash_mode="sideways")


def test_a_profiles_law_csv_is_read_beside_the_profile(cli, tmp_path, monkeypatch):
    # the profile names its CSV by a bare file name; the command runs from the folder above
    folder = tmp_path / "designs"
    folder.mkdir()
    phi = np.linspace(0.0, 360.0, 361)
    psi = np.degrees(np.radians(phi) - 0.3 * np.sin(np.radians(phi)))
    distance = center_distance_for_module(law_from_samples(phi, psi), 28, 1.5)
    (folder / "law.csv").write_text("driving_deg,driven_deg\n"
                                    + "\n".join(f"{a:.9f},{b:.9f}" for a, b in zip(phi, psi)))
    (folder / "smooth.yaml").write_text(
        f"gears:\n  law_csv: law.csv\n  z: 28\n  center_distance: {distance:.6f}\n"
        f"  install_distance: {distance:.6f}\n  bore: 4\n")
    monkeypatch.chdir(tmp_path)
    result = cli("gears", "--profile", "designs/smooth.yaml", "--format", "stl", "--out", "out")
    assert result.exit_code == 0, result.stderr
    report = json.loads((tmp_path / "out" / "gears.json").read_text())
    # named from the working folder, as the user would name it there (no folder above it)
    assert report["parameters"]["law_csv"] == "designs/law.csv"
    assert report["generated"]["pinion_teeth"] == 28
