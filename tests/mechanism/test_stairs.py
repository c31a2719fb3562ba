"""Stairs (SPEC §6): reference sizing, one cycle = one step up/down, sweep, design check."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st_

from wheelstep_cli.errors import DesignError
from wheelstep_cli.mechanism import stairs as st


def test_reference_sizing_spec6():
    d = st.size_for_stair(300.0, 150.0, 70.0, np.radians(-90.0))
    assert round(d.b) == 20 and round(d.y1) == 150 and round(d.a) == 40   # SPEC: 0.020, 0.150, 0.040 m
    assert d.a == pytest.approx(2 * d.b)


def _cycle_delta(design, start):
    """Hub displacement over phi in [start, start + pi/2], from the kinematics table."""
    kin = st.hub_kinematics(design, np.array([start, start + np.pi / 2]), start)
    return kin[1, 1] - kin[0, 1], kin[1, 4] - kin[0, 4], kin[0, 1]


@settings(max_examples=150, deadline=None)
@given(b=st_.floats(5, 150), y1=st_.floats(5, 400), sole=st_.floats(10, 250),
       landing=st_.floats(-170.0, -50.0))   # where a cycle rises (cos + sin < 0) and advances
def test_one_cycle_is_one_step_up_and_one_step_down(b, y1, sole, landing):
    """A random physical design and landing angle define a stair (SPEC's two cycle
    conditions, written out here); sizing for that stair must give the design back, and
    its kinematics table must advance one run and rise/drop one rise per quarter turn."""
    al = np.radians(landing)
    u = 2 * b + y1
    run = u * (np.cos(al) - np.sin(al)) - 2 * b * np.sin(2 * al) + sole * np.pi / 2
    rise = 2 * b * np.cos(2 * al) - u * (np.cos(al) + np.sin(al))
    assume(run > 1.0 and rise > 1.0 and abs(np.sin(3 * al) - np.cos(3 * al)) > 1e-3)
    d = st.size_for_stair(run, rise, sole, al)
    assert d.b == pytest.approx(b, rel=1e-6) and d.y1 == pytest.approx(y1, rel=1e-6)
    assert d.a == pytest.approx(2 * d.b)
    dx, dy, x0 = _cycle_delta(d, al)
    assert x0 == 0.0                                         # X01 measured from the landing
    assert dx == pytest.approx(run, rel=1e-9, abs=1e-6)
    assert dy == pytest.approx(rise, rel=1e-9, abs=1e-6)
    beta = st.descent_landing(al)
    assert beta == pytest.approx(-np.pi / 2 - al)
    dx, dy, _ = _cycle_delta(d, beta)
    assert dx == pytest.approx(run, rel=1e-9, abs=1e-6)
    assert dy == pytest.approx(-rise, rel=1e-9, abs=1e-6)
    # the next shoe takes over in the same pose one step on: the multi-step hub path has no jumps
    path = st.hub_path(d, al, run, rise, 3, per_cycle=50)
    ends, starts = path[49::50][:-1], path[50::50]
    assert np.allclose(ends, starts, atol=1e-6)


@settings(max_examples=60, deadline=None)
@given(run=st_.floats(150, 400), rise=st_.floats(80, 220), sole=st_.floats(20, 250),
       landing=st_.floats(-179.0, 179.0))
def test_meaningless_sizes_are_refused_not_returned(run, rise, sole, landing):
    al = np.radians(landing)
    b, y1, _ = st._sizing_raw(run, rise, sole, al)
    if st.singular_landing(al) or not (b > 0 and y1 > 0):
        with pytest.raises(DesignError):
            st.size_for_stair(run, rise, sole, al)
    else:
        d = st.size_for_stair(run, rise, sole, al)
        assert d.b == pytest.approx(b) and d.y1 == pytest.approx(y1)


def test_derivative_columns_match_numeric_derivatives():
    d = st.size_for_stair(300.0, 150.0, 70.0, np.radians(-90.0))
    phi = np.linspace(-1.5, 0.2, 9)
    eps = 1e-5
    k, kp, km = (st.hub_kinematics(d, phi + s, -np.pi / 2) for s in (0.0, eps, -eps))
    for val, der in ((1, 2), (2, 3), (4, 5), (5, 6)):
        assert np.allclose((kp[:, val] - km[:, val]) / (2 * eps), k[:, der], atol=1e-4)


def test_sweep_marks_singular_and_negative():
    rows = st.sizing_sweep(300.0, 150.0, np.radians([-105.0, -90.0, -60.0, -45.0]), [70.0])
    status = [r["status"] for r in rows]
    assert status == ["singular", "ok", "negative b", "singular"]
    assert rows[1]["b"] == pytest.approx(20.02, abs=0.01)
    assert all(r["b"] is None for r in rows if r["status"] != "ok")


def test_old_prototype_cannot_climb_but_sized_design_can():
    old = st.StairDesign(a=100.0, b=50.0, y1=130.0, y2=192.0)
    check = st.check_climb(old, 300.0, 150.0)
    assert not check.climbs
    for al, adv in zip(check.landing_for_rise, check.advance_at_rise):
        assert st.cycle_motion(old, al)[1] == pytest.approx(150.0, abs=1e-6)
        assert abs(adv - 300.0) > 100
    d = st.size_for_stair(300.0, 150.0, 70.0, np.radians(-90.0))
    good = st.check_climb(d, 300.0, 150.0)
    assert good.climbs and good.best_landing == pytest.approx(-np.pi / 2, abs=1e-4)
