"""Foot trajectory from a line and three arcs (SPEC §8): SPEC formulas, continuity, clearance."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st_

from wheelstep_cli.errors import DesignError
from wheelstep_cli.mechanism import trajectory as tr


def _assert_smooth_closed(path, tol=1e-9):
    """Every piece starts where the previous ends, with the same direction; the loop turns once."""
    pieces = path.pieces
    for prev, nxt in zip(pieces, pieces[1:] + pieces[:1]):
        assert np.allclose(prev.point(1.0), nxt.point(0.0), atol=tol * max(1.0, path.r3))
        assert np.allclose(prev.tangent(1.0), nxt.tangent(0.0), atol=1e-9)
    # tangency conditions of SPEC §8, from the construction points
    assert np.linalg.norm(path.O3 - path.O1) == pytest.approx(path.r3 - path.r1, rel=1e-9)
    assert np.linalg.norm(path.O3 - path.O2) == pytest.approx(path.r3 - path.r2, rel=1e-9)
    assert np.allclose(path.O1, path.A + [0, path.r1]) and np.allclose(path.O2, path.D + [0, path.r2])
    assert sum(p.sweep for p in pieces[1:]) == pytest.approx(2 * np.pi)


def _sampled_top(path):
    pts, _ = tr.sample_path(path, spacing=0.05)
    gaps = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert gaps.max() < 0.051                                 # no jumps anywhere on the path
    return pts[:, 1].max() - path.y0


def test_spec_symmetric_formulas():
    H, r = 300.0, 30.0
    p = tr.foot_path(H, r, r, h_max=100.0)
    assert p.r3 == pytest.approx((100.0 + H**2 / (4 * (100.0 - 2 * r))) / 2)   # 2 r3 = h + H^2/(4(h - 2 r2))
    assert p.O3[0] == pytest.approx(H / 2)
    q = tr.foot_path(H, r, r, r3=400.0)
    assert q.h_max == pytest.approx(400.0 + r - np.sqrt((400.0 - r) ** 2 - H**2 / 4))
    assert tr.symmetric_clearance(H, r, tr.symmetric_top_radius(H, r, 100.0)) == pytest.approx(100.0)


@settings(max_examples=80, deadline=None)
@given(H=st_.floats(20, 600), r1=st_.floats(2, 80), r2=st_.floats(2, 80), extra=st_.floats(0.5, 300),
       y0=st_.floats(-200, 200), x0=st_.floats(-200, 200))
def test_clearance_mode_is_smooth_and_reaches_h_max(H, r1, r2, extra, y0, x0):
    h_max = 2 * max(r1, r2) + extra
    p = tr.foot_path(H, r1, r2, h_max=h_max, x0=x0, y0=y0)
    _assert_smooth_closed(p)
    assert p.h_max == pytest.approx(h_max, rel=1e-9)
    top = _sampled_top(p)
    assert h_max - 0.05**2 / p.r1 <= top <= h_max + 1e-9     # sampled chord can only dip below the top
    assert p.O1[0] < p.O3[0] < p.O2[0]


@settings(max_examples=80, deadline=None)
@given(H=st_.floats(20, 600), r1=st_.floats(2, 80), r2=st_.floats(2, 80), extra=st_.floats(0.1, 500),
       root=st_.sampled_from(["lower", "upper"]))
def test_radius_mode_is_smooth_and_reports_its_top(H, r1, r2, extra, root):
    dist = np.hypot(H, r2 - r1)
    r3 = (dist + r1 + r2) / 2 + extra
    try:
        p = tr.foot_path(H, r1, r2, r3=r3, root=root)
    except DesignError as err:          # only refused when the arcs would not form one convex loop
        assert "convex" in err.limit
        return
    _assert_smooth_closed(p)
    top = _sampled_top(p)
    assert top == pytest.approx(p.h_max, abs=0.05**2 / min(r1, r2) + 1e-9)
    if r1 == r2 and root == "lower":
        assert p.h_max == pytest.approx(tr.symmetric_clearance(H, r1, r3))
    # the same clearance asked for gives the same top arc back (when its centre lies between O1, O2)
    if p.O1[0] < p.O3[0] < p.O2[0]:
        back = tr.foot_path(H, r1, r2, h_max=p.h_max)
        assert back.r3 == pytest.approx(r3, rel=1e-7)


@pytest.mark.parametrize("kwargs, param", [
    (dict(h_max=59.0), "h-max"),                 # needs h_max > 2 r = 60
    (dict(r3=25.0), "r3"),                        # smaller than the corner arcs
    (dict(r3=150.0), "r3"),                       # cannot reach round both arcs
])
def test_impossible_tangency_is_refused(kwargs, param):
    with pytest.raises(DesignError) as err:
        tr.foot_path(300.0, 30.0, 30.0, **kwargs)
    assert err.value.param == param
