"""Meshing check (SPEC §10) on outlines with known answers: involute spur gears, bars, paper pair."""

from dataclasses import replace

import numpy as np
import pytest
import shapely
from hypothesis import example, given, settings
from hypothesis import strategies as st

from tests.helpers.laws import FunctionLaw
from wheelstep_cli.gears.meshing import MeshingSettings, check_meshing


def involute_gear(teeth: int, module: float, thinning: float, space_at_zero: bool,
                  alpha: float = np.radians(20.0), flank_points: int = 60) -> np.ndarray:
    """Exact involute spur gear outline (CCW, mm), every tooth thinned by ``thinning`` mm
    of arc on the pitch circle. A tooth (or, with ``space_at_zero``, a space) is centred
    at angle 0. Root: radial lines from the base circle down to r_p - 1.25 m."""
    rp = module * teeth / 2.0
    rb = rp * np.cos(alpha)
    ra, rf = rp + module, rp - 1.25 * module
    inv = lambda r: np.tan(np.arccos(rb / r)) - np.arccos(rb / r)
    r = np.linspace(rb, ra, flank_points)
    half = (np.pi * module / 2.0 - thinning) / (2.0 * rp) + inv(rp) - inv(r)  # half tooth angle
    pitch = 2.0 * np.pi / teeth
    tooth_angle = np.concatenate([[-half[0]], -half, half[::-1], [half[0]]])
    tooth_radius = np.concatenate([[rf], r, r[::-1], [rf]])
    # tooth flank 1 goes root -> tip at angle -half(r), tip land, flank 2 tip -> root
    shift = pitch / 2.0 if space_at_zero else 0.0
    angles = (tooth_angle[None, :] + shift + pitch * np.arange(teeth)[:, None]).ravel()
    radii = np.tile(tooth_radius, teeth)
    order_ok = np.all(np.diff(angles) >= -1e-12)
    assert order_ok
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


def spur_transmission(z1: int, z2: int) -> FunctionLaw:
    return FunctionLaw(lambda t: np.asarray(t) * z1 / z2, 2.0 * np.pi / z1)


Z1, Z2, M, J = 24, 40, 2.0, 0.2   # teeth, module (mm), circular backlash on the pitch circle (mm)


@pytest.fixture(scope="module")
def spur_pair():
    # fine flanks: the check is exact for polygons, and coarse facets make real speed ripple
    # (30 points per flank: 1.5 %, 60: 0.5 %, 240: 0.08 % at 800 poses per tooth)
    pinion = involute_gear(Z1, M, J / 2.0, space_at_zero=False, flank_points=240)
    wheel = involute_gear(Z2, M, J / 2.0, space_at_zero=True, flank_points=240)
    return pinion, wheel


def test_involute_spur_pair_has_constant_te_zero_ripple_and_built_in_backlash(spur_pair):
    pinion, wheel = spur_pair
    a = M * (Z1 + Z2) / 2.0
    report = check_meshing(pinion, wheel, spur_transmission(Z1, Z2), a,
                           MeshingSettings(samples=100))
    r2 = M * Z2 / 2.0
    assert not report.interferes and not report.contact_lost
    # the wheel lags by half the backlash on the drive side, leads by half on the coast side
    assert np.allclose(report.transmission_error, -J / 2.0 / r2, rtol=0.01)
    assert np.allclose(report.backlash, J / r2, rtol=0.01)
    assert np.allclose(report.backlash_mm, J, rtol=0.01)   # pitch radius = r2 at a = standard
    assert report.te_peak_to_peak < 1e-3 * J / r2 * 10
    assert report.hub_speed_ripple < 5e-4
    summary = report.to_dict()
    assert summary["interference"] is False
    assert summary["backlash_min_mm"] == pytest.approx(J, rel=0.01)
    assert summary["pinion_teeth"] == Z1   # counted on the outline
    for side in ("drive", "coast"):
        assert summary[side]["hub_speed_ripple_pct"] < 0.05
        assert summary[side]["F_i_total_um"] < 1.0 and summary[side]["f_i_tooth_um"] < 1.0


def test_where_the_search_starts_within_the_play_changes_no_figure(spur_pair):
    """The band's cases start each pose in the middle of the play, which varies pose by pose:
    the contacts are where they are, so the transmission error (from the law) and the law's
    own hub speed are those of a search from the law's angle."""
    pinion, wheel = spur_pair
    law, a = spur_transmission(Z1, Z2), M * (Z1 + Z2) / 2.0
    settings = MeshingSettings(samples=100)
    plain = check_meshing(pinion, wheel, law, a, settings)
    half_play = 0.5 * J / (M * Z2 / 2.0)
    # up to 0.4 of the half play either way, varying with the pose
    moved = check_meshing(pinion, wheel, law, a, settings,
                          start_offset=lambda theta: 0.4 * half_play * np.sin(7.0 * theta))
    _reports_equal(plain, moved, atol=1e-9)
    np.testing.assert_allclose(moved.transmission_error, plain.transmission_error, atol=1e-9)
    np.testing.assert_allclose(moved.hub_speed_law, plain.hub_speed_law, rtol=1e-12)


def test_opening_the_centre_distance_adds_the_involute_backlash(spur_pair):
    pinion, wheel = spur_pair
    a = M * (Z1 + Z2) / 2.0
    da = 0.3
    report = check_meshing(pinion, wheel, spur_transmission(Z1, Z2), a + da,
                           MeshingSettings(samples=60))
    alpha, alpha_w = np.radians(20.0), np.arccos(a * np.cos(np.radians(20.0)) / (a + da))
    inv = lambda x: np.tan(x) - x
    # circular backlash on the operating pitch circles (standard involute geometry)
    r2w = (a + da) * Z2 / (Z1 + Z2)
    r1w = (a + da) * Z1 / (Z1 + Z2)
    s = np.pi * M / 2.0 - J / 2.0   # tooth thickness on the standard pitch circle, both gears
    s1w = 2.0 * r1w * (s / (M * Z1) + inv(alpha) - inv(alpha_w))
    s2w = 2.0 * r2w * (s / (M * Z2) + inv(alpha) - inv(alpha_w))
    space_minus_tooth = 2.0 * np.pi * r2w / Z2 - s1w - s2w
    assert np.allclose(report.backlash * r2w, space_minus_tooth, rtol=0.01)
    assert report.hub_speed_ripple < 1e-3


def test_pair_pushed_too_close_interferes(spur_pair):
    pinion, wheel = spur_pair
    a = M * (Z1 + Z2) / 2.0
    report = check_meshing(pinion, wheel, spur_transmission(Z1, Z2), a - 0.6,
                           MeshingSettings(samples=40))
    assert report.interference.all()
    assert report.overlap_area.max() > 0.01
    assert 0 < report.penetration.max() < 0.6   # mm; cannot exceed the 0.6 mm push
    assert np.nanmin(report.backlash) < 0
    assert report.to_dict()["interference"] is True


def test_without_the_overlap_area_the_rest_of_an_interfering_report_is_the_same(spur_pair):
    """The band's cases skip the overlap area: interference, depth and contacts stay as
    with it, and the report gives no area rather than a zero."""
    from dataclasses import replace

    pinion, wheel = spur_pair
    a = M * (Z1 + Z2) / 2.0 - 0.6
    law = spur_transmission(Z1, Z2)
    full = check_meshing(pinion, wheel, law, a, MeshingSettings(samples=40))
    bare = check_meshing(pinion, wheel, law, a, replace(MeshingSettings(samples=40), overlap_area=False))
    assert full.interference.all() and full.overlap_area.max() > 0.01
    assert np.array_equal(full.penetration, bare.penetration)
    assert np.array_equal(full.interference, bare.interference)
    np.testing.assert_array_equal(full.phi_drive, bare.phi_drive)
    assert np.isnan(bare.overlap_area).all() and bare.to_dict()["max_overlap_area_mm2"] is None


def test_without_contacts_where_jammed_only_the_jammed_poses_lose_their_contacts(spur_pair):
    """The band's cases search contacts only where the teeth clear: the poses that overlap
    get NaN rotations, every other pose, the interference and the depth stay bit for bit."""
    pinion, wheel = spur_pair
    # one pinion tooth 0.6 mm longer (past the 0.5 mm tip clearance): it jams where it meshes
    radius, angle = np.hypot(*pinion.T), np.arctan2(pinion[:, 1], pinion[:, 0])
    rp = M * Z1 / 2.0
    grow = (np.abs(angle) < np.pi / Z1) & (radius > rp)
    radius = radius + np.where(grow, 0.6 * (radius - rp) / M, 0.0)
    long_tooth = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    law, a = spur_transmission(Z1, Z2), M * (Z1 + Z2) / 2.0
    plain = MeshingSettings(samples=240, overlap_area=False)
    full = check_meshing(long_tooth, wheel, law, a, plain)
    bare = check_meshing(long_tooth, wheel, law, a, replace(plain, contacts_where_jammed=False))
    jammed = full.interference
    assert 0 < jammed.sum() < len(jammed)
    assert np.array_equal(bare.interference, jammed) and np.array_equal(bare.penetration, full.penetration)
    for name in ("phi_drive", "phi_coast"):
        assert np.isnan(getattr(bare, name)[jammed]).all()
        np.testing.assert_array_equal(getattr(bare, name)[~jammed], getattr(full, name)[~jammed])
    assert bare.to_dict()["backlash_min_mm"] > 0 > full.to_dict()["backlash_min_mm"]


def _bar_and_plates():
    """Wheel: a bar 2 mm wide from its axis to 22 mm out; pinion: plates above and below it."""
    bar = np.array([[0.0, -1.0], [22.0, -1.0], [22.0, 1.0], [0.0, 1.0]])
    plates = np.array([[-5.0, -30.0], [5.0, -30.0], [5.0, -2.0], [-5.0, -2.0]])
    return bar, plates


def test_bar_against_plate_matches_hand_computed_contact_angle():
    bar, plate = _bar_and_plates()
    D = 20.0
    # wheel rotated by pi puts the bar along -x from (20, 0) to (-2, 0), 1 mm either side.
    still = FunctionLaw(lambda t: np.zeros_like(np.asarray(t, dtype=float)), 1e-3)
    report = check_meshing(plate, bar, still, D, MeshingSettings(samples=1, window=40.0))
    # forwards (counter-clockwise about (20, 0)) the bar's far lower corner (-2, -1) swings
    # down onto the plate's top y = -2; the plate's corner (5, -2) reaches the bar's lower
    # edge later (0.0664 rad), so the corner decides.
    rho = np.hypot(22.0, 1.0)
    x_touch = np.sqrt(rho**2 - 4.0)
    expected = np.arctan2(2.0, x_touch) - np.arctan2(1.0, 22.0)
    assert report.phi_coast[0] == pytest.approx(expected, abs=1e-12)
    plate_corner = np.arctan2(2.0, 15.0) - np.arctan2(1.0, np.sqrt(15.0**2 + 2.0**2 - 1.0))
    assert expected < plate_corner
    # nothing above the bar: backwards it never meets the plate inside the window
    assert np.isnan(report.phi_drive[0])
    assert report.contact_lost and not report.interferes


def _first_touch(moving: shapely.Polygon, fixed: shapely.Polygon, centre, direction: float) -> float:
    """Independent reference: scan then bisect shapely ``intersects`` over the wheel rotation (rad).

    "Touches after turning by a" is true only on an interval [first, exit]: turned far
    enough, the tooth passes clean through a block (a 3 mm tooth at 25 mm from the axis
    clears a 6 mm block in about 0.5 rad). So the bracket is found by scanning in steps
    that move any point of the wheel by at most 0.1 mm (thinner than every part here),
    then bisected.
    """
    from shapely import affinity

    def touches(angle):
        turned = affinity.rotate(moving, direction * angle, origin=tuple(centre), use_radians=True)
        return turned.intersects(fixed)

    reach = np.hypot(*(np.asarray(moving.exterior.coords) - centre).T).max()  # mm
    step = 0.1 / reach
    lo = 0.0
    assert not touches(lo)
    while not touches(lo + step):
        lo += step
        assert lo < np.pi, "never touches"
    hi = lo + step
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if touches(mid) else (mid, hi)
    return hi


def _ccw(poly: shapely.Polygon) -> np.ndarray:
    return np.asarray(shapely.orient_polygons(poly).exterior.coords)[:-1]


@settings(max_examples=15, deadline=None)
@given(st.floats(0.2, 3.0), st.floats(-0.6, 0.6), st.floats(-0.3, 0.3), st.integers(5, 9))
@example(0.2, -0.14214059737073936, 0.2, 5)   # the tooth passes clean through a block by 0.5 rad
@example(0.2, 0.2, -0.17849989594809426, 5)
def test_contact_angles_match_shapely_bisection(gap, tilt, offset, sides):
    """A polygonal wheel 'tooth' on a bar between two pinion 'teeth' (blocks)."""
    D = 50.0
    t = np.linspace(0, 2 * np.pi, sides, endpoint=False) + tilt
    tooth = shapely.Polygon(np.column_stack([25.0 + 3.0 * np.cos(t), offset + 3.0 * np.sin(t)]))
    wheel = _ccw(shapely.union(tooth, shapely.box(0.0, -0.5, 24.0, 0.5)))
    # world: wheel axis at (50, 0), turned by pi: the tooth sits round (25, -offset)
    hi_y, lo_y = 3.0 + gap + 0.4, -3.0 - gap - 0.4
    pin_poly = shapely.union_all([shapely.box(14.0, hi_y, 30.0, hi_y + 6.0),
                                  shapely.box(14.0, lo_y - 6.0, 30.0, lo_y),
                                  shapely.box(14.0, lo_y - 6.0, 19.0, hi_y + 6.0)])
    pinion = _ccw(pin_poly)
    still = FunctionLaw(lambda x: np.zeros_like(np.asarray(x, dtype=float)), 1e-3)
    report = check_meshing(pinion, wheel, still, D, MeshingSettings(samples=1, window=60.0))
    world_wheel = shapely.affinity.translate(
        shapely.affinity.rotate(shapely.Polygon(wheel), np.pi, origin=(0, 0), use_radians=True), D, 0)
    assert not world_wheel.intersects(pin_poly)
    back = _first_touch(world_wheel, pin_poly, (D, 0.0), -1.0)
    fwd = _first_touch(world_wheel, pin_poly, (D, 0.0), 1.0)
    assert -report.phi_drive[0] == pytest.approx(back, abs=1e-9)
    assert report.phi_coast[0] == pytest.approx(fwd, abs=1e-9)


@pytest.fixture(scope="module")
def paper_pair():
    from wheelstep_cli.parts.gear_pair import GearPairSpec, build_gear_pair

    return build_gear_pair(GearPairSpec(teeth="paper"))


def test_paper_wheel_is_mirror_symmetric_so_it_fits_the_convention(paper_pair):
    # the paper draws the wheel's pitch point for phi at +phi; the check expects -phi.
    # Both are the same outline when the wheel is symmetric about its x axis.
    wheel = shapely.Polygon(paper_pair.wheel_outline)
    mirrored = shapely.Polygon(paper_pair.wheel_outline * [1.0, -1.0])
    assert shapely.symmetric_difference(wheel, mirrored).area < 1e-6 * wheel.area


def test_paper_pair_runs_and_reports_finite_figures(paper_pair):
    law = paper_pair.law
    transmission = law
    report = check_meshing(paper_pair.pinion_outline, paper_pair.wheel_outline, transmission,
                           144.0, MeshingSettings(samples=96))
    summary = report.to_dict()
    assert summary["samples"] == 96 and summary["period_deg"] == pytest.approx(180.0)
    assert not report.contact_lost
    # away from the handover corners (theta = +-90 deg) the sector teeth mesh with backlash
    middle = np.abs(report.theta - np.pi / 2.0) > np.radians(30.0)
    assert not report.interference[middle].any()
    assert np.all(report.backlash[middle] > 0)
    # the crank law keeps the hub speed constant: read from the law's own rate its ripple is
    # nil at any pose count (a difference over 96 poses read the pitch curves' corners as 2 %)
    assert summary["law_hub_speed_ripple_pct"] < 1e-3
    for key in ("backlash_min_mm", "diagnostic_pointwise_ripple_pct"):
        assert np.isfinite(summary[key])
    for side in ("drive", "coast"):
        assert all(np.isfinite(summary[side][key]) for key in
                   ("F_i_total_um", "f_i_tooth_um", "hub_speed_ripple_pct", "te_max_step_um"))


def _reports_equal(a, b, atol=0.0):
    for name in ("phi_drive", "phi_coast", "overlap_area", "penetration"):
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=0, atol=atol,
                                   equal_nan=True, err_msg=name)
    assert np.array_equal(a.interference, b.interference)


def _case(case, spur_pair, paper_pair):
    """Outlines and (transmission, centre distance) of the spur or the paper pair."""
    if case == "spur":
        return (*spur_pair, (spur_transmission(Z1, Z2), M * (Z1 + Z2) / 2.0))
    law = paper_pair.law
    transmission = FunctionLaw(law.carrier_angle, law.theta_period)
    return paper_pair.pinion_outline, paper_pair.wheel_outline, (transmission, 144.0)


@pytest.mark.parametrize("case", ["spur", "paper"])
def test_first_pass_within_reach_and_chunking_change_nothing(case, spur_pair, paper_pair):
    """The fast path (contacts within the reach first, far vertices and edges skipped, pairs
    in chunks) gives exactly what the plain search over all pairs gives, also where the
    teeth interfere (the paper pair) and the first pass must hand poses to the second."""
    pinion, wheel, args = _case(case, spur_pair, paper_pair)
    base = MeshingSettings(samples=48)
    fast = check_meshing(pinion, wheel, *args, base)
    plain = check_meshing(pinion, wheel, *args,
                          replace(base, reach=np.inf, max_pairs=997))   # many small chunks
    _reports_equal(fast, plain)
    if case == "paper":
        assert fast.interferes   # the second pass was needed


@pytest.mark.parametrize("case", ["spur", "paper"])
@pytest.mark.parametrize("margin", [0.3, 1.5])
def test_pilot_narrowed_reach_changes_nothing(case, margin, spur_pair, paper_pair, monkeypatch):
    """The first pass sized by a pilot's gaps gives bit for bit what it gives without the
    pilot, also when the margin is too small for most poses (they go to the second pass)."""
    from wheelstep_cli.gears.meshing.check import _pilot_reach, mesh_window
    from wheelstep_cli.gears.meshing.search import prepare

    import wheelstep_cli.gears.meshing.check as check

    pinion, wheel, args = _case(case, spur_pair, paper_pair)
    base = MeshingSettings(samples=48, pilot=8, pilot_margin=margin, peak_rounds=0)   # the pilot alone
    reaches = []
    searched = check.batch_contacts

    def spy(pair, theta, phi, settings):
        reaches.append(settings.reach)
        return searched(pair, theta, phi, settings)

    monkeypatch.setattr(check, "batch_contacts", spy)
    piloted = check_meshing(pinion, wheel, *args, base)
    monkeypatch.undo()
    plain = check_meshing(pinion, wheel, *args, replace(base, pilot=0))
    _reports_equal(piloted, plain)
    if case == "spur":   # the pilot did narrow the reach the poses were searched with
        law, distance = args
        theta = law.theta_period * np.arange(48) / 48
        pair = prepare(pinion, wheel, distance, mesh_window(pinion, wheel, distance, base), base)
        narrowed = _pilot_reach(pair, theta, law.carrier_angle(theta), base)
        assert base.reach / 16 <= narrowed < base.reach
        assert reaches[0] == base.reach and set(reaches[1:]) == {narrowed}


def test_pilot_reach_keeps_a_floor_for_teeth_with_no_play():
    """Teeth with next to no play (gaps of microradians) keep the first pass at a sixteenth of
    the reach, not at the gaps: its angle bins are twice the reach wide."""
    from wheelstep_cli.gears.meshing.check import _pilot_reach, mesh_window
    from wheelstep_cli.gears.meshing.search import prepare

    pinion = involute_gear(Z1, M, 1e-5, space_at_zero=False)
    wheel = involute_gear(Z2, M, 1e-5, space_at_zero=True)
    law, distance = spur_transmission(Z1, Z2), M * (Z1 + Z2) / 2.0
    base = MeshingSettings(samples=48, pilot=8)
    theta = law.theta_period * np.arange(48) / 48
    pair = prepare(pinion, wheel, distance, mesh_window(pinion, wheel, distance, base), base)
    assert _pilot_reach(pair, theta, law.carrier_angle(theta), base) == base.reach / 16


@pytest.mark.parametrize("case", ["spur", "paper"])
def test_threads_change_nothing(case, spur_pair, paper_pair):
    """Poses checked on several threads give bit for bit what one thread gives."""
    pinion, wheel, args = _case(case, spur_pair, paper_pair)
    base = MeshingSettings(samples=96, batch=7)          # many batches to share out
    single = check_meshing(pinion, wheel, *args, replace(base, threads=1))
    threaded = check_meshing(pinion, wheel, *args, replace(base, threads=3))
    _reports_equal(single, threaded)
    assert np.array_equal(single.hub_speed, threaded.hub_speed, equal_nan=True)


def test_large_outlines_bounded_memory_and_same_answer_as_coarse():
    """~20k-point outlines (like unsimplified exports) run in bounded memory and agree
    with a coarse sampling of the same involute pair and with the built-in backlash."""
    import tracemalloc

    fine = (involute_gear(Z1, M, J / 2.0, False, flank_points=416),
            involute_gear(Z2, M, J / 2.0, True, flank_points=250))
    coarse = (involute_gear(Z1, M, J / 2.0, False, flank_points=60),
              involute_gear(Z2, M, J / 2.0, True, flank_points=60))
    assert min(len(fine[0]), len(fine[1])) > 20000
    a = M * (Z1 + Z2) / 2.0
    tracemalloc.start()
    try:
        report = check_meshing(*fine, spur_transmission(Z1, Z2), a, MeshingSettings(samples=12))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 200e6   # bytes, numpy temporaries included
    rough = check_meshing(*coarse, spur_transmission(Z1, Z2), a, MeshingSettings(samples=12))
    r2 = M * Z2 / 2.0
    assert not report.interferes and not report.contact_lost
    assert np.allclose(report.transmission_error, -J / 2.0 / r2, rtol=2e-3)
    assert np.allclose(report.backlash, J / r2, rtol=2e-3)
    # facets of the coarse outline move contacts by about their sagitta (~1e-4 mm)
    assert np.allclose(report.phi_drive, rough.phi_drive, rtol=0, atol=1e-5)
    assert np.allclose(report.phi_coast, rough.phi_coast, rtol=0, atol=1e-5)


@settings(max_examples=10, deadline=None)
@given(st.floats(0.2, 3.0), st.floats(-0.6, 0.6), st.floats(-0.3, 0.3), st.integers(3, 9),
       st.floats(-0.2, 0.2))
def test_fast_path_equals_plain_search_on_coarse_polygons(gap, tilt, offset, sides, swing):
    """Coarse polygons with long edges (the ones the fast path never skips) over a few
    poses of a swinging wheel, near contact and far from it."""
    t = np.linspace(0, 2 * np.pi, sides, endpoint=False) + tilt
    tooth = shapely.Polygon(np.column_stack([25.0 + 3.0 * np.cos(t), offset + 3.0 * np.sin(t)]))
    wheel = _ccw(shapely.union(tooth, shapely.box(0.0, -0.5, 24.0, 0.5)))
    hi_y, lo_y = 3.0 + gap + 0.4, -3.0 - gap - 0.4
    pinion = _ccw(shapely.union_all([shapely.box(14.0, hi_y, 30.0, hi_y + 6.0),
                                     shapely.box(14.0, lo_y - 6.0, 30.0, lo_y),
                                     shapely.box(14.0, lo_y - 6.0, 19.0, hi_y + 6.0)]))
    swinging = FunctionLaw(lambda x: swing * np.sin(np.asarray(x, dtype=float)), 2.0 * np.pi)
    for window in (None, 60.0):
        base = MeshingSettings(samples=16, window=window)
        fast = check_meshing(pinion, wheel, swinging, 50.0, base)
        plain = check_meshing(pinion, wheel, swinging, 50.0, replace(base, reach=np.inf))
        _reports_equal(fast, plain)


def test_penetration_depth_near_search_equals_all_edges():
    """The depth's near search (grown edge boxes, radii in turn) gives bit for bit the
    distance to the nearest of all the pose's edges, for points on, near and far from the
    edges (the far ones beyond every radius take the plain path)."""
    from wheelstep_cli.gears.meshing.interference import DEPTH_RADII, _all_depth, depth
    from wheelstep_cli.gears.meshing.outlines import Window

    rng = np.random.default_rng(7)
    poses = 5
    ring = np.column_stack([np.cos(np.linspace(0, 2 * np.pi, 400)), np.sin(np.linspace(0, 2 * np.pi, 400))])
    e0, e1, e_pose = [], [], []
    for k in range(poses):
        pts = (20.0 + k) * ring + rng.normal(0.0, 0.02, ring.shape)
        e0.append(pts[:-1]), e1.append(pts[1:]), e_pose.append(np.full(len(pts) - 1, k))
    edges = Window(np.concatenate(e_pose), np.concatenate(e0), np.concatenate(e1),
                   np.zeros(0, dtype=int), np.zeros((0, 2)))
    pose = rng.integers(0, poses, 3000)
    radius = (20.0 + pose) * (1.0 + rng.choice([0.0, 1e-3, 0.01, 0.05, 0.2, 0.6], len(pose))
                              * rng.uniform(-1.0, 1.0, len(pose)))
    angle = rng.uniform(0.0, 2 * np.pi, len(pose))
    points = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    points[:5] = [0.0, 0.0]                     # farther than every radius from every edge
    order = np.argsort(pose, kind="stable")
    points, pose = points[order], pose[order]
    fast = depth(points, pose, edges, max_pairs=1 << 12)
    plain = _all_depth(points, pose, edges, max_pairs=1 << 12)
    assert np.array_equal(fast, plain)
    assert (plain > DEPTH_RADII[-1]).sum() >= 5 and (plain < DEPTH_RADII[0]).sum() > 1000


def test_overlap_area_of_body_cut_pieces_equals_the_whole_posed_outlines(paper_pair):
    """The overlap area measured on pieces cut from each outline in its own frame is the area
    of the whole posed outlines in the window (to rounding), where they overlap and not."""
    from wheelstep_cli.gears.meshing.check import mesh_window
    from wheelstep_cli.gears.meshing.interference import overlap_area, posed_overlap_area
    from wheelstep_cli.gears.meshing.outlines import rotate
    from wheelstep_cli.geometry.planar import prepared_polygon

    pinion, wheel = paper_pair.pinion_outline, paper_pair.wheel_outline
    distance = 143.5       # closer than installed: the paper teeth overlap at most poses
    box = mesh_window(pinion, wheel, distance)
    theta = np.linspace(0.0, paper_pair.law.theta_period, 40, endpoint=False)
    phi = np.asarray(paper_pair.law.carrier_angle(theta), dtype=float)
    centre = np.array([distance, 0.0])
    whole = overlap_area(rotate(pinion[None], -theta[:, None]),
                         rotate(wheel[None], np.pi + phi[:, None]) + centre, box)
    cut = posed_overlap_area((prepared_polygon(pinion), prepared_polygon(wheel)), (pinion, wheel),
                             theta, phi, centre, box)
    assert (whole > 1e-3).sum() >= 10
    np.testing.assert_allclose(cut, whole, rtol=1e-12, atol=1e-12)


def test_the_default_sampling_keeps_sixteen_poses_per_tooth_pitch():
    """SPEC §10 asks for at least 16 poses per tooth; a flat 1536 gave 12.8 per average tooth
    pitch to a 120-tooth pinion with n = 4 (a period is one pinion turn; with n = 2 half a
    turn). default_samples counts 16 per tooth pitch it is given, at least 1536; on a circle
    every tooth pitch is the average one."""
    from wheelstep_cli.gears.meshing.settings import POSES_PER_TOOTH, default_samples

    assert POSES_PER_TOOTH == 16
    assert default_samples(1) == default_samples(96) == 1536
    assert default_samples(120) == 1920 and default_samples(100) == 1600
    assert default_samples(97.5) == 1600      # 1560 poses, in whole batches of 64
    # a 100-tooth spur pinion over a whole turn: counted on its outline, sampled 16 per tooth
    teeth = 100
    pinion = involute_gear(teeth, 1.0, 0.05, space_at_zero=False, flank_points=12)
    wheel = involute_gear(teeth, 1.0, 0.05, space_at_zero=True, flank_points=12)
    law = FunctionLaw(lambda t: np.asarray(t), 2.0 * np.pi)
    report = check_meshing(pinion, wheel, law, float(teeth))
    assert report.teeth == teeth and len(report.theta) == 1600
    assert not report.interferes and not report.contact_lost
    given = check_meshing(pinion, wheel, law, float(teeth), MeshingSettings(samples=1024))
    assert len(given.theta) == 1024        # a count given is kept


@pytest.mark.parametrize("z, turns", [(48, 2), (240, 2), (64, 4), (120, 4)])
def test_the_default_sampling_gives_every_tooth_of_a_crank_law_pinion_sixteen_poses(z, turns):
    """The teeth are equal arcs of the pinion's pitch curve, so those where it runs fastest
    span the least pinion angle: 16 per average tooth pitch left such teeth 10.2 poses."""
    from wheelstep_cli.config.specs import GearPairSpec
    from wheelstep_cli.gears.meshing.check import default_pose_count
    from wheelstep_cli.gears.pitch_curves import pitch_curves

    law = GearPairSpec(z=z, turns=turns).law()
    samples = default_pose_count(law, z)
    curves = pitch_curves(law, 144.0, 65536)
    per_period = z * law.theta_period / (2.0 * np.pi)
    # tooth edges at equal arcs along the curve, read back as pinion angles over the period
    theta = np.unwrap(np.arctan2(curves.pinion[:, 1], curves.pinion[:, 0]))
    edges = np.interp(curves.period_arc * np.arange(round(per_period) + 1) / per_period,
                      curves.arc, np.abs(theta - theta[0]))
    poses_per_tooth = np.diff(edges) / law.theta_period * samples
    assert poses_per_tooth.min() >= 16.0
    assert samples == 1536 or poses_per_tooth.min() < 17.5    # not more than the least needs


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 64).flatmap(lambda bins: st.tuples(
    st.just(bins),
    st.lists(st.tuples(st.integers(0, bins - 1), st.integers(1, bins), st.floats(-1e3, 1e3)),
             min_size=1, max_size=30))))
def test_a_radial_bands_bins_see_every_range_that_holds_them(case):
    """The bands' folding of bin ranges (two power-of-two blocks a range) gives each bin the
    min and max of exactly the values whose ranges hold it, as visiting every bin would."""
    from wheelstep_cli.gears.meshing.outlines import _over_ranges

    bins, ranges = case
    first, count, values = (np.array(column) for column in zip(*ranges))
    for op, empty in ((np.minimum, np.inf), (np.maximum, -np.inf)):
        want = np.full(bins, empty)
        for f, c, v in ranges:
            for j in range(c):
                want[(f + j) % bins] = op(want[(f + j) % bins], v)
        assert np.array_equal(_over_ranges(op, values.astype(float), first, count, bins, empty), want)
