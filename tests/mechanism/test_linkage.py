"""Walking linkages (SPEC §7): Chebyshev reference points, loop closure, branch continuity, errors."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st_

from wheelstep_cli.errors import DesignError
from wheelstep_cli.mechanism import linkage as lk


def test_chebyshev_lambda_reference_points():
    sol = lk.solve(lk.chebyshev_lambda(1.0), np.radians([90.0, 180.0, 270.0]))
    assert np.allclose(sol.joints["F"], [[4, 4], [2, 4], [0, 4]], atol=1e-12)


def _closure_errors(leg, sol):
    """Recompute every link length from the solved joints (independent of the solver's residual)."""
    errs = [0.0]
    for s in leg.steps:
        if isinstance(s, lk.Dyad):
            for c, r in ((s.p, s.rp), (s.q, s.rq)):
                errs.append(np.max(np.abs(np.linalg.norm(sol.joints[s.name] - sol.joints[c], axis=1) - r)))
        elif isinstance(s, lk.Attached):
            errs.append(np.max(np.abs(np.linalg.norm(sol.joints[s.name] - sol.joints[s.p], axis=1) - s.length)))
        elif isinstance(s, lk.Crank):
            errs.append(np.max(np.abs(np.linalg.norm(sol.joints[s.name] - sol.joints[s.center], axis=1) - s.length)))
    return max(errs)


@pytest.mark.parametrize("name", sorted(lk.PRESETS))
def test_presets_close_and_stay_on_their_branch(name):
    leg = lk.PRESETS[name]()
    coarse = lk.solve(leg, lk.cycle_angles(360))
    fine = lk.solve(leg, lk.cycle_angles(3600))
    assert coarse.residual < 1e-9 and fine.residual < 1e-9
    assert _closure_errors(leg, fine) < 1e-9
    for joint, path in fine.joints.items():
        # the same joint at the same crank angle whatever the sampling: no branch change
        assert np.allclose(coarse.joints[joint], path[::10], atol=1e-9)
        # continuity: successive positions 0.1 deg apart never jump
        steps = np.linalg.norm(np.diff(np.vstack([path, path[:1]]), axis=0), axis=1)
        size = np.ptp(np.vstack([p for p in fine.joints.values()]), axis=0).max()
        assert steps.max() < 0.01 * size
    # the rigid bent arm of the paper four-bar keeps its angle beta to the coupler
    if name == "four-bar":
        kl = fine.joints["L"] - fine.joints["K"]
        lh = fine.joints["H"] - fine.joints["L"]
        ang = np.degrees(np.arctan2(kl[:, 0] * lh[:, 1] - kl[:, 1] * lh[:, 0], (kl * lh).sum(axis=1)))
        assert np.allclose(np.abs(ang), 180 - 70.8)


@pytest.mark.parametrize("name", sorted(lk.PRESETS))
def test_joint_rates_match_finite_differences(name):
    leg = lk.PRESETS[name]()
    th = lk.cycle_angles(3600)
    sol = lk.solve(leg, th)
    h = th[1] - th[0]
    for joint, path in sol.joints.items():
        numeric = (np.roll(path, -1, axis=0) - np.roll(path, 1, axis=0)) / (2 * h)   # error ~ h^2/6
        scale = max(1.0, np.abs(sol.rates[joint]).max())
        assert np.abs(numeric - sol.rates[joint]).max() < 1e-4 * scale


def test_flipped_branch_is_the_mirror_across_the_centre_line():
    leg = lk.chebyshev_lambda(1.0)
    th = np.radians([100.0, 200.0, 300.0])
    a = lk.solve(leg, th).joints
    b = lk.solve(leg.with_branches({"C": -1}), th).joints
    d = np.array([2.0, 0.0]) - a["B"]
    u = d / np.linalg.norm(d, axis=1)[:, None]
    rel = a["C"] - a["B"]
    along = (rel * u).sum(axis=1)[:, None] * u
    mirrored = a["B"] + 2 * along - rel
    assert np.allclose(b["C"], mirrored, atol=1e-12)


@settings(max_examples=40, deadline=None)
@given(crank=st_.floats(0.5, 1.5), ground=st_.floats(3.0, 5.0), coupler=st_.floats(2.0, 6.0),
       rocker=st_.floats(2.0, 6.0), branch=st_.sampled_from([1, -1]))
def test_random_grashof_crank_rockers_close_everywhere(crank, ground, coupler, rocker, branch):
    longest = max(ground, coupler, rocker)
    others = ground + coupler + rocker - longest
    margin = others - (crank + longest)          # Grashof: crank shortest and s + l < p + q
    assume(abs(margin) > 0.05)
    if margin < 0:                                # the crank cannot turn fully: refused
        with pytest.raises(DesignError, match="cannot close"):
            _solve_four_bar(crank, ground, coupler, rocker, branch)
        return
    leg, sol = _solve_four_bar(crank, ground, coupler, rocker, branch)
    assert sol.residual < 1e-9 and _closure_errors(leg, sol) < 1e-9
    bd, bc = np.array([ground, 0.0]) - sol.joints["B"], sol.joints["C"] - sol.joints["B"]
    side = bd[:, 0] * bc[:, 1] - bd[:, 1] * bc[:, 0]
    assert np.all(np.sign(side) == branch)


def _solve_four_bar(crank, ground, coupler, rocker, branch):
    leg = lk.Linkage("t", "", (lk.Fixed("A", 0, 0), lk.Fixed("D", ground, 0), lk.Crank("B", "A", crank),
                               lk.Dyad("C", "B", coupler, "D", rocker, branch)), foot="C")
    return leg, lk.solve(leg, lk.cycle_angles(720))


def test_loop_that_cannot_close_names_the_crank_angle():
    leg = lk.Linkage("t", "", (lk.Fixed("A", 0, 0), lk.Fixed("D", 3, 0), lk.Crank("B", "A", 1),
                               lk.Dyad("C", "B", 1.5, "D", 1.0)), foot="C")
    with pytest.raises(DesignError) as err:
        lk.solve(leg, lk.cycle_angles(360))
    # |BD|^2 = 10 - 6 cos t exceeds (1.5 + 1)^2 once cos t < 0.625, t > 51.3 deg: first sample 52
    assert err.value.param == "crank-angle" and err.value.value == pytest.approx(52.0)
    assert "cannot close" in err.value.limit


def test_dead_point_where_branches_meet_is_reported():
    # parallelogram (crank 1, ground 2, coupler 2, rocker 1): at crank angle 0 the circles touch
    leg = lk.Linkage("t", "", (lk.Fixed("A", 0, 0), lk.Fixed("D", 2, 0), lk.Crank("B", "A", 1),
                               lk.Dyad("C", "B", 2.0, "D", 1.0)), foot="C")
    with pytest.raises(DesignError) as err:
        lk.solve(leg, lk.cycle_angles(360))
    assert err.value.value == 0.0 and "branches" in err.value.limit


def test_gait_of_chebyshev_lambda():
    leg = lk.chebyshev_lambda(1.0)
    sol = lk.solve(leg, lk.cycle_angles(720))
    g = lk.gait(leg, sol, rpm=60.0, ground_tol=0.01)
    deg = np.degrees(g.theta)
    assert g.ground_level == pytest.approx(4.0)
    assert g.support[(deg >= 90) & (deg <= 270)].all()       # the straight part stands
    assert g.duty_factor >= 0.5 and g.stride >= 4.0
    assert g.lift == pytest.approx(np.sqrt(24) - 4.0)         # top at crank 0: foot (2, 2 sqrt 6)
    assert np.allclose(g.velocity, sol.rates["F"] * 2 * np.pi, rtol=1e-12)   # 60 rpm = 2 pi rad/s
    # the foot moves backwards while it stands, so the body moves forward (+x)
    assert np.all(g.body_speed[g.support] > 0)
